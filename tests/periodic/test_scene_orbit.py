"""Periodic reference motions by shooting and the variational coefficients along them.

- A pendulum on a horizontally vibrating pivot, x_p = A sin(omega t), small amplitude: the forced orbit
  against the linear harmonic response J theta'' + c theta' + k theta = m l x_p'' (k = m g l, J = m l^2).
- The pendulum's large swing as an autonomous orbit: T = 4 K(k) / omega0, k = sin(theta0 / 2),
  omega0^2 = g / l (scipy.special.ellipk(k**2)); the monodromy minus I has rank 1 (Jordan pair at 1).
- M(t), C(t), K(t) against central differences of the nonlinear free dynamics (FreeDynamics).
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
import scipy.special
from numpy.testing import assert_allclose
from scene_cases import pivot_scene

import pinlin
from pinlin.nonlinear.dynamics import FreeDynamics

G, L, MASS = 9.81, 0.5, 1.3


def _linear_response(A, omega, c):
    """theta(t) = Re(Theta e^{i omega t}) of J theta'' + c theta' + k theta = -m l A omega^2 sin(omega t)."""
    J, k = MASS * L**2, MASS * G * L
    Theta = -MASS * L * A * omega**2 / (k - J * omega**2 + 1j * c * omega) / 1j  # sin = Re(e^{i w t} / i)
    return lambda t: (Theta * np.exp(1j * omega * t)).real, lambda t: (1j * omega * Theta * np.exp(1j * omega * t)).real


def test_forced_orbit_matches_linear_harmonic_response():
    A, omega, c = 1e-7, 3.0, 0.2
    scene = pivot_scene({"pivot_x": pinlin.Harmonic(A, omega)}, length=L, mass=MASS,
                        elements=[pinlin.JointDamper("swing", c)])
    orbit = pinlin.periodic_orbit(scene, np.zeros(scene.model.nq))
    assert not orbit.constant and not orbit.autonomous
    assert_allclose(orbit.period, 2 * math.pi / omega, rtol=1e-15)
    assert orbit.residual <= 1e-10 and orbit.error >= orbit.residual
    assert orbit.history[0] > 0.1 and orbit.history[-1] == orbit.residual and orbit.iterations >= 1
    theta, theta_dot = _linear_response(A, omega, c)
    amp = abs(theta(0.0)) + abs(theta(math.pi / 2 / omega))
    for t in np.linspace(0.0, 2 * orbit.period, 9):  # periodic extension included
        # nonlinear corrections are O(theta^3): 1e-14 of theta here
        assert_allclose(orbit.q(t)[2], theta(t), rtol=0, atol=1e-9 * amp)
        assert_allclose(orbit.v(t)[2], theta_dot(t), rtol=0, atol=1e-9 * amp * omega)
        assert orbit.q(t)[0] == A * math.sin(omega * t)
    d = orbit.to_dict()
    assert d["type"] == "PeriodicOrbit" and d["period"] == orbit.period and "scene" not in d
    assert "forced" in repr(orbit) and "shooting" in orbit.method
    flo = pinlin.floquet_analysis(scene, orbit)
    # linear in theta to O(theta^2): the damped pendulum's multipliers exp(lambda T), lambda = -c/2J +- i w_d
    J, k = MASS * L**2, MASS * G * L
    lam = -c / (2 * J) + 1j * math.sqrt(k / J - (c / (2 * J)) ** 2)
    mu = np.exp(np.array([lam, lam.conjugate()]) * orbit.period)
    assert_allclose(sorted(flo.multipliers, key=np.imag), sorted(mu, key=np.imag), rtol=1e-9)
    assert flo.stability.kind == "asymptotically_stable"


def test_large_swing_period_is_the_elliptic_integral():
    scene = pivot_scene({}, length=L, mass=MASS)
    theta0 = 2.0
    q0 = np.zeros(scene.model.nq)
    q0[2] = theta0
    omega0 = math.sqrt(G / L)
    orbit = pinlin.periodic_orbit(scene, q0, period=1.3 * 2 * math.pi / omega0, residual_tol=1e-12)
    assert orbit.autonomous and not orbit.constant
    k = math.sin(orbit.q0[2] / 2)
    exact = 4 * scipy.special.ellipk(k**2) / omega0
    print(f"swing: period error {orbit.period / exact - 1:.2e}, residual {orbit.residual:.1e}, "
          f"iterations {orbit.iterations}, amplitude {orbit.q0[2]!r}")
    assert abs(orbit.period / exact - 1) <= 1e-12
    assert abs(orbit.q0[2] - theta0) < 0.05 and abs(orbit.v0[2]) < 1e-9  # the phase condition: v(0) = 0
    sv = np.linalg.svd(orbit.monodromy - np.eye(2), compute_uv=False)
    assert sv[0] > 1.0 and sv[1] <= 1e-9 * sv[0]  # rank 1: one Jordan chain of length 2 at mu = 1
    assert not np.allclose(orbit.monodromy, np.eye(2), atol=1e-3)  # not diagonalizable: a true Jordan block
    flo = pinlin.floquet_analysis(scene, orbit)
    assert flo.trivial.all() and len(flo.multipliers) == 2
    assert_allclose(flo.multipliers, 1.0, atol=1e-4)  # a Jordan pair splits as sqrt(rounding)


