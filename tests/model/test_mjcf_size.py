"""MJCF files too large or too deep for Pinocchio's parser: refused on the XML, before it reads them.

Before the check, 30000 nested bodies crashed the parser (a segfault), 700 reached 10.7 GB and
1100-5000 ended in a bare MemoryError.  Each case runs in a fresh process under a 3 GB address-space
limit and a 60 s timeout, as a user's would.
"""

import json
import re
import subprocess
import sys
import textwrap

import pytest

import pinlin
from pinlin.model.mjcf_checks import MAX_MJCF_BODIES, MAX_MJCF_DEPTH

BODY = ('<body name="b{i}"><joint name="j{i}" type="hinge" axis="0 1 0"/>'
        '<inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>')


def chain(n: int) -> str:
    """n bodies, each inside the previous one."""
    return ("<mujoco><worldbody>" + "".join(BODY.format(i=i) for i in range(n)) + "</body>" * n
            + "</worldbody></mujoco>")


def fan(n: int) -> str:
    """One body holding n - 1 bodies side by side (depth 2)."""
    children = "".join(BODY.format(i=i) + "</body>" for i in range(1, n))
    return f"<mujoco><worldbody>{BODY.format(i=0)}{children}</body></worldbody></mujoco>"


CHILD = textwrap.dedent("""
    import json, resource, sys, time
    resource.setrlimit(resource.RLIMIT_AS, (3 * 2**30, 3 * 2**30))
    import pinlin
    start = time.perf_counter()
    try:
        robot = pinlin.load_mjcf(sys.argv[1])
        answer = {"nv": robot.nv}
    except pinlin.PinlinError as exc:
        answer = {"error": type(exc).__name__, "message": str(exc)}
    answer["seconds"] = time.perf_counter() - start
    print(json.dumps(answer))
""")


def load_in_a_fresh_process(path) -> dict:
    done = subprocess.run([sys.executable, "-c", CHILD, str(path)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, (done.returncode, done.stderr[-2000:])  # no segfault, no bare MemoryError
    return json.loads(done.stdout.splitlines()[-1])


@pytest.mark.parametrize(
    ("n", "shape", "match"),
    [
        (30000, chain, r"elements nested more than 400 deep \(MAX_MJCF_DEPTH\)"),
        (5000, chain, "nested more than"),
        (1100, chain, "nested more than"),
        (700, chain, "nested more than"),
        (700, fan, r"700 bodies; pinlin accepts at most 300 \(MAX_MJCF_BODIES\)"),
        (301, chain, r"301 bodies; pinlin accepts at most 300"),
    ],
)
def test_too_many_bodies_are_refused_before_parsing(tmp_path, n, shape, match):
    path = tmp_path / "big.xml"
    path.write_text(shape(n))
    answer = load_in_a_fresh_process(path)
    assert answer["error"] == "ModelTooLargeError", answer
    assert answer["seconds"] < 5.0  # refused on the XML, before any large allocation
    assert re.search(match, answer["message"]), answer["message"]


def test_the_largest_accepted_model_loads_within_3_gb(tmp_path):
    path = tmp_path / "largest.xml"
    path.write_text(chain(MAX_MJCF_BODIES))
    assert load_in_a_fresh_process(path)["nv"] == MAX_MJCF_BODIES


def test_deep_elements_other_than_bodies_are_refused(tmp_path):
    path = tmp_path / "defaults.xml"
    depth = MAX_MJCF_DEPTH + 1
    path.write_text("<mujoco>" + '<default class="d">' * depth + "</default>" * depth
                    + "<worldbody>" + BODY.format(i=0) + "</body></worldbody></mujoco>")
    with pytest.raises(pinlin.ModelTooLargeError, match="nested more than 400 deep") as caught:
        pinlin.load_mjcf(path)
    assert caught.value.required > caught.value.available > 0
    assert isinstance(caught.value, MemoryError)
