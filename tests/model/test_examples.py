"""Every robot of example-robot-data by name; every URDF it ships that is physically valid loads."""

import warnings
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.examples import EXCLUDED, robots_directory

ROOT = robots_directory()
URDFS = sorted(str(p.relative_to(ROOT)) for p in ROOT.glob("*/*/*.urdf"))

#: The 8 names of pinlin 0.2 and their entries then: kept unchanged.
OLD_EXAMPLES = {
    "double_pendulum": ("double_pendulum_description/urdf/double_pendulum.urdf", None, False),
    "double_pendulum_continuous": ("double_pendulum_description/urdf/double_pendulum_continuous.urdf", None, False),
    "ur3": ("ur_description/urdf/ur3_robot.urdf", None, False),
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "ur_description/srdf/ur5.srdf", False),
    "ur10": ("ur_description/urdf/ur10_robot.urdf", None, False),
    "panda": ("panda_description/urdf/panda.urdf", "panda_description/srdf/panda.srdf", False),
    "talos_reduced": ("talos_data/robots/talos_reduced.urdf", "talos_data/srdf/talos.srdf", True),
    "solo12": ("solo_description/robots/solo12.urdf", "solo_description/srdf/solo.srdf", True),
}

#: URDFs that do not load with the defaults of load_urdf, and why (example-robot-data 6.0.0).
REFUSED = {
    "icub_description/robots/icub.urdf": "is not positive semi-definite",  # point-mass legs: zero inertia
    "icub_description/robots/icub_reduced.urdf": "is not positive semi-definite",
    "romeo_description/urdf/romeo_small.urdf": "moved by joint .RShoulderYaw.",
    "romeo_description/urdf/romeo_laas_small.urdf": "link .LHipPitch_link. is not positive semi-definite",
    "hector_description/robots/quadrotor_base.urdf": "no movable joint",  # a flying body: free_flyer=True
    "iris_description/robots/iris_simple.urdf": "no movable joint",
    "ur_description/urdf/ur3.urdf": "has no <link>",  # an empty xacro output
}

#: URDFs that load with an InertiaWarning: a dummy link with an impossible tensor merged into a valid body.
WARNED = {
    "alex_description/urdf/alex_psyonic_hands.urdf",
    "allegro_hand_description/urdf/allegro_left_hand.urdf",
    "allegro_hand_description/urdf/allegro_right_hand.urdf",
    "anymal_b_simple_description/robots/anymal-kinova.urdf",
    "anymal_b_simple_description/robots/anymal.urdf",
    "anymal_c_simple_description/urdf/anymal.urdf",
    "b1_description/urdf/b1-z1.urdf",
    "b1_description/urdf/b1.urdf",
    "go1_description/urdf/go1.urdf",
    "hyq_description/robots/hyq_no_sensors.urdf",
    "pr2_description/urdf/pr2.urdf",
    "tiago_description/robots/tiago.urdf",
    "tiago_description/robots/tiago_dual.urdf",
    "tiago_description/robots/tiago_no_hand.urdf",
}


def test_every_shipped_urdf_is_accounted_for():
    assert len(URDFS) == 69
    assert set(REFUSED) | WARNED <= set(URDFS)


@pytest.mark.parametrize("relative", URDFS)
def test_every_valid_urdf_of_example_robot_data_loads(relative):
    path = ROOT / relative
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if relative in REFUSED:
            with pytest.raises(pinlin.UrdfError, match=REFUSED[relative]):
                pinlin.load_urdf(path)
            if REFUSED[relative] == "no movable joint":  # a flying body: its free flyer is all that moves
                assert pinlin.load_urdf(path, free_flyer=True).nv == 6
            return
        robot = pinlin.load_urdf(path)
    inertia_warnings = [w for w in caught if issubclass(w.category, pinlin.InertiaWarning)]
    assert bool(inertia_warnings) == (relative in WARNED), [str(w.message) for w in inertia_warnings]
    for w in inertia_warnings:
        assert "which is valid" in str(w.message) or "fixed to the world" in str(w.message)
    assert robot.nv > 0


