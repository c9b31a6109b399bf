"""URDFs too deep for the parser or too large for memory are refused before parsing."""

import pinocchio as pin
import pytest

import pinlin
from pinlin.model import urdf_text
from pinlin.model.memory import pinocchio_data_bytes


def _no_parser(monkeypatch):
    calls = []

    def parser(*args, **kwargs):
        calls.append(args)
        raise AssertionError("Pinocchio's URDF parser was called")

    monkeypatch.setattr(pin, "buildModelFromXML", parser)
    monkeypatch.setattr(pin, "buildModelFromUrdf", parser)
    return calls


def test_a_4000_link_chain_is_refused_before_parsing(monkeypatch):
    """A 4000-link chain crashed the process inside the parser (stack overflow); now it is a refusal.

    The chain: base, link1 ... link4000, tip: 4002 links, 4001 below the root."""
    text = pinlin.pendulum_chain_urdf(4000)
    calls = _no_parser(monkeypatch)
    with pytest.raises(pinlin.ModelTooLargeError, match=r"the URDF's tree is 4001 links deep \(4002 links\).*at most 1000") as info:
        pinlin.load_urdf_string(text, memory_limit=10**30)  # even with an unlimited budget
    assert calls == []
    assert info.value.required == pinocchio_data_bytes(4000)


def test_a_100000_link_chain_is_refused_while_streaming(monkeypatch, tmp_path):
    path = tmp_path / "chain.urdf"
    path.write_text(pinlin.pendulum_chain_urdf(100_000))
    calls = _no_parser(monkeypatch)
    monkeypatch.setattr(urdf_text.ET, "fromstring", lambda text: pytest.fail("the whole tree was built"))
    with pytest.raises(pinlin.ModelTooLargeError, match=r"chain.urdf: the URDF has more than 10000 links"):
        pinlin.load_urdf(path)
    assert calls == []


def test_link_count():
    assert urdf_text.count_links(pinlin.pendulum_chain_urdf(3), "<string>") == 5  # base, 3 bars, tip
    assert urdf_text.count_links("<robot><link name='a'/><link", "<string>") == 1  # malformed: counted so far
    with pytest.raises(pinlin.ModelTooLargeError, match="more than 4 links"):
        urdf_text.count_links(pinlin.pendulum_chain_urdf(3), "<string>", limit=4)


def test_wide_models_are_refused_by_the_memory_estimate_before_parsing(monkeypatch, tmp_path):
    """600 one-link branches: shallow, but nv = 600 needs 72 * 600^3 bytes; the budget says no before parsing."""
    joints = "".join(
        f'<link name="l{i}"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>'
        f'</inertial></link><joint name="j{i}" type="revolute"><parent link="base"/><child link="l{i}"/>'
        f'<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        for i in range(600)
    )
    path = tmp_path / "wide.urdf"
    path.write_text(f'<robot name="wide"><link name="base"/>{joints}</robot>')
    calls = _no_parser(monkeypatch)
    with pytest.raises(pinlin.ModelTooLargeError, match=r"nv = 600 needs about"):
        pinlin.load_urdf(path, memory_limit=10**9)
    with pytest.raises(pinlin.ModelTooLargeError, match=r"nv = 606 needs about"):  # a free flyer adds 6
        pinlin.load_urdf(path, memory_limit=10**9, free_flyer=True)
    assert calls == []


def test_depth_limit_allows_deep_chains_within_it():
    assert urdf_text.MAX_URDF_DEPTH == 1000
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(200))
    assert robot.nv == 200


def test_depth_of_a_tree():
    # a -> b -> c, a -> d: depth 2 (links below the root)
    assert urdf_text._depth({"b": "a", "c": "b", "d": "a"}) == 2
    assert urdf_text._depth({"x": "y", "y": "x"}) == 2  # a loop (the parser refuses it later) ends the walk
