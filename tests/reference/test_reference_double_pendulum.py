"""The paper's double pendulum with follower load (Example 6.2; theory: double pendulum), hand-derived.

Absolute angles phi from the downward vertical, relative URDF angles theta with
phi = T theta, T = [[1, 0], [1, 1]].  Closed forms:

    M_phi = [[(m1/3 + m2) l1^2, m2 l1 l2/2], [m2 l1 l2/2, m2 l2^2/3]]
    S_phi = [[k1 + k2 + (m1/2 + m2) g l1 - P l1, -k2 + P l1/2], [-k2 + P l1/2, k2 + m2 g l2/2]]
    N_phi = (P l1/2) [[0, 1], [-1, 0]],  D = G = 0,  f_phi = [0, c]

and in URDF coordinates X_theta = T^T X_phi T.
"""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin

T = np.array([[1.0, 0.0], [1.0, 1.0]])


def closed_form(m1, l1, m2, l2, k1, k2, P, g):
    M = np.array([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]])
    S = np.array(
        [[k1 + k2 + (m1 / 2 + m2) * g * l1 - P * l1, -k2 + P * l1 / 2], [-k2 + P * l1 / 2, k2 + m2 * g * l2 / 2]]
    )
    N = P * l1 / 2 * np.array([[0.0, 1.0], [-1.0, 0.0]])
    return T.T @ M @ T, T.T @ S @ T, T.T @ N @ T


def scene_for(m1, l1, m2, l2, k1, k2, P, g):
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf(m1, l1, m2, l2))
    elements = [pinlin.JointSpring("joint1", k1), pinlin.JointSpring("joint2", k2)]
    if P:
        elements.append(pinlin.FollowerWrench("tip", force=(0, 0, P)))
    return pinlin.Scene(robot, elements, gravity=(0, 0, -g))


PARAMETERS = [
    # m1, l1, m2, l2, k1, k2, P, g
    (1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 4.0, 9.81),  # theory: double pendulum check values
    (1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 0.0, 9.81),  # no load
    (1.3, 0.7, 0.9, 0.5, 3.0, 2.0, -6.0, 9.81),  # tensile load
    (2.0, 1.5, 0.4, 0.3, 0.0, 0.0, 25.0, 9.81),  # no springs, strong compression
    (1.0, 1.0, 1.0, 1.0, 10.0, 5.0, 3.0, 0.0),  # zero gravity
]


@pytest.mark.parametrize("params", PARAMETERS)
def test_matrices_equal_closed_form(params):
    M, S, N = closed_form(*params)
    sys = pinlin.linearize(scene_for(*params), np.zeros(2))
    assert_allclose(sys.M, M, rtol=1e-12, atol=1e-14 * np.abs(M).max())
    assert_allclose(sys.S, S, rtol=1e-12, atol=1e-13 * np.abs(S).max())
    assert_allclose(sys.N, N, rtol=1e-12, atol=1e-13 * np.abs(S).max())
    assert not np.any(sys.D) and not np.any(sys.G)
    assert sys.dof_names == ("joint1", "joint2")


def test_spec_check_values():
    sys = pinlin.linearize(scene_for(1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 4.0, 9.81), np.zeros(2))
    assert_allclose(sys.M, [[1.04333, 0.2325], [0.2325, 0.075]], rtol=1e-5)
    assert_allclose(sys.S, [[15.8511, 3.60725], [3.60725, 4.20725]], rtol=1e-5)
    assert_allclose(sys.N, [[0, 1.4], [-1.4, 0]], rtol=1e-12)
    assert sys.nonzero == ("M", "S", "N")


def test_no_load_has_exactly_zero_circulatory_matrix():
    sys = pinlin.linearize(scene_for(1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 0.0, 9.81), np.zeros(2))
    assert sys.is_zero("N")
    assert sys.nonzero == ("M", "S")


@pytest.mark.parametrize("theta", [(0.3, -0.5), (1.2, 2.0), (-2.5, 0.7)])
def test_follower_generalized_force_closed_form(theta):
    """Q1 = -P l1 sin(phi2 - phi1), Q2 = 0 in absolute angles; Q_theta = T^T Q_phi = [Q1, 0]."""
    P, l1 = 4.0, 0.7
    scene = scene_for(1.3, l1, 0.9, 0.5, 3.0, 2.0, P, 9.81)
    load = pinlin.FollowerWrench("tip", force=(0, 0, P))
    Q = pinlin.generalized_force(scene, np.array(theta), load)
    assert_allclose(Q, [-P * l1 * np.sin(theta[1]), 0.0], rtol=1e-12, atol=1e-14)


def test_follower_couple_generalized_force():
    """A follower couple c on bar 2 about the joint axis: f_phi = [0, c], f_theta = T^T f_phi = [c, c]."""
    c = 1.7
    scene = scene_for(1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 4.0, 9.81)
    couple = pinlin.FollowerWrench("link2", torque=(0, c, 0))
    for q in (np.zeros(2), np.array([0.4, -1.1])):  # body-fixed axis y stays the joint axis
        assert_allclose(pinlin.generalized_force(scene, q, couple), T.T @ [0.0, c], rtol=1e-14)


def test_bundled_urdf_is_the_generator_output():
    assert pinlin.data_path("urdf/double_pendulum.urdf").read_text() == pinlin.double_pendulum_urdf()
    assert pinlin.data_path("urdf/turntable.urdf").read_text() == pinlin.turntable_urdf()
    assert pinlin.data_path("urdf/rotating_ring.urdf").read_text() == pinlin.rotating_ring_urdf()
    assert pinlin.data_path("urdf/pendulum_chain_10.urdf").read_text() == pinlin.pendulum_chain_urdf(10)


def test_load_urdf_from_repository_path():
    robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    assert robot.joint_names == ("joint1", "joint2")
    assert "tip" in robot.frame_names