def test_old_names_keep_their_models():
    for name, entry in OLD_EXAMPLES.items():
        assert pinlin.EXAMPLES[name] == entry


def test_examples_table():
    table = pinlin.examples()
    names = table.names()
    for name in ["go1", "a1", "anymal", "anymal_c", "talos", "talos_full_v2", "tiago", "tiago_dual", "pr2", "icub",
                 "romeo", "baxter", "kinova", "xarm", "z1", "so_arm", "bolt", "solo12", "ur5", "panda",
                 "double_pendulum", "hyq", "b1", "alex"]:
        assert name in names, name
    assert not any(row.file in EXCLUDED for row in table)
    rows = {row.name: row for row in table}
    go1 = rows["go1"]
    assert (go1.file, go1.nv, go1.free_flyer, go1.references, go1.inertia) == (
        "go1_description/urdf/go1.urdf", 18, True, ("standing",), "check")
    assert (rows["ur5"].nv, rows["ur5"].free_flyer) == (6, False)
    assert rows["talos"].file == rows["talos_reduced"].file == "talos_data/robots/talos_reduced.urdf"
    assert rows["icub"].inertia == "repair" and rows["romeo"].inertia == "check"
    assert "LHand" in rows["romeo"].massless
    assert rows["hector"].free_flyer and rows["hector"].nv == 6  # a quadrotor: only its free flyer moves
    assert not rows["talos_left_arm"].free_flyer  # an arm of a humanoid's package
    text = repr(table)
    assert text.startswith(f"{len(table)} example robots:") and "go1" in text and "free_flyer=True" in text


def test_unknown_example_lists_close_matches():
    with pytest.raises(pinlin.ExampleNotFoundError, match=r"unknown example 'anymall'; did you mean 'anymal'") as info:
        pinlin.load_example("anymall")
    assert isinstance(info.value, pinlin.ParameterError) and isinstance(info.value, pinlin.NameNotFoundError)
    assert "go1" in info.value.valid and info.value.close[0] == "anymal" and info.value.parameter == "name"
    with pytest.raises(pinlin.ParameterError, match=r"unknown example 'r2d2'; known examples: \[.*'ur5'"):
        pinlin.load_example("r2d2")


ROWS = pinlin.examples()
G = 9.81


def _reference(robot):
    for name in ("standing", "half_sitting"):
        if name in robot.reference_configurations:
            return robot.reference_configurations[name]
    return robot.neutral()


@pytest.mark.parametrize("row", ROWS, ids=[row.name for row in ROWS])
def test_every_example_loads_and_linearizes(row):
    """Loads by name (with inertia='repair' where the table says so, its massless joints locked) and
    linearizes at its SRDF reference pose or neutral, held by balancing forces; a free base is held too:
    the balancing force on its linear coordinates is the weight."""
    if row.inertia == "repair":
        with pytest.raises(pinlin.UrdfError, match="inertia='repair'"):
            pinlin.load_example(row.name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pinlin.InertiaWarning)  # each is checked in the test above
        robot = pinlin.load_example(row.name, inertia=row.inertia, locked=list(row.massless) or None)
    assert robot.nv == row.nv - len(row.massless)
    assert (robot.joint_names[0] == "root_joint") == row.free_flyer
    q = _reference(robot)
    sys = pinlin.linearize(pinlin.Scene(robot, [], gravity=(0, 0, -G)), q, balancing=True)
    assert sys.n == robot.nv and np.all(np.isfinite(sys.S))
    if row.free_flyer:
        weight = G * sum(inertia.mass for inertia in robot.model.inertias)
        assert_allclose(np.linalg.norm(sys.balancing[:3]), weight, rtol=1e-12)


def test_the_docs_table_lists_every_example():
    text = (Path(__file__).parents[2] / "docs" / "guide" / "model.md").read_text()
    missing = [row.name for row in ROWS if f"| `{row.name}` | `{row.file}` | {row.nv} |" not in text]
    assert not missing
