"""Loading URDFs and example robots; locked joints; the memory guard; bad input."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.memory import pinocchio_data_bytes

MESHY = """<robot name="meshy">
  <link name="base"><visual><geometry><mesh filename="package://nowhere/does_not_exist.stl"/></geometry></visual></link>
  <link name="arm">
    <inertial><mass value="2.0"/><origin xyz="0 0 -0.5"/><inertia ixx="0.1" iyy="0.1" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="/nonexistent/arm.dae"/></geometry></collision>
  </link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"""


def test_meshes_are_never_opened():
    robot = pinlin.load_urdf_string(MESHY)
    assert robot.joint_names == ("hinge",)
    assert robot.nv == 1


@pytest.mark.parametrize(
    "name, nq, nv",
    [("double_pendulum", 2, 2), ("ur5", 6, 6), ("panda", 9, 9), ("talos_reduced", 39, 38), ("solo12", 19, 18)],
)
def test_examples(name, nq, nv):
    robot = pinlin.load_example(name)
    assert (robot.nq, robot.nv) == (nq, nv)
    assert robot.source == f"example:{name}"


def test_example_reference_configurations_from_srdf():
    talos = pinlin.load_example("talos_reduced")
    assert "half_sitting" in talos.reference_configurations
    assert talos.reference_configurations["half_sitting"].shape == (talos.nq,)


def test_free_flyer_option():
    robot = pinlin.load_example("ur5", free_flyer=True)
    assert (robot.nq, robot.nv) == (13, 12)
    assert robot.joint("root_joint").kind == "JointModelFreeFlyer"
    fixed = pinlin.load_example("solo12", free_flyer=False)
    assert (fixed.nq, fixed.nv) == (12, 12)


def test_locked_joints_reduce_the_model():
    robot = pinlin.load_example("ur5", locked=["wrist_3_joint", "wrist_2_joint"])
    assert robot.nv == 4
    assert "wrist_2_joint" not in robot.joint_names


def test_locked_value_moves_the_remaining_bodies():
    """Locking joint2 of the double pendulum at 90 degrees makes a rigid L: the inertia about joint1 changes."""
    m1, l1, m2, l2 = 1.3, 0.7, 0.9, 0.5
    text = pinlin.double_pendulum_urdf(m1, l1, m2, l2)
    straight = pinlin.load_urdf_string(text, locked=["joint2"])
    bent = pinlin.load_urdf_string(text, locked={"joint2": np.pi / 2})
    scene = pinlin.Scene(bent, gravity=(0, 0, 0))
    sys = pinlin.linearize(scene, [0.0])
    # bar 2 horizontal from A: its centre at distance sqrt(l1^2 + (l2/2)^2) from O
    J = m1 * l1**2 / 3 + m2 * l2**2 / 12 + m2 * (l1**2 + (l2 / 2) ** 2)
    assert_allclose(sys.M, [[J]], rtol=1e-12)
    straight_sys = pinlin.linearize(pinlin.Scene(straight, gravity=(0, 0, 0)), [0.0])
    assert_allclose(straight_sys.M, [[m1 * l1**2 / 3 + m2 * l2**2 / 12 + m2 * (l1 + l2 / 2) ** 2]], rtol=1e-12)


def test_joint_and_frame_lookup():
    robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    j = robot.joint("joint2")
    assert (j.idx_q, j.nq, j.idx_v, j.nv) == (1, 1, 1, 1)
    assert robot.frame_id("tip") == robot.model.getFrameId("tip")
    with pytest.raises(pinlin.JointNotFoundError, match=r"unknown joint 'joint9'.*'joint1', 'joint2'") as info:
        robot.joint("joint9")
    assert info.value.valid == ("joint1", "joint2")
    with pytest.raises(pinlin.FrameNotFoundError, match=r"unknown frame 'toe'.*'tip'"):
        robot.frame_id("toe")


def test_missing_file(tmp_path):
    with pytest.raises(pinlin.UrdfError, match="URDF file not found"):
        pinlin.load_urdf(tmp_path / "nothing.urdf")


def test_malformed_xml(tmp_path):
    path = tmp_path / "bad.urdf"
    path.write_text("<robot name='x'><link name='a'></robot>")
    with pytest.raises(pinlin.UrdfError, match="malformed XML") as info:
        pinlin.load_urdf(path)
    assert info.value.source == str(path)
    with pytest.raises(pinlin.UrdfError, match="malformed XML"):
        pinlin.load_urdf_string("<robot")


def test_not_a_robot():
    with pytest.raises(pinlin.UrdfError, match="root element is <sdf>"):
        pinlin.load_urdf_string("<sdf version='1.6'/>")


def test_invalid_urdf_structure():
    text = "<robot name='x'><link name='a'/><joint name='j' type='revolute'><parent link='a'/><child link='nope'/></joint></robot>"
    with pytest.raises(pinlin.UrdfError, match="not a valid URDF model"):
        pinlin.load_urdf_string(text)


def test_no_movable_joint():
    text = "<robot name='x'><link name='a'/><link name='b'/><joint name='j' type='fixed'><parent link='a'/><child link='b'/></joint></robot>"
    with pytest.raises(pinlin.UrdfError, match="no movable joint"):
        pinlin.load_urdf_string(text)


def test_lock_every_joint():
    with pytest.raises(pinlin.UrdfError, match="leaves no movable joint"):
        pinlin.load_urdf_string(pinlin.double_pendulum_urdf(), locked=["joint1", "joint2"])


def test_lock_unknown_joint():
    with pytest.raises(pinlin.JointNotFoundError, match=r"unknown joint 'elbow'.*'joint1'"):
        pinlin.load_urdf_string(pinlin.double_pendulum_urdf(), locked=["elbow"])


def test_lock_bad_value():
    with pytest.raises(pinlin.ParameterError, match=r"locked\['joint2'\]"):
        pinlin.load_urdf_string(pinlin.double_pendulum_urdf(), locked={"joint2": [0.1, 0.2]})


def test_unknown_example():
    with pytest.raises(pinlin.ParameterError, match="unknown example 'r2d2'.*ur5"):
        pinlin.load_example("r2d2")


def test_memory_estimate_follows_spec():
    # Pinocchio keeps 32 nv^3 bytes (about 4 GB at nv = 500, theory: equations) and peaks near twice that
    assert 64 * 500**3 <= pinocchio_data_bytes(500) <= 80 * 500**3


def test_memory_guard_refuses_before_allocating():
    text = pinlin.pendulum_chain_urdf(60)
    with pytest.raises(pinlin.ModelTooLargeError, match="nv = 60 needs about") as info:
        pinlin.load_urdf_string(text, memory_limit=1_000_000)
    assert info.value.required > info.value.available
    assert isinstance(info.value, MemoryError)
    robot = pinlin.load_urdf_string(text)
    with pytest.raises(pinlin.ModelTooLargeError, match="lock joints"):
        pinlin.Scene(robot, memory_limit=1_000_000)


def test_memory_guard_default_limit_refuses_huge_chain():
    """nv = 1000: Pinocchio's data keeps 32 GB and peaks near 70 GB, more than a 24 GB machine allows (theory: equations)."""
    with pytest.raises(pinlin.ModelTooLargeError, match="nv = 1000"):
        pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1000), memory_limit=24 * 2**30 // 2)


