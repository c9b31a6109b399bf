"""Structure in the verdict: an autonomous orbit's trivial multipliers (the pendulum's large swing, a Jordan
block at 1), Krein signatures of colliding multipliers (equal: stable; mixed: undecided)."""

from __future__ import annotations

import numpy as np
import scipy.special
from numpy.testing import assert_allclose

from pinlin.periodic import floquet_analysis_matrices

W0, THETA0 = 1.3, 2.0                   # omega0 = sqrt(g / l) [rad/s], amplitude [rad]


def _pendulum_swing():
    """x'' + omega0^2 cos(theta(t)) x = 0 along theta = 2 arcsin(k sn(omega0 t + K(k), k)), k = sin(theta0/2),
    period 4 K(k) / omega0 (theory: Floquet), beside an uncoupled oscillator of frequency 1.7 rad/s."""
    k = np.sin(THETA0 / 2)
    Kk = scipy.special.ellipk(k ** 2)

    def K(t):
        sn = scipy.special.ellipj(W0 * t + Kk, k ** 2)[0]
        return np.diag([W0 ** 2 * np.cos(2 * np.arcsin(k * sn)), 1.7 ** 2])
    return K, 4 * Kk / W0


def test_autonomous_orbit_sets_the_jordan_pair_at_one_apart():
    K, T = _pendulum_swing()
    plain = floquet_analysis_matrices(np.eye(2), None, K, T)
    assert plain.stability.kind == "undecided" and "Krein" in plain.stability.reason
    res = floquet_analysis_matrices(np.eye(2), None, K, T, autonomous=True)
    assert res.trivial.sum() == 2
    split = np.abs(res.multipliers[res.trivial] - 1)
    assert np.all(split < 1e-5)                         # a Jordan block: split ~ sqrt(rounding)
    # the first-order bound at the split pair is of the split's order (1 / |w^H z| ~ 1 / split): it holds
    bound = res.error_bound[res.trivial]
    assert np.all((split <= bound) & (bound <= 100 * split)), (split, bound)
    assert res.stability.kind == "marginally_stable"
    assert "trivial" in res.stability.reason
    other = res.multipliers[~res.trivial]
    assert_allclose(np.sort(np.abs(np.angle(other))), abs(np.angle(np.exp(1.7j * T))), rtol=1e-12)
    assert np.isfinite(res.error) and res.error < 1e-11     # the trivial pair is left out of the figure


def test_equal_krein_signatures_collide_stably():
    res = floquet_analysis_matrices(np.eye(2), None, np.diag([2.0, 2.0]), 1.0)   # double multiplier pairs
    assert res.stability.kind == "marginally_stable", res.stability
    assert_allclose(np.abs(res.multipliers), 1.0, atol=1e-13)


def test_mixed_krein_signatures_are_undecided():
    # the rotating shaft at its critical speed: G = 2 J, K = diag(0, 1): a double 0 eigenvalue
    J = np.array([[0.0, -1.0], [1.0, 0.0]])
    res = floquet_analysis_matrices(np.eye(2), 2 * J, np.diag([0.0, 1.0]), 1.0)
    assert res.conservative
    assert res.stability.kind == "undecided" and "Krein" in res.stability.reason
