"""Legged robots standing on the ground: standing_scene."""

import warnings

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin

GO1_FEET = ["FL_foot", "FR_foot", "RL_foot", "RR_foot"]
G = 9.81


@pytest.fixture(scope="module")
def go1():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pinlin.InertiaWarning)  # its dummy base link, tested in test_inertia_bodies
        return pinlin.load_example("go1")


@pytest.fixture(scope="module")
def standing(go1):
    return pinlin.standing_scene(go1, GO1_FEET, stiffness=50.0, damping=1.0, friction=0.8)


def test_go1_stands_on_four_feet(go1, standing):
    assert standing.pose == "standing" and standing.feet == tuple(GO1_FEET)
    mass = sum(inertia.mass for inertia in go1.model.inertias)
    assert_allclose(standing.weight, G * mass, rtol=1e-15)
    # the lowest foot is on the ground plane z = 0, the springs rest at the SRDF pose
    data = go1.model.createData()
    pin.framesForwardKinematics(go1.model, data, standing.q0)
    heights = [data.oMf[go1.frame_id(f)].translation[2] for f in GO1_FEET]
    assert min(heights) == pytest.approx(0.0, abs=1e-15)
    assert_allclose(standing.q0[7:], go1.reference_configurations["standing"][7:], rtol=0)
    assert [c.frame for c in standing.scene.constraints] == GO1_FEET
    assert "go1" in repr(standing) and "128.516" in repr(standing)


def test_go1_standing_equilibrium_and_modes(standing):
    eq = pinlin.find_equilibrium(standing.scene, standing.q0)
    forces = np.array([f.force for f in eq.constraint_forces])
    # the contact normal forces carry the weight, the horizontal forces cancel
    assert_allclose(forces[:, 2].sum(), standing.weight, rtol=1e-10)
    assert_allclose(forces[:, :2].sum(axis=0), [0, 0], atol=1e-10 * standing.weight)
    assert all(c.normal_force > 0 and not c.pulls and not c.slips for c in eq.contacts)
    sys = pinlin.linearize(standing.scene, eq.q)
    assert sys.n == 18 - 12  # four point contacts take 12 of the 18 coordinates
    modes = pinlin.modal_analysis(sys)
    assert modes.stability.kind != "undecided"
    assert modes.stability.kind == "asymptotically_stable"  # springs, dampers, positive definite S
    assert np.all(modes.eigenvalues.real < 0)


def test_standing_needs_a_free_flyer_and_good_gains(go1):
    fixed = pinlin.load_example("ur5")
    with pytest.raises(pinlin.ParameterError, match="robot: 'ur5' has no free-flyer root joint"):
        pinlin.standing_scene(fixed, ["tool0"], stiffness=1.0)
    with pytest.raises(pinlin.ParameterError, match="stiffness: expected a finite number > 0, got 0.0"):
        pinlin.standing_scene(go1, GO1_FEET, stiffness=0.0)
    with pytest.raises(pinlin.ParameterError, match="damping: expected a finite number >= 0, got nan"):
        pinlin.standing_scene(go1, GO1_FEET, stiffness=1.0, damping=float("nan"))
    with pytest.raises(pinlin.ParameterError, match=r"stiffness: no value for joints \['FL_hip_joint'"):
        pinlin.standing_scene(go1, GO1_FEET, stiffness={"FR_hip_joint": 1.0})
    with pytest.raises(pinlin.ParameterError, match="feet: expected at least one contact frame"):
        pinlin.standing_scene(go1, [], stiffness=1.0)
    with pytest.raises(pinlin.FrameNotFoundError, match="unknown frame 'paw'"):
        pinlin.standing_scene(go1, ["paw"], stiffness=1.0)
    with pytest.raises(pinlin.ConfigurationError, match="q must be 19 finite numbers"):
        pinlin.standing_scene(go1, GO1_FEET, stiffness=1.0, q=np.zeros(3))
    with pytest.raises(pinlin.ParameterError, match="gravity: expected 3 finite numbers, not all zero"):
        pinlin.standing_scene(go1, GO1_FEET, stiffness=1.0, gravity=(0, 0, 0))


def test_a_given_pose_and_per_joint_gains(go1):
    q = go1.reference_configurations["standing"].copy()
    q[2] = 5.0  # in the air: the base is lowered onto the ground
    gains = {j: 30.0 for j in go1.joint_names[1:]}
    standing = pinlin.standing_scene(go1, GO1_FEET, stiffness=gains, q=q)
    assert standing.pose == "given"
    assert standing.q0[2] < 1.0
    assert all(float(e.stiffness) == 30.0 for e in standing.scene.elements)
