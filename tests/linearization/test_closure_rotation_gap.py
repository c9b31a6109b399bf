"""close_loops closes a frame constraint's rotation too, not only its position.

A FrameConstraint asks for the frame's placement: position and orientation.  Started from a configuration
where the position is already closed but the orientation is off by 0.036 rad, the closure must iterate (and
end with rotation_gap below tol), not report success at once.
"""

import numpy as np
import pinocchio as pin
from numpy.testing import assert_allclose

import pinlin
from helpers import BOX_URDF

ANGLE = 0.036  # [rad] about an oblique axis


def test_a_frame_constraint_closed_in_position_but_rotated_is_closed_in_rotation():
    robot = pinlin.load_urdf_string(BOX_URDF, free_flyer=True)
    target = pin.SE3(np.eye(3), np.array([0.4, -0.2, 0.7]))
    scene = pinlin.Scene(robot, constraints=[pinlin.FrameConstraint("box", target.homogeneous)])
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    quat = pin.Quaternion(pin.exp3(ANGLE * axis))
    q0 = np.concatenate([target.translation, quat.coeffs()])  # position closed, rotated by 0.036 rad
    result = pinlin.close_loops(scene, q0)
    assert result.initial_gap <= 1e-12
    assert_allclose(result.initial_rotation_gap, ANGLE, rtol=1e-9)
    assert result.rotation_gap <= 1e-10 and result.gap <= 1e-10
    assert result.iterations >= 1
    data = robot.model.createData()
    pin.framesForwardKinematics(robot.model, data, result.q)
    placement = data.oMf[robot.frame_id("box")]
    assert_allclose(placement.rotation, np.eye(3), atol=1e-10)
    assert_allclose(placement.translation, target.translation, atol=1e-10)
