"""Mathieu's equation x'' + (delta + eps cos t) x = 0 (theory: Floquet): transition curves against Mathieu
characteristic values (scipy.special, checked against Hill's method), verdicts inside and outside the
tongues, and the error bounds against a 36-digit mpmath reference."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import scipy.optimize
import scipy.special
from floquet_cases import hill_characteristic, mathieu
from floquet_reference import reference_multipliers, second_order_parts
from numpy.testing import assert_allclose

from pinlin.periodic import floquet_analysis_matrices

EPS = 0.3                  # eps; q = -2 eps in y'' + (a - 2 q cos 2z) y = 0, a = 4 delta, t = 2 z
Q = 2 * EPS                # the regions are symmetric in q: use |q|


def _trace_excess(delta: float) -> float:
    res = floquet_analysis_matrices(*mathieu(delta, EPS), 2 * np.pi)
    return abs(np.trace(res.monodromy)) - 2.0


@pytest.mark.parametrize("kind, r", [("a", 0), ("a", 1), ("b", 1), ("a", 2), ("b", 2), ("a", 3), ("b", 3)])
def test_scipy_characteristic_values_agree_with_hill(kind, r):
    scipy_value = (scipy.special.mathieu_a if kind == "a" else scipy.special.mathieu_b)(r, Q)
    assert_allclose(scipy_value, hill_characteristic(kind, r, Q), rtol=0, atol=1e-12)


@pytest.mark.parametrize("kind, r", [("b", 1), ("a", 1), ("b", 2), ("a", 2)])
def test_transition_curve_located_by_floquet(kind, r):
    """|tr Phi(T)| = 2 at delta = a_r / 4 or b_r / 4: root-finding on the trace of the monodromy."""
    target = hill_characteristic(kind, r, Q) / 4
    inside = (hill_characteristic("a", r, Q) + hill_characteristic("b", r, Q)) / 8   # mid-tongue
    outside = target + np.sign(target - inside) * 0.02
    assert _trace_excess(inside) > 0 > _trace_excess(outside)
    found = scipy.optimize.brentq(_trace_excess, min(inside, outside), max(inside, outside), xtol=1e-15)
    assert_allclose(found, target, rtol=0, atol=1e-9)
    assert abs(found - target) < 1e-11     # measured: a few 1e-14


def test_verdicts_inside_and_outside_the_tongues():
    b1, a1 = hill_characteristic("b", 1, Q) / 4, hill_characteristic("a", 1, Q) / 4
    b2, a2 = hill_characteristic("b", 2, Q) / 4, hill_characteristic("a", 2, Q) / 4
    a0 = hill_characteristic("a", 0, Q) / 4
    cases = {  # delta: kind
        (b1 + a1) / 2: "flutter",          # multiplier < -1: period doubling
        b1 - 1e-4: "marginally_stable",
        a1 + 1e-4: "marginally_stable",
        (b2 + a2) / 2: "divergence",       # multiplier > 1, real
        a0 - 0.01: "divergence",
        (a1 + b2) / 2: "marginally_stable",
    }
    for delta, kind in cases.items():
        res = floquet_analysis_matrices(*mathieu(delta, EPS), 2 * np.pi)
        assert res.stability.kind == kind, (delta, res.stability)
        assert res.conservative
    inside = floquet_analysis_matrices(*mathieu((b1 + a1) / 2, EPS), 2 * np.pi)
    assert np.all(inside.multipliers.real < 0)
    assert "period doubling" in inside.stability.reason


def test_damped_mathieu_is_asymptotically_stable_and_not_conservative():
    res = floquet_analysis_matrices(*mathieu(0.5, 0.2, damping=0.1), 2 * np.pi)
    assert res.stability.kind == "asymptotically_stable"
    assert not res.conservative
    # Liouville: det Phi(T) = exp(-damping T)
    assert_allclose(np.prod(res.multipliers), np.exp(-0.1 * 2 * np.pi), rtol=1e-13)


_REFERENCES: dict = {}


def _reference(delta, eps):
    """36-digit multipliers of x'' + (delta + eps cos t) x = 0 (computed once per session)."""
    if (delta, eps) not in _REFERENCES:
        parts = second_order_parts([np.zeros((1, 1))] * 3,
                                   [np.array([[delta]]), np.array([[eps]]), np.zeros((1, 1))])
        _REFERENCES[delta, eps] = reference_multipliers(*parts, steps=12)
    return _REFERENCES[delta, eps]


@pytest.mark.parametrize("delta, eps", [(0.3, 0.2), (0.6, 0.3)])     # in the first tongue; stable, |mu| = 1
@pytest.mark.parametrize("rtol", [1e-13, 1e-10, 1e-7])
@pytest.mark.parametrize("sampling", ["spectral", "nodes"])
def test_error_bounds_against_mpmath(delta, eps, rtol, sampling):
    """Every bound contains the 36-digit reference and is at most 100 times the true error (measured 2.4-38)."""
    reference = _reference(delta, eps)
    res = floquet_analysis_matrices(*mathieu(delta, eps), 2 * np.pi, rtol=rtol, sampling=sampling)
    for mu, bound in zip(res.multipliers, res.error_bound):
        err = min(float(abs(mpmath.mpc(mu) - z)) for z in reference)
        assert err <= bound <= 100 * err + 1e-15 * abs(mu), (mu, err, bound)
    assert res.error <= 100 * rtol


def test_frequency_identified_by_harmonic_content():
    """Weak pumping (eps = 0.04) at delta = 0.6: the modes oscillate near sqrt(delta) = 0.775 rad/s, outside the
    principal strip |Im lambda| <= 1/2, so the harmonic j = +-1 must be chosen; sidebands j +- 1 are weak."""
    res = floquet_analysis_matrices(*mathieu(0.6, 0.04), 2 * np.pi)
    assert_allclose(np.sort(res.frequencies), [-np.sqrt(0.6), np.sqrt(0.6)], atol=5e-3)
    assert np.all(np.abs(res.exponents.imag) <= 0.5 + 1e-12)
    assert sorted(res.dominant_harmonic.tolist()) == [-1, 1]
    J = (res.harmonic_content.shape[1] - 1) // 2
    share = res.harmonic_content[np.arange(2), res.dominant_harmonic + J]
    # Parseval up to the quadrature: harmonics near the node resolution pick up aliasing (measured 2e-6)
    assert np.all(share > 0.99) and np.all(np.abs(res.harmonic_content.sum(axis=1) - 1) < 1e-5)