def test_bundled_file_lookup():
    assert pinlin.data_path("scenes/double_pendulum.toml").is_file()
    with pytest.raises(pinlin.ParameterError, match="no bundled file 'urdf/nope.urdf'.*double_pendulum.urdf"):
        pinlin.data_path("urdf/nope.urdf")


def test_chain_generator_validation():
    with pytest.raises(pinlin.ParameterError, match="n: number of links"):
        pinlin.pendulum_chain_urdf(0)
    with pytest.raises(pinlin.ParameterError, match="length: expected a number or 3 values"):
        pinlin.pendulum_chain_urdf(3, length=[1.0, 2.0])
    with pytest.raises(pinlin.ParameterError, match="mass: must be positive"):
        pinlin.pendulum_chain_urdf(2, mass=[1.0, -1.0])
    with pytest.raises(pinlin.ParameterError, match="joint_type"):
        pinlin.pendulum_chain_urdf(2, joint_type="prismatic")
    with pytest.raises(pinlin.ParameterError, match="must be finite"):
        pinlin.pendulum_chain_urdf(2, length=np.nan)


def test_chain_per_link_properties():
    """Per-link lengths and masses: M of a 2-chain against the double-pendulum closed form."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, length=[0.7, 0.5], mass=[1.3, 0.9]))
    sys = pinlin.linearize(pinlin.Scene(robot), np.zeros(2))
    m1, l1, m2, l2 = 1.3, 0.7, 0.9, 0.5
    M_phi = np.array([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]])
    T = np.array([[1.0, 0.0], [1.0, 1.0]])
    assert_allclose(sys.M, T.T @ M_phi @ T, rtol=1e-12)


def test_unreadable_srdf_is_reported_not_dropped(monkeypatch, tmp_path):
    """A broken SRDF used to be swallowed (no reference configurations, no word): now a warning says so."""
    from pinlin.model import loading

    bad = tmp_path / "broken.srdf"
    bad.write_text("<robot name='ur5'><group_state name='home' group='arm'><joint name='nope' value='1 2'/>")
    original = loading._erd_file
    monkeypatch.setattr(loading, "_erd_file", lambda rel: bad if rel.endswith(".srdf") else original(rel))
    with pytest.warns(UserWarning, match="could not read the reference configurations"):
        robot = pinlin.load_example("ur5")
    assert robot.reference_configurations == {}


def test_missing_srdf_is_reported(monkeypatch, tmp_path):
    from pinlin.model import loading

    original = loading._erd_file
    monkeypatch.setattr(
        loading, "_erd_file", lambda rel: tmp_path / "none.srdf" if rel.endswith(".srdf") else original(rel)
    )
    with pytest.warns(UserWarning, match="SRDF .* is missing"):
        robot = pinlin.load_example("ur5")
    assert robot.reference_configurations == {}


def test_memory_guard_says_when_it_cannot_read_the_memory(monkeypatch):
    from pinlin.model import memory

    monkeypatch.setattr(memory, "available_memory", lambda: None)
    with pytest.warns(ResourceWarning, match="cannot be read"):
        pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2))
    pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2), memory_limit=10**9)  # an explicit budget: no warning