def test_coefficients_against_finite_differences_of_the_free_dynamics():
    """At points of a forced orbit of a double pendulum (spring, damper), M^-1 K and M^-1 C against
    -d a_f / d q and -d a_f / d v by central differences (pin.integrate), and M against crba."""
    scene = pivot_scene({"pivot_x": pinlin.Harmonic(0.05, 4.0), "pivot_z": pinlin.Harmonic(0.02, 8.0, phase=0.3)},
                        length=L, mass=MASS, links=2,
                        elements=[pinlin.JointSpring("swing2", 3.0), pinlin.JointDamper("swing", 0.4),
                                  pinlin.JointDamper("swing2", 0.3)])
    assert_allclose(pinlin.scene_period(scene), 2 * math.pi / 4.0, rtol=1e-15)
    orbit = pinlin.periodic_orbit(scene, np.zeros(scene.model.nq))
    co = pinlin.variational_coefficients(scene, orbit)
    dyn = FreeDynamics(scene)
    free, h = scene.free_dofs, 1e-6
    worst = 0.0
    for t in (0.11, 0.52, 1.3):
        q, v = orbit.q(t), orbit.v(t)
        p = co.point(t)

        def acc(dq, dv, q=q, v=v, t=t):
            qq = pin.integrate(scene.model, q, dq)
            vv = v + dv
            a_p = dyn.apply_motions(t, qq, vv)
            return dyn.acceleration(qq, vv, a_p)

        Aq = np.empty((2, 2))
        Av = np.empty((2, 2))
        for j, i in enumerate(free):
            e = np.zeros(scene.model.nv)
            e[i] = h
            Aq[:, j] = (acc(e, 0 * e) - acc(-e, 0 * e)) / (2 * h)
            Av[:, j] = (acc(0 * e, e) - acc(0 * e, -e)) / (2 * h)
        MK = np.linalg.solve(p.M, p.K)
        MC = np.linalg.solve(p.M, p.C)
        worst = max(worst, np.linalg.norm(MK + Aq) / np.linalg.norm(MK), np.linalg.norm(MC + Av) / np.linalg.norm(MC))
        assert_allclose(p.M, pin.crba(scene.model, scene.model.createData(), q)[np.ix_(free, free)], rtol=1e-14)
        assert_allclose(p.a_free, acc(0 * q[: scene.model.nv], 0 * v), rtol=1e-14)
    print(f"finite differences: largest relative error {worst:.1e}")
    assert worst <= 1e-7


def test_simulate_follows_the_orbit():
    scene = pivot_scene({"pivot_x": pinlin.Harmonic(0.05, 4.0)}, length=L, mass=MASS,
                        elements=[pinlin.JointDamper("swing", 0.4)])
    orbit = pinlin.periodic_orbit(scene, np.zeros(scene.model.nq))
    t = np.linspace(0.0, 2 * orbit.period, 7)
    sim = pinlin.simulate(scene, orbit.q0, orbit.v0, t, rtol=1e-12, atol=1e-14)
    for i, ti in enumerate(t):
        assert_allclose(sim.q[i, 2], orbit.q(ti)[2], rtol=0, atol=1e-9)


def test_bad_orbits_raise():
    scene = pivot_scene({}, length=L, mass=MASS)
    q0 = np.zeros(scene.model.nq)
    q0[2] = 1.0
    with pytest.raises(pinlin.NoPeriodError, match="give period="):
        pinlin.periodic_orbit(scene, q0)
    with pytest.raises(pinlin.PeriodicOrbitError, match="did not converge") as info:
        pinlin.periodic_orbit(scene, q0, period=5.0, max_iterations=1)
    assert len(info.value.history) == 2 and info.value.history[0] > 0.1
    damped = pivot_scene({}, length=L, mass=MASS, elements=[pinlin.JointDamper("swing", 0.5)])
    with pytest.raises(pinlin.PeriodicOrbitError) as info:  # a damped pendulum has no free oscillation
        pinlin.periodic_orbit(damped, q0, period=1.5)
    assert info.value.history
    limited = pivot_scene({}, length=L, mass=MASS, limit=(-1.2, 1.2))
    q0[2] = 1.5
    with pytest.raises(pinlin.OrbitLimitError, match="'swing' reaches") as info:
        pinlin.periodic_orbit(limited, q0, period=1.6)
    assert info.value.joint == "swing" and info.value.upper == 1.2
    forced = pivot_scene({"pivot_x": pinlin.Harmonic(0.05, 4.0)}, length=L, mass=MASS)
    with pytest.raises(pinlin.NoPeriodError, match="not a whole multiple"):
        pinlin.periodic_orbit(forced, np.zeros(forced.model.nq), period=1.0)
    sub = pinlin.periodic_orbit(pivot_scene({"pivot_z": pinlin.Harmonic(0.05, 4.0)}, length=L, mass=MASS),
                                np.zeros(forced.model.nq), period=math.pi)
    assert sub.constant and sub.period == math.pi  # twice the forcing period: a subharmonic is allowed
    with pytest.raises(pinlin.ParameterError, match="autonomous"):
        pinlin.floquet_analysis(sub.scene, sub, autonomous=True)
    with pytest.raises(pinlin.ParameterError, match="another scene"):
        pinlin.floquet_analysis(forced, sub)
