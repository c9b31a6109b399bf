"""Analytic derivatives against central finite differences taken on the manifold.

K = dr/dq is differenced through ``pin.integrate`` (tangent space), C = dr/dv
directly, for models with every kind of element (theory: equations, elements).
"""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from helpers import fd_jacobians, rel_err
from pinlin.linearization.assembly import assemble

END_EFFECTORS = {"ur5": "tool0", "panda": "panda_hand", "talos_reduced": "gripper_left_joint"}


def loaded_scene(robot, frame, prescribed, rng, dead=True):
    elements = []
    for name in robot.joint_names:
        j = robot.joint(name)
        if j.nv == 1:
            elements.append(pinlin.JointSpring(name, rng.uniform(1, 10), rest=rng.uniform(-0.3, 0.3)))
        else:  # free-flyer: spring on SE(3) through pin.difference
            elements.append(pinlin.JointSpring(name, np.diag(rng.uniform(1, 10, j.nv))))
        elements.append(pinlin.JointDamper(name, rng.uniform(0.1, 1)))
    elements.append(pinlin.FollowerWrench(frame, force=5 * rng.normal(size=3), torque=rng.normal(size=3)))
    if dead:
        elements.append(pinlin.DeadWrench(frame, force=5 * rng.normal(size=3), torque=rng.normal(size=3)))
    elements.append(pinlin.RayleighDamping(0.1, 0.01))
    return pinlin.Scene(robot, elements, prescribed=prescribed)


def random_q(scene, rng):
    q = scene.neutral() + rng.uniform(-0.6, 0.6, scene.robot.nq)
    return scene.check_configuration(q)


@pytest.mark.parametrize("name", ["ur5", "panda", "talos_reduced"])
def test_example_robot_derivatives(name):
    rng = np.random.default_rng(7)
    robot = pinlin.load_example(name)
    first_revolute = next(n for n in robot.joint_names if robot.joint(n).nv == 1)
    scene = loaded_scene(robot, END_EFFECTORS[name], {first_revolute: 1.7}, rng)
    q = random_q(scene, rng)
    asm = assemble(scene, q, stiffness=True, damping=True, mass=True)
    K_fd, C_fd = fd_jacobians(scene, q)
    assert rel_err(asm.K, K_fd) < 1e-6
    assert rel_err(asm.C, C_fd) < 1e-6
    data = scene.model.createData()
    assert_allclose(asm.M, pin.crba(scene.model, data, q), rtol=1e-12, atol=1e-12)


def test_linearize_matches_fd_on_time_invariant_arm():
    """ur5 spun about its vertical base joint: a steady motion, checked end to end."""
    rng = np.random.default_rng(3)
    robot = pinlin.load_example("ur5")
    scene = loaded_scene(robot, "tool0", {"shoulder_pan_joint": 2.0}, rng, dead=False)
    q = random_q(scene, rng)
    sys = pinlin.linearize(scene, q, balancing=True)
    K_fd, C_fd = fd_jacobians(scene, q)
    f = scene.free_dofs
    assert rel_err(sys.K, K_fd[np.ix_(f, f)]) < 1e-6
    assert rel_err(sys.C, C_fd[np.ix_(f, f)]) < 1e-6
    assert not sys.is_zero("G")  # Coriolis coupling with the spinning base
    assert sys.calls[0] == "computeRNEADerivatives" and "crba" not in sys.calls


def test_continuous_joint_chain():
    """Continuous joints (nq = 2, nv = 1) with springs at non-zero rest angles."""
    rng = np.random.default_rng(11)
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(4, joint_type="continuous"))
    assert (robot.nq, robot.nv) == (8, 4)
    elements = [pinlin.JointSpring(f"joint{i}", 5.0, rest=rng.uniform(-1, 1)) for i in range(1, 5)]
    elements += [pinlin.JointDamper("joint2", 0.3), pinlin.DeadWrench("tip", force=(1.0, 0.0, -2.0))]
    scene = pinlin.Scene(robot, elements)
    q = pin.integrate(scene.model, scene.neutral(), rng.uniform(-1, 1, 4))
    asm = assemble(scene, q, stiffness=True, damping=True)
    K_fd, C_fd = fd_jacobians(scene, q)
    assert rel_err(asm.K, K_fd) < 1e-6
    assert rel_err(asm.C, C_fd) < 1e-6


def test_free_flyer_chain():
    rng = np.random.default_rng(5)
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3, radius=0.05), free_flyer=True)
    assert (robot.nq, robot.nv) == (10, 9)
    elements = [
        pinlin.JointSpring("root_joint", np.diag([50, 60, 70, 8, 9, 10.0])),
        pinlin.JointSpring("joint2", 4.0),
        pinlin.FollowerWrench("tip", force=(0.0, 1.0, 3.0), torque=(0.2, 0.0, 0.1)),
        pinlin.DeadWrench("link1", force=(0.5, -1.0, 0.0), torque=(0.0, 0.3, 0.0)),
    ]
    scene = pinlin.Scene(robot, elements)
    q = random_q(scene, rng)
    asm = assemble(scene, q, stiffness=True)
    K_fd, _ = fd_jacobians(scene, q)
    assert rel_err(asm.K, K_fd) < 1e-6


def test_dead_force_is_conservative_at_equilibrium():
    """A pure dead force has a symmetric stiffness: at equilibrium N = 0 exactly after rounding."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3))
    springs = [pinlin.JointSpring(f"joint{i}", 20.0) for i in range(1, 4)]
    scene = pinlin.Scene(robot, springs + [pinlin.DeadWrench("tip", force=(3.0, 0.0, 1.0))])
    eq = pinlin.find_equilibrium(scene)
    assert np.abs(eq.q).max() > 0.01  # the dead force deflects the chain
    sys = pinlin.linearize(scene, eq.q)
    assert sys.is_zero("N")
    K_fd, _ = fd_jacobians(scene, eq.q)
    assert rel_err(sys.K, K_fd) < 1e-6


def test_dead_force_stiffness_closed_form_single_pendulum():
    """Bar of length l with a horizontal dead force F at the tip and gravity off:
    V = -F l sin(theta)... at equilibrium theta = pi/2 (hanging along the force), k = F l."""
    l, F = 0.8, 2.5
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1, length=l))
    # joint angle theta about +y moves the tip to (-l sin(theta), 0, -l cos(theta))
    scene = pinlin.Scene(robot, [pinlin.DeadWrench("tip", force=(-F, 0.0, 0.0))], gravity=(0, 0, 0))
    eq = pinlin.find_equilibrium(scene, [1.0])
    assert_allclose(eq.q, [np.pi / 2], rtol=1e-12)
    sys = pinlin.linearize(scene, eq.q)
    assert_allclose(sys.S, [[F * l]], rtol=1e-12)
