"""Prescribed rotation: the turntable (Example 6.1; theory: turntable) and the rotating ring (Example 11.1; theory: rotating ring).

Turntable, coordinates (theta, r):  M = diag(m r0^2, m),  G = 2 m W r0 [[0, 1], [-1, 0]],
S = diag(m W^2 a r0, k - m W^2),  D = N = 0,  r0 = (k l0 + m W^2 a) / (k - m W^2).
Ring, Cartesian coordinates in the ring frame:  M = m I, D = c I, G = 2 m W [[0, -1], [1, 0]],
S = (k - m W^2) I, N = 0.
"""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin

A, MASS, K, L0 = 0.5, 1.3, 10.0, 0.3


def turntable(omega, **kw):
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(A, MASS))
    return pinlin.Scene(robot, [pinlin.JointSpring("slider", K, rest=L0)], prescribed={"table": omega}, **kw)


def r0(omega):
    return (K * L0 + MASS * omega**2 * A) / (K - MASS * omega**2)


def start(scene, theta, r, table_angle=0.0):
    q = scene.neutral()
    q[0:2] = np.cos(table_angle), np.sin(table_angle)
    q[2], q[3] = theta, r
    return q


@pytest.mark.parametrize("omega", [0.5, 1.5, 2.5])
def test_turntable_matrices_and_equilibrium(omega):
    scene = turntable(omega)
    rr = r0(omega)
    eq = pinlin.find_equilibrium(scene, start(scene, 0.0, 1.3 * rr))  # 30% off
    assert_allclose(eq.q[3], rr, rtol=1e-12)
    assert eq.iterations >= 1
    sys = pinlin.linearize(scene, eq.q)
    assert sys.dof_names == ("arm", "slider")
    m = MASS
    assert_allclose(sys.M, np.diag([m * rr**2, m]), rtol=1e-12)
    assert_allclose(sys.G, 2 * m * omega * rr * np.array([[0, 1], [-1, 0]]), rtol=1e-12)
    assert_allclose(sys.S, np.diag([m * omega**2 * A * rr, K - m * omega**2]), rtol=1e-12, atol=1e-12)
    assert sys.is_zero("D") and sys.is_zero("N")


def test_turntable_unstable_equilibrium_at_pi():
    omega = 1.5
    scene = turntable(omega)
    r_pi = (K * L0 - MASS * omega**2 * A) / (K - MASS * omega**2)
    eq = pinlin.find_equilibrium(scene, start(scene, np.pi - 0.15, 1.2 * r_pi))
    assert_allclose(eq.q[2], np.pi, rtol=1e-12)
    assert_allclose(eq.q[3], r_pi, rtol=1e-10)
    sys = pinlin.linearize(scene, eq.q)
    assert sys.S[0, 0] < 0  # theta = pi is unstable: negative stiffness m W^2 a r (with r -> -a side)
    assert_allclose(sys.S[0, 0], -MASS * omega**2 * A * r_pi, rtol=1e-10)


def test_turntable_independent_of_table_angle():
    omega = 1.5
    scene = turntable(omega)
    rr = r0(omega)
    systems = [pinlin.linearize(scene, start(scene, 0.0, rr, angle)) for angle in (0.0, 0.7, 2.9)]
    for other in systems[1:]:
        for name in ("M", "G", "S"):
            assert_allclose(getattr(other, name), getattr(systems[0], name), rtol=1e-13, atol=1e-13)


def test_tilted_turntable_is_time_periodic():
    """Gravity in the table's plane makes the equations depend on the table angle."""
    scene = turntable(1.5, gravity=(9.81, 0.0, 0.0))
    with pytest.raises(pinlin.TimePeriodicError, match="time-periodic") as info:
        pinlin.linearize(scene, start(scene, 0.0, r0(1.5)), balancing=True)
    assert info.value.joint == "table"


def ring(omega, c):
    robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf(MASS))
    elements = [pinlin.JointSpring("x", K), pinlin.JointSpring("y", K)]
    if c:
        elements += [pinlin.JointDamper("x", c), pinlin.JointDamper("y", c)]
    return pinlin.Scene(robot, elements, prescribed={"ring": omega})


@pytest.mark.parametrize("omega, c", [(1.0, 0.0), (2.0, 0.3), (5.0, 0.3), (1e3, 0.0)])
def test_rotating_ring_matrices(omega, c):
    scene = ring(omega, c)
    sys = pinlin.linearize(scene, scene.neutral())
    m = MASS
    assert_allclose(sys.M, m * np.eye(2), rtol=1e-14)
    assert_allclose(sys.D, c * np.eye(2), rtol=1e-14, atol=0)
    assert_allclose(sys.G, 2 * m * omega * np.array([[0, -1], [1, 0]]), rtol=1e-13)
    assert_allclose(sys.S, (K - m * omega**2) * np.eye(2), rtol=1e-12)
    assert sys.is_zero("N")
    assert sys.is_zero("D") == (c == 0)


def test_rotating_ring_independent_of_ring_angle():
    scene = ring(2.0, 0.3)
    q = pin.integrate(scene.model, scene.neutral(), np.array([1.234, 0.0, 0.0]))
    assert_allclose(pinlin.linearize(scene, q).G, pinlin.linearize(scene, scene.neutral()).G, rtol=1e-13)
