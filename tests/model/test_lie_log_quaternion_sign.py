"""A free-flyer joint spring sees a rotation, not a quaternion: q and -q give the same torque.

The unit quaternions q and -q are one rotation (SO(3) is covered twice by S^3).  The logarithm must take the
branch w >= 0 (or equivalently flip the sign of a quaternion with w < 0) so that the rotation vector has
angle <= pi; without it a quaternion with w < 0 maps to the rotation vector of angle 2 pi - theta about the
opposite axis, and a spring of stiffness k gives k (2 pi - theta) instead of k theta (Sola et al.,
"A micro Lie theory for state estimation in robotics", 2018, sec. 4).
"""

import numpy as np
from numpy.testing import assert_allclose

import pinlin
from helpers import BOX_URDF


def _torque(quaternion_xyzw, k=5.0):
    robot = pinlin.load_urdf_string(BOX_URDF, free_flyer=True)
    spring = pinlin.JointSpring("root_joint", k)
    scene = pinlin.Scene(robot, [spring], gravity=(0, 0, 0))
    q = np.concatenate([[0.0, 0.0, 0.0], quaternion_xyzw])  # at the rest position: a pure rotation
    ev = pinlin.model.evaluation.Evaluation(scene, q, np.zeros(robot.nv))
    return spring.generalized_force(ev)


def test_free_flyer_spring_is_the_same_at_q_and_minus_q():
    theta = 1.0  # [rad] about z: the torque is -k theta = -5 N m about z
    quat = np.array([0.0, 0.0, np.sin(theta / 2), np.cos(theta / 2)])  # (x, y, z, w), w > 0
    tau = _torque(quat)
    tau_minus = _torque(-quat)  # w < 0: the same rotation
    assert_allclose(tau[5], -5.0 * theta, rtol=1e-12)  # the documented k * log(R): 5 N m (not 5 (2 pi - 1))
    assert_allclose(tau_minus, tau, rtol=1e-12, atol=1e-12)
    assert_allclose(tau[:5], 0.0, atol=1e-12)  # a pure rotation about z: no force, no other torque
