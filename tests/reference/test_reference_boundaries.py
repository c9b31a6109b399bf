"""Stability boundaries and sensitivities against closed forms (theory: worked examples, boundaries).

Sources of the reference values (derivations in tests/boundaries/boundary_cases.py, evaluated with mpmath):

- Ziegler's column (Ziegler, "Die Stabilitaetskriterien der Elastomechanik", Ing.-Arch. 20, 1952; Bolotin 1963):
  two rigid links of length l, masses 2m (middle joint) and m (tip), joint springs k, follower load P:
  det(mu M + K) = m^2 l^4 (2 mu^2 + (7 - 2P) mu + 1) for k = l = m = 1, so P_f = 7/2 - sqrt(2); with equal
  joint dampers c the flutter load is the smallest positive root of the Routh-Hurwitz determinant.
- The paper's double pendulum (theory: double pendulum, Example 6.2): P_f = 16.4328976484... and the divergence load P_d, the
  roots of the discriminant of det(mu M + K(P)); damped: Routh-Hurwitz as above.
- The rotating ring (theory: rotating ring, Example 11.1) with damping: critical speed sqrt(k/m).
- A chain of n links under a dead compressive tip force (no gravity): K = k T - P l I in absolute angles,
  buckling at P = (4k/l) sin^2(pi / (2(2n + 1))), the smallest root of det K(P) = 0 (checked also as a
  generalized eigenvalue problem of pinlin's own K(0) and dK/dP).

Every returned error bound must contain the reference.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

import pinlin
from boundaries.boundary_cases import (
    RING,
    ZIEGLER_FLUTTER,
    chain_buckling_load,
    compressed_chain,
    damped_flutter_load,
    double_pendulum,
    double_pendulum_dlam,
    double_pendulum_theta,
    ring_matrices,
    undamped_loads,
    ziegler,
    ziegler_theta,
)

P_F, P_D = undamped_loads(double_pendulum_theta)


def _contains(result, reference):
    assert abs(result.value - reference) <= result.error_bound, (result, reference)


def test_ziegler_undamped_flutter_load():
    assert_allclose(undamped_loads(ziegler_theta)[0], ZIEGLER_FLUTTER, rtol=1e-15)  # the two derivations agree
    r = pinlin.critical_parameter(ziegler(), (0.5, 3.0))
    assert_allclose(r.value, 3.5 - np.sqrt(2.0), rtol=1e-12)
    _contains(r, ZIEGLER_FLUTTER)
    assert r.evaluations <= 10


@pytest.mark.parametrize("c", [1e-3, 1e-2, 0.1, 0.5])
def test_ziegler_damped_flutter_loads(c):
    reference = damped_flutter_load(ziegler_theta, c, 10.0)
    r = pinlin.critical_parameter(ziegler(c), (0.5, 3.0))
    assert_allclose(r.value, reference, rtol=1e-10)
    _contains(r, reference)


def test_ziegler_paradox():
    """Vanishing damping lowers the flutter load below the undamped one (Ziegler's paradox)."""
    small = pinlin.critical_parameter(ziegler(1e-6), (0.5, 3.0))
    assert small.value < 0.75 * ZIEGLER_FLUTTER


def test_double_pendulum_flutter_and_divergence_loads():
    assert_allclose(P_F, 16.4328976484, rtol=1e-11)
    flutter = pinlin.critical_parameter(double_pendulum(), (10.0, 20.0))
    divergence = pinlin.critical_parameter(double_pendulum(), (20.0, 38.0))
    assert_allclose(flutter.value, P_F, rtol=1e-12)
    assert_allclose(divergence.value, P_D, rtol=1e-12)
    _contains(flutter, P_F)
    _contains(divergence, P_D)
    assert (flutter.kind, divergence.kind) == ("flutter", "divergence")
    assert flutter.evaluations <= 10 and divergence.evaluations <= 10


@pytest.mark.parametrize("c", [1e-3, 1e-2, 0.1, 1.0])
def test_double_pendulum_damped_flutter_loads(c):
    reference = damped_flutter_load(double_pendulum_theta, c, 40.0)
    r = pinlin.critical_parameter(double_pendulum(c), (1.0, 40.0))
    assert_allclose(r.value, reference, rtol=1e-10)
    _contains(r, reference)


@pytest.mark.parametrize("c", [0.05, 0.3, 2.0])
def test_rotating_ring_critical_speed(c):
    critical = np.sqrt(RING["k"] / RING["m"])
    r = pinlin.critical_parameter(ring_matrices(c), (0.5 * critical, 2.0 * critical))
    assert_allclose(r.value, critical, rtol=1e-12)
    _contains(r, critical)
    # below: stable (marginally so within rounding of the speed, where S = (k - m Omega^2) I is singular to the
    # definiteness tolerance); above: unstable (Kelvin-Tait-Chetaev: damping destroys gyroscopic stabilization)
    assert r.verdicts[0] in ("asymptotically_stable", "marginally_stable") and r.verdicts[1] in ("flutter", "divergence")
    assert abs(r.eigenvalue) <= 1e-6 * critical  # K = (k - m Omega^2) I = 0: the pair passes through the origin


@pytest.mark.parametrize("n", [3, 10, 25])
def test_chain_buckling_load(n):
    func = compressed_chain(n)
    reference = chain_buckling_load(n)
    r = pinlin.critical_parameter(func, (0.0, 1.0))
    assert r.kind == "divergence" and r.verdicts == ("marginally_stable", "divergence")
    assert_allclose(r.value, reference, rtol=1e-12)
    _contains(r, reference)
    # the same load as the smallest root of det(K0 + P K1) = 0, a generalized eigenvalue problem
    K0, K1 = func(0.0).K, func(1.0).K - func(0.0).K
    roots = scipy.linalg.eigvals(K0, -K1)
    smallest = np.min(roots[np.isfinite(roots) & (roots.real > 0)].real)
    assert_allclose(r.value, smallest, rtol=1e-12)


def test_stability_boundary_of_the_damped_double_pendulum():
    dampings = np.logspace(-3, 0, 7)
    curve = pinlin.stability_boundary(lambda c, P: double_pendulum(c)(P), dampings, (1.0, 40.0))
    reference = np.array([damped_flutter_load(double_pendulum_theta, c, 40.0) for c in dampings])
    assert np.all(curve.found) and set(curve.kind) == {"flutter"}
    assert_allclose(curve.p2, reference, rtol=1e-10)
    assert np.all(np.abs(curve.p2 - reference) <= curve.error_bound)


@pytest.mark.parametrize("P", [2.0, 12.0])
def test_double_pendulum_sensitivities(P):
    r = pinlin.eigenvalue_sensitivity(double_pendulum(), P)
    reference = np.array([double_pendulum_dlam(P, lam) for lam in r.eigenvalues])
    assert_allclose(r.derivatives, reference, rtol=1e-10)
    assert np.all(np.abs(r.derivatives - reference) <= r.derivative_error)
