"""Fuzzed MJCF files through load_mjcf, a scene, the loop closure, linearization and modal analysis.

The bundled four-bar (``data/mjcf/four_bar.xml``) is mutated (:mod:`mjcf_mutants`).  In process, under
hypothesis: every stage gives a PinlinError or an honest result, and a loaded model holds only finite
numbers.  In subprocesses, so that a crash (Pinocchio 4.1's MJCF parser read unparsable numbers as
uninitialized memory and once segfaulted) is seen rather than killing the test run: a fixed-seed sample
of 40 mutants in one worker process in the "ci" profile, 10^4 mutants across workers in the "long"
profile (``pytest tests/fuzz --hypothesis-profile=long``).
"""

from __future__ import annotations

import os
import random
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from hypothesis import event, given, settings
from hypothesis import strategies as st
from mjcf_mutants import BASE, analyse, mutate, random_mutant

import pinlin

HERE = Path(__file__).parent
#: The "long" profile (max_examples 3000 or more) runs 10^4 mutants; "ci" its own 50.
LONG = settings.default.max_examples >= 1000
MUTANTS = 10_000 if LONG else 50


@st.composite
def mutated_mjcf(draw) -> str:
    return mutate(lambda options: draw(st.sampled_from(options)))


@settings(max_examples=MUTANTS)
@given(text=mutated_mjcf())
def test_fuzzed_mjcf_loads_and_analyses_or_says_why(text):
    with tempfile.TemporaryDirectory() as directory:
        path = Path(directory) / "mutant.xml"
        path.write_text(text)
        event(analyse(str(path)))


def test_the_unmutated_four_bar_is_analysed(tmp_path):
    path = tmp_path / "four_bar.xml"
    path.write_text(BASE)
    assert analyse(str(path)) == "analysed"


def _run_workers(paths: list[str], workers: int) -> list[str]:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(Path(pinlin.__file__).parents[1]), str(HERE)])}
    chunks = [paths[k::workers] for k in range(workers)]
    runs = [subprocess.Popen([sys.executable, str(HERE / "mjcf_mutants.py")], stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env) for _ in chunks]
    lines = []
    for run, chunk in zip(runs, chunks):
        out, err = run.communicate("\n".join(chunk) + "\n", timeout=60 + 5 * len(chunk))
        done = out.splitlines()
        crashed = chunk[len(done)] if len(done) < len(chunk) else None
        assert run.returncode == 0, f"the worker died (return code {run.returncode}) on {crashed}: {err[-2000:]}"
        lines += done
    return lines


def test_mutants_in_subprocesses(tmp_path):
    rng = random.Random(24)
    paths = []
    for k in range(MUTANTS if LONG else 40):
        path = tmp_path / f"mutant{k}.xml"
        path.write_text(random_mutant(rng))
        paths.append(str(path))
    lines = _run_workers(paths, workers=2)
    assert len(lines) == len(paths)
    bugs = [line for line in lines if "\tBUG " in line]
    assert not bugs, bugs[:3]
    verdicts = {line.split("\t")[1] for line in lines}
    assert "analysed" in verdicts and "refused by load_mjcf" in verdicts  # the sample reaches both ends


def test_found_by_the_fuzzer_a_one_dof_robot_with_a_point_constraint():
    """A four-bar mutant with two of its joints removed: one hinge, one connect (3 equations on 1 DOF).
    The same with a URDF: the constrained equilibrium raised IndexError; now OverconstrainedError, as linearize."""
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"), locked=["coupler_joint", "rocker_joint"])
    loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", 10.0)], constraints=[loop])
    with pytest.raises(pinlin.OverconstrainedError, match="no motion left"):
        pinlin.find_equilibrium(scene, scene.neutral())
