"""Orbits of a conservative family keep the user's start, against closed forms.

- The pendulum's free swing of amplitude theta0 (point mass m at distance l, omega0^2 = g / l):
  T = 4 K(k^2) / omega0 with k = sin(theta0 / 2) (``scipy.special.ellipk`` takes the parameter m = k^2);
  its energy E = -m g l cos(theta0) (Pinocchio's potential, zero at the world origin), so with
  dK/dm = (E(m) - (1 - m) K(m)) / (2 m (1 - m)) (Abramowitz & Stegun 17.3.11 and 17.3.12 differentiated)
  and dm/dtheta0 = sin(theta0) / 2: dT/dtheta0 = (2 / omega0) dK/dm sin(theta0) and
  dT/dE = dT/dtheta0 / (m g l sin(theta0)) = 2 dK/dm / (omega0 m g l).
- The double pendulum's first nonlinear mode with a kept coordinate: dT/dq_1 against central differences
  of the periods of the orbits kept at q_1 +- h.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.special
from numpy.testing import assert_allclose
from scene_cases import pivot_scene

import pinlin
from pinlin.periodic.family import Family

G, L, MASS = 9.81, 0.5, 1.3
OMEGA0 = math.sqrt(G / L)


def _swing(theta0):
    """(T, dT/dE, dT/dtheta0, E) of the swing of amplitude theta0, closed form."""
    m = math.sin(theta0 / 2) ** 2
    K, E = scipy.special.ellipk(m), scipy.special.ellipe(m)
    dK = (E - (1 - m) * K) / (2 * m * (1 - m))
    return (4 * K / OMEGA0, 2 * dK / (OMEGA0 * MASS * G * L), 2 * dK * math.sin(theta0) / OMEGA0,
            -MASS * G * L * math.cos(theta0))


def _start(scene, theta0):
    q0 = np.zeros(scene.model.nq)
    q0[2] = theta0
    return q0


@pytest.mark.parametrize("theta0", [2.0, 2.5, 3.0])
@pytest.mark.parametrize("factor", [1.02, 1.3, 0.7])
def test_swing_keeps_its_energy(theta0, factor):
    scene = pivot_scene({}, length=L, mass=MASS)
    T, dT_dE, _, energy = _swing(theta0)
    orbit = pinlin.periodic_orbit(scene, _start(scene, theta0), period=factor * T)
    print(f"theta0 {theta0}, guess x{factor}: amplitude {orbit.q0[2] - theta0:.1e}, period {orbit.period / T - 1:.1e}, "
          f"dT/dE {orbit.period_derivative / dT_dE - 1:.1e} (error figure {orbit.period_derivative_error / dT_dE:.1e})")
    assert orbit.family == "energy" and "energy kept" in orbit.method and "family='energy'" in repr(orbit)
    assert_allclose(orbit.q0[2], theta0, rtol=0, atol=1e-9)  # the start's own swing, not a neighbour
    assert_allclose(orbit.q(orbit.period / 2)[2], -theta0, rtol=0, atol=1e-9)  # the other turning point
    assert_allclose(orbit.period, T, rtol=1e-9)
    assert_allclose(orbit.family_value, energy, rtol=1e-12)
    assert_allclose(orbit.period_derivative, dT_dE, rtol=1e-6)
    assert abs(orbit.period_derivative - dT_dE) <= orbit.period_derivative_error <= 1e-8 * dT_dE


def test_swing_from_three_radians_and_the_linear_period():
    """The start that did not converge with the minimum-norm step: 3 rad, the guess 1.3 x 2 pi / omega0."""
    scene = pivot_scene({}, length=L, mass=MASS)
    orbit = pinlin.periodic_orbit(scene, _start(scene, 3.0), period=1.3 * 2 * math.pi / OMEGA0)
    assert_allclose(orbit.period, _swing(3.0)[0], rtol=1e-9)
    assert_allclose(orbit.q0[2], 3.0, rtol=0, atol=1e-9)


def test_swing_keeps_a_coordinate():
    scene = pivot_scene({}, length=L, mass=MASS)
    T, _, dT_dtheta, _ = _swing(2.5)
    orbit = pinlin.periodic_orbit(scene, _start(scene, 2.5), period=1.3 * T, keep="swing")
    assert orbit.family == "swing" and "swing kept" in orbit.method
    assert orbit.family_value == 2.5
    assert_allclose(orbit.q0[2], 2.5, rtol=0, atol=1e-9)
    assert_allclose(orbit.period, T, rtol=1e-9)
    assert_allclose(orbit.period_derivative, dT_dtheta, rtol=1e-6)
    d = orbit.to_dict()
    assert d["family"] == "swing" and d["period_derivative"] == orbit.period_derivative


def test_double_pendulum_mode_keeps_a_coordinate():
    """Off its nonlinear mode, the start moves onto it with q_1 held; dT/dq_1 against central differences."""
    scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    start = np.array([0.3, 0.137])  # near the first linear mode shape (1, 0.457)

    def orbit(q1):
        return pinlin.periodic_orbit(scene, [q1, start[1]], period=1.8, keep="joint1", residual_tol=1e-12)

    mid = orbit(start[0])
    assert mid.family == "joint1" and mid.iterations >= 1
    assert_allclose(mid.q0[0], start[0], rtol=0, atol=1e-12)
    assert abs(mid.q0[1] - start[1]) > 1e-3  # the second coordinate moved onto the mode
    h = 1e-3
    fd = (orbit(start[0] + h).period - orbit(start[0] - h).period) / (2 * h)
    assert_allclose(mid.period_derivative, fd, rtol=1e-5)  # central differences: O(h^2) ~ 1e-6
    energy = pinlin.periodic_orbit(scene, mid.q0, mid.v0, period=mid.period)  # the same orbit by its energy
    assert energy.family == "energy"
    assert_allclose(energy.q0, mid.q0, rtol=0, atol=1e-9)
    assert_allclose(energy.period, mid.period, rtol=1e-10)


def test_isolated_orbits_have_no_family():
    forced = pivot_scene({"pivot_x": pinlin.Harmonic(0.05, 4.0)}, length=L, mass=MASS,
                         elements=[pinlin.JointDamper("swing", 0.4)])
    orbit = pinlin.periodic_orbit(forced, np.zeros(forced.model.nq))
    assert orbit.family is None and orbit.period_derivative is None and orbit.period_derivative_error is None


def test_bad_keep_raises():
    scene = pivot_scene({}, length=L, mass=MASS)
    q0 = _start(scene, 1.0)
    with pytest.raises(pinlin.ParameterError, match=r"keep: the robot has no joint 'elbow'; its joints: .*'swing'"):
        pinlin.periodic_orbit(scene, q0, period=1.5, keep="elbow")
    with pytest.raises(pinlin.ParameterError, match="'pivot_x' is not a free 1-DOF joint"):
        pinlin.periodic_orbit(scene, q0, period=1.5, keep="pivot_x")
    with pytest.raises(pinlin.ParameterError, match="expected a joint name"):
        pinlin.periodic_orbit(scene, q0, period=1.5, keep=2)
    damped = pivot_scene({}, length=L, mass=MASS, elements=[pinlin.JointDamper("swing", 0.5)])
    with pytest.raises(pinlin.ParameterError, match=r"not conservative \(its elements add damping\)"):
        pinlin.periodic_orbit(damped, q0, period=1.5, keep="swing")
    forced = pivot_scene({"pivot_x": pinlin.Harmonic(0.05, 4.0)}, length=L, mass=MASS)
    with pytest.raises(pinlin.ParameterError, match="forced"):
        pinlin.periodic_orbit(forced, np.zeros(forced.model.nq), keep="swing")


def test_energy_gradient_against_central_differences():
    """dE/ds from Pinocchio's RNEA derivatives against central differences of E (springs on both joints)."""
    robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 2.0), pinlin.JointSpring("joint2", 1.5, rest=0.2)])
    family = Family(scene, np.array([0.4, -0.3]), np.zeros(2), None)
    s = np.random.default_rng(7).normal(size=4)
    h = 1e-6
    fd = np.array([(family.energy(s + h * e) - family.energy(s - h * e)) / (2 * h) for e in np.eye(4)])
    assert_allclose(family.energy_gradient(s), fd, rtol=1e-8, atol=1e-8 * np.abs(fd).max())


def test_swing_with_a_spring_keeps_its_energy():
    """E = -m g l cos(theta0) + k theta0^2 / 2 at rest; dT/dE against central differences of the period in
    theta0 over dE/dtheta0 = m g l sin(theta0) + k theta0."""
    k = 4.0
    scene = pivot_scene({}, length=L, mass=MASS, elements=[pinlin.JointSpring("swing", k)])

    def orbit(theta0):
        return pinlin.periodic_orbit(scene, _start(scene, theta0), period=1.3, residual_tol=1e-12)

    mid = orbit(2.0)
    assert mid.family == "energy"
    assert_allclose(mid.q0[2], 2.0, rtol=0, atol=1e-9)
    assert_allclose(mid.family_value, -MASS * G * L * math.cos(2.0) + k * 2.0**2 / 2, rtol=1e-12)
    h = 1e-3
    dT = (orbit(2.0 + h).period - orbit(2.0 - h).period) / (2 * h)
    assert_allclose(mid.period_derivative, dT / (MASS * G * L * math.sin(2.0) + k * 2.0), rtol=1e-5)
