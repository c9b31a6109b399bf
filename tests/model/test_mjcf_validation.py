"""The MJCF reader checks every attribute before Pinocchio reads it, and gives the same answer in every process."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from mjcf_bad_cases import CASES, MODEL, load
from numpy.testing import assert_allclose

import pinlin

HERE = Path(__file__).parent


@pytest.mark.parametrize("label, text, match", [c for c in CASES if c[2] is not None], ids=[c[0] for c in CASES if c[2]])
def test_bad_mjcf_attribute_is_named(tmp_path, label, text, match):
    with pytest.raises(pinlin.MjcfError, match=match) as info:
        load(text, tmp_path, 0)
    assert info.value.source.endswith("case0.xml")


def test_connect_between_sites_loads_with_the_sites_placements(tmp_path):
    robot = load(MODEL.format(equality='<connect name="loop" site1="sb" site2="sa"/>'), tmp_path, 0)
    (loop,) = robot.constraints
    assert (loop.frame, loop.target) == ("loop_1", "loop_2")
    model = robot.model
    f1, f2 = model.frames[robot.frame_id("loop_1")], model.frames[robot.frame_id("loop_2")]
    assert (model.names[f1.parentJoint], model.names[f2.parentJoint]) == ("j2", "j1")
    assert_allclose(f1.placement.translation, [0, 0, -1], atol=1e-15)  # site sb in body b
    assert_allclose(f2.placement.translation, [0, 0, -1], atol=1e-15)  # site sa in body a


def test_weld_to_the_world_with_a_relpose(tmp_path):
    robot = load(MODEL.format(equality='<weld name="w" body1="b" relpose="0 0 1 1 0 0 0"/>'), tmp_path, 0)
    (weld,) = robot.constraints
    assert isinstance(weld, pinlin.FrameConstraint) and np.all(np.isfinite(weld.target))


def test_inactive_entries_are_checked_too(tmp_path):
    with pytest.raises(pinlin.MjcfError, match=r"anchor='nan 0 0'"):
        load(MODEL.format(equality='<connect body1="b" anchor="nan 0 0" active="false"/>'), tmp_path, 0)


@pytest.mark.slow
def test_the_same_answer_in_20_fresh_processes(tmp_path):
    """Pinocchio read these files with uninitialized memory (8 of 12 runs accepted a missing site, one crashed):
    now every process refuses each the same way.  Four processes at a time (about 1.5 s each, mostly import)."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(Path(pinlin.__file__).parents[1]), str(HERE)])}
    outputs = set()
    for batch in range(5):
        runs = []
        for k in range(4):
            directory = tmp_path / f"run{batch}_{k}"
            directory.mkdir()
            runs.append(subprocess.Popen([sys.executable, str(HERE / "mjcf_bad_cases.py"), str(directory)],
                                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env))
        for run in runs:
            out, err = run.communicate(timeout=120)
            assert run.returncode == 0, err  # a crash (SIGSEGV) is a negative return code
            outputs.add(out)
    assert len(outputs) == 1
    lines = outputs.pop().splitlines()
    assert len(lines) == len(CASES)
    for (label, _, match), line in zip(CASES, lines):
        assert line.startswith(f"{label}: "), line
        assert ("MjcfError" in line) == (match is not None), line


def test_an_impossible_mjcf_body_is_repaired_on_request(tmp_path):
    """diaginertia 0.1 0.1 0.5 breaks I1 + I2 >= I3; the nearest valid moments are e + 0.1 (1, 1, -1)."""
    text = MODEL.format(equality="").replace('diaginertia="0.1 0.1 0.01"', 'diaginertia="0.1 0.1 0.5"', 1)
    path = tmp_path / "model.xml"
    path.write_text(text)
    with pytest.warns(pinlin.InertiaWarning, match=r"link 'a' \(the body moved by joint 'j1'\).*repaired"):
        robot = pinlin.load_mjcf(path, inertia="repair")
    assert_allclose(np.linalg.eigvalsh(robot.model.inertias[1].inertia), [0.2, 0.2, 0.4], atol=1e-12)
    with pytest.raises(pinlin.ParameterError, match="inertia: expected one of"):
        pinlin.load_mjcf(path, inertia="ignore")
