"""A damped 2-DOF periodic system whose multipliers span 32 decades (5e2 beside 2e-30): each keeps its
relative accuracy against a 36-digit mpmath reference, the bounds contain the reference within a stated
factor, and the eigenvalues of the formed monodromy do not (the design need for the periodic eigenproblem)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from floquet_reference import reference_multipliers, second_order_parts
from numpy.testing import assert_allclose

from pinlin.periodic import floquet_analysis_matrices, floquet_from_first_order

# M = I, C = C0 + C1 cos t + C2 sin t, K likewise: a heavily damped DOF (c = 11: a mode decaying like
# exp(-10.9 t)) coupled to a negatively damped one (c = -2: growing like exp(t)); period 2 pi.
C_PARTS = [np.array([[11.0, 0.0], [0.0, -2.0]]), np.array([[1.0, 0.0], [0.2, 0.0]]), np.array([[0.0, 0.3], [0.0, 0.0]])]
K_PARTS = [np.array([[1.0, 0.4], [0.0, 3.0]]), np.array([[0.5, 0.0], [0.0, 0.0]]), np.array([[0.0, 0.0], [0.1, 0.0]])]


def _C(t):
    return C_PARTS[0] + C_PARTS[1] * np.cos(t) + C_PARTS[2] * np.sin(t)


def _K(t):
    return K_PARTS[0] + K_PARTS[1] * np.cos(t) + K_PARTS[2] * np.sin(t)


@pytest.fixture(scope="module")
def reference():
    return reference_multipliers(*second_order_parts(C_PARTS, K_PARTS), steps=20)


@pytest.fixture(scope="module", params=["spectral", "nodes"])
def sampling(request):
    """Both ways of taking the coefficients: sampled once per period (interpolant) and at every node."""
    return request.param


@pytest.fixture(scope="module")
def result(sampling):
    return floquet_analysis_matrices(np.eye(2), _C, _K, 2 * np.pi, sampling=sampling)


def _errors(result, reference):
    return [min(float(abs(mpmath.mpc(mu) - z)) for z in reference) for mu in result.multipliers]


def test_multipliers_span_32_decades_each_with_its_relative_accuracy(result, reference):
    r = np.abs(result.multipliers)
    assert r.max() / r.min() > 1e32
    rel = np.array(_errors(result, reference)) / r
    assert np.all(rel < 1e-10)          # measured: 2e-14 (large pair), 8e-12 (smallest, 1.7e-30)
    assert result.segments >= 11        # the 32 decades need K >= 32 / 3 segments of condition <= 1e3


def test_formed_product_loses_the_smallest_multiplier(result, reference):
    naive = sorted(np.linalg.eigvals(result.monodromy), key=abs)[0]
    smallest = complex(reference[-1])
    assert abs(naive - smallest) / abs(smallest) > 1e3      # measured ~1e15: not even its sign or decade


def test_error_bounds_contain_the_reference_within_a_factor(result, reference):
    for mu, bound, err in zip(result.multipliers, result.error_bound, _errors(result, reference)):
        assert err <= bound <= 1e3 * err, (mu, err, bound)      # measured ratios 4.5-12
    assert_allclose(result.error, np.max(result.error_bound / np.abs(result.multipliers)), rtol=1e-15)


def test_verdict_flutter_from_the_growing_complex_pair(result):
    assert result.stability.kind == "flutter"
    assert abs(result.stability.eigenvalue) > 500
    assert not result.conservative


def test_stable_variant_is_asymptotically_stable():
    C = lambda t: _C(t) + np.diag([0.0, 2.5])   # noqa: E731 (the second DOF now damped: c = 0.5)
    res = floquet_analysis_matrices(np.eye(2), C, _K, 2 * np.pi)
    assert res.stability.kind == "asymptotically_stable"
    assert np.max(np.abs(res.multipliers)) < 1
    # Liouville: det Phi(T) = exp(-int tr C) = exp(-(11 + 0.5) 2 pi)
    assert_allclose(np.prod(res.multipliers), np.exp(-11.5 * 2 * np.pi), rtol=1e-11)


def test_first_order_entry_point_gives_the_same_multipliers(result, sampling):
    A0, A1, A2 = second_order_parts(C_PARTS, K_PARTS)
    res = floquet_from_first_order(lambda t: A0 + A1 * np.cos(t) + A2 * np.sin(t), 2 * np.pi, sampling=sampling)
    assert_allclose(res.multipliers, result.multipliers, rtol=1e-11)
    assert res.evaluations == result.evaluations


def test_general_first_order_path_agrees_with_the_second_order_elimination(result):
    """A similarity y = S w hides the [[0, I], [X, Y]] form, so the full (2 s n)-square stage solve is used;
    the multipliers are invariant."""
    A0, A1, A2 = second_order_parts(C_PARTS, K_PARTS)
    S = np.eye(4) + 0.3 * np.random.default_rng(11).standard_normal((4, 4))
    Si = np.linalg.inv(S)
    res = floquet_from_first_order(lambda t: Si @ (A0 + A1 * np.cos(t) + A2 * np.sin(t)) @ S, 2 * np.pi)
    for mu in result.multipliers:
        assert np.min(np.abs(res.multipliers - mu)) <= 1e-10 * abs(mu)
