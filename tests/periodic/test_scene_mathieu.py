"""Mathieu's equation through a multibody model (theory: Floquet): a point-mass pendulum
on a pivot moving vertically, z_p = A sin(omega t + phi).

Derivation (tests/periodic/scene_cases.py): J theta'' + m l (g + z_p'') sin theta = 0 with J = m l^2, so
about the hanging position K(t) = m l (g - A omega^2 sin(omega t + phi)), M = m l^2, C = 0.  With
phi = pi / 2 (z_p = A cos omega t), omega = 1 and l = 1 this is theta'' + (delta + eps cos t) theta = 0 with
delta = g and eps = -A (the theory page writes +A: its z_p points down; the regions are symmetric in eps).
Inverted (theta = pi): K(t) = -m l (g + z_p''): delta = -g / (l omega^2), eps = A / l (Kapitza).
Transition curves: Mathieu characteristic values a_r(q), b_r(q) (scipy.special), a = 4 delta, q = -2 eps.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.optimize
import scipy.special
from numpy.testing import assert_allclose
from scene_cases import pivot_scene

import pinlin

EPS = 0.3
Q = 2 * EPS


def _hanging(g: float, A: float = EPS, omega: float = 1.0, length: float = 1.0, mass: float = 1.0, q=0.0):
    scene = pivot_scene({"pivot_z": pinlin.Harmonic(A, omega, phase=math.pi / 2)}, length=length, mass=mass, g=g)
    q0 = np.zeros(scene.model.nq)
    q0[2] = q
    return scene, pinlin.periodic_orbit(scene, q0)


def test_hanging_orbit_is_constant_and_coefficients_match_closed_form():
    A, omega, length, mass, g = 0.02, 60.0, 0.3, 1.7, 9.81
    scene, orbit = _hanging(g, A, omega, length, mass)
    assert orbit.constant and not orbit.autonomous and orbit.iterations == 0
    assert orbit.residual == 0.0
    assert_allclose(orbit.period, 2 * math.pi / omega, rtol=1e-15)
    co = pinlin.variational_coefficients(scene, orbit)
    for t in np.linspace(0.0, 2 * orbit.period, 11):
        K = mass * length * (g - A * omega**2 * math.cos(omega * t))
        assert_allclose(co.M(t), [[mass * length**2]], rtol=1e-12)
        assert_allclose(co.K(t), [[K]], rtol=1e-12)
        assert_allclose(co.C(t), [[0.0]], atol=1e-12 * mass * length**2 * omega)
        assert_allclose(orbit.q(t)[1], A * math.cos(omega * t), rtol=0, atol=1e-16)
        assert_allclose(orbit.a(t)[1], -A * omega**2 * math.cos(omega * t), rtol=0, atol=1e-13)
    co.K(0.1), co.M(0.1), co.C(0.1)
    before = co.evaluations
    co.K(0.1), co.M(0.1), co.C(0.1)
    assert co.evaluations == before  # cached per t


def _trace_excess(g: float) -> float:
    scene, orbit = _hanging(g)
    flo = pinlin.floquet_analysis(scene, orbit)
    return abs(np.trace(flo.monodromy)) - 2.0


@pytest.mark.parametrize("kind", ["b", "a"])
def test_first_tongue_transition_matches_scipy(kind):
    """|tr Phi(T)| = 2 at delta = b_1(q) / 4 and a_1(q) / 4: root finding on gravity (delta = g)."""
    a1, b1 = float(scipy.special.mathieu_a(1, Q)), float(scipy.special.mathieu_b(1, Q))
    target = (b1 if kind == "b" else a1) / 4
    inside = (a1 + b1) / 8
    outside = target + np.sign(target - inside) * 0.03
    assert _trace_excess(inside) > 0 > _trace_excess(outside)
    found = scipy.optimize.brentq(_trace_excess, min(inside, outside), max(inside, outside), xtol=1e-14)
    print(f"transition {kind}_1: found {found!r}, scipy {target!r}, error {found - target:.2e}")
    assert abs(found - target) <= 1e-9


@pytest.mark.parametrize("omega, stable", [(100.0, True), (50.0, False)])
def test_kapitza_inverted_pendulum_stable_where_mathieu_says(omega, stable):
    A, length, g = 0.03, 0.2, 9.81
    delta, eps = -g / (length * omega**2), A / length
    a0 = float(scipy.special.mathieu_a(0, 2 * eps)) / 4
    assert (delta > a0) == stable  # the Mathieu region, independently of pinlin
    scene, orbit = _hanging(g, A, omega, length, 1.0, q=math.pi)
    assert orbit.constant
    co = pinlin.variational_coefficients(scene, orbit)
    t = 0.37 * orbit.period
    assert_allclose(co.K(t), [[-length * (g - A * omega**2 * math.cos(omega * t))]], rtol=1e-12)
    flo = pinlin.floquet_analysis(scene, orbit)
    if stable:
        assert flo.stability.kind == "marginally_stable"
        assert_allclose(np.abs(flo.multipliers), 1.0, atol=1e-10)
    else:
        assert flo.stability.kind == "divergence"  # a real multiplier > 1 (the tongue below a_0)
        assert np.max(np.abs(flo.multipliers)) > 1.01
