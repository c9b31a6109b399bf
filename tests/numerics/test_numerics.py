"""pinlin.numerics: the shared numerics, each against hand values or an independent reference.

Definiteness and determinant signs are in test_definiteness.py.  The condition numbers are
checked against the values theory: spectrum gives for its 3 x 3 check problem,
with eigenvalues from mpmath and eigenvectors from an SVD of L(lam) -- not from
pinlin's solver.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin import numerics as nm
from pinlin.errors import ComputationError, ParameterError
from spectral_cases import A0, A1, A2, mp_eigenvalues

CHECK_EIGENVALUES = np.array([-3.8513, -0.59217 + 0.80280j, -0.59217 - 0.80280j, 0.52326 + 0.62251j,
                             0.52326 - 0.62251j, 0.78909])
CHECK_KAPPA = np.array([2.3092, 0.70275, 0.70275, 2.7013, 2.7013, 2.0144])


def _null_vectors(L):
    """Right x (L x = 0) and plain-transpose left y (y^T L = 0) from the SVD of L."""
    U, _, Vh = np.linalg.svd(L)
    return Vh[-1].conj(), U[:, -1].conj()


def test_condition_numbers_match_the_spec_check_values():
    lam = mp_eigenvalues(A2, A1, A0)
    order = [int(np.argmin(np.abs(lam - v))) for v in CHECK_EIGENVALUES]
    lam = lam[order]
    assert_allclose(lam, CHECK_EIGENVALUES, atol=1e-4)
    kappa = []
    for z in lam:
        x, y = _null_vectors(z * z * A2 + z * A1 + A0)
        kappa.append(nm.condition_number(A2, A1, A0, z, x, y))
        assert nm.backward_error(A2, A1, A0, z, x) < 1e-14
        assert nm.backward_error(A2, A1, A0, z, y, left=True) < 1e-14
    assert_allclose(kappa, CHECK_KAPPA, rtol=2e-4)


def test_backward_error_by_hand():
    M, C, K = np.eye(2), np.zeros((2, 2)), np.diag([1.0, 4.0])
    # lam = i, x = e1 is exact; x = (1, 1): L(i) x = (0, 3), w = 1 * sqrt 2 + sqrt 17
    assert nm.backward_error(M, C, K, 1j, [1.0, 0.0]) == 0.0
    want = 3.0 / ((math.sqrt(2) + math.sqrt(17)) * math.sqrt(2))
    assert_allclose(nm.backward_error(M, C, K, 1j, [1.0, 1.0]), want, rtol=1e-15)
    # batched: a zero column is no eigenvector (inf); an exact residual 0 at lam = 0 with K = 0 is 0
    X = np.array([[0.0, 1.0], [0.0, 0.0]])
    Z = np.zeros((2, 2))
    eta = nm.backward_errors(np.array([1j, 0.0]), X, M @ X, Z, Z @ X, (math.sqrt(2), 0.0, 0.0))
    assert eta[0] == np.inf and eta[1] == 0.0
    assert_allclose(nm.eigen_weight(2.0, (1.0, 3.0, 5.0)), 4 + 6 + 5, rtol=0)


def test_homogeneous_form_without_overflow():
    a, b = nm.homogeneous(np.array([0.0, 1.0, 1e300, -3j]))
    assert_allclose(np.abs(a) ** 2 + b**2, 1.0, rtol=1e-15)
    assert_allclose(a[:2] / b[:2], [0.0, 1.0], rtol=1e-15)
    assert b[2] > 0 and abs(a[2] / b[2] - 1e300) <= 1e285
    assert_allclose(a[3] / b[3], -3j, rtol=1e-15)


def test_chain_residuals_by_hand():
    # critically damped: L(-w) = L'(-w) = 0, so x0 = 1 and any x1 solve the chain equations exactly
    w = 3.0
    assert nm.chain_residuals([[1.0]], [[2 * w]], [[w * w]], -w, [np.ones(1), np.array([5.0])]) == (0.0, 0.0)
    # L(i sqrt 2) = [[1, 1], [-1, -1]] for M = I, K = [[3, 1], [-1, 1]]: x0 = e1 is no eigenvector
    K = np.array([[3.0, 1.0], [-1.0, 1.0]])
    rho = nm.chain_residuals(np.eye(2), np.zeros((2, 2)), K, 1j * math.sqrt(2), [np.array([1.0, 0.0])])
    assert_allclose(rho, [math.sqrt(2) / (2 * math.sqrt(2) + math.sqrt(12))], rtol=1e-15)


def test_find_clusters():
    lam = np.array([1.0, 1 + 1e-7, 2.0, 2 + 1e-3, 0.0, 1e-9])
    assert nm.find_clusters(lam, 1e-5, scale=1.0) == [(0, 1), (4, 5)]
    assert nm.find_clusters(lam, 1e-5, scale=1.0, singletons=True) == [(0, 1), (2,), (3,), (4, 5)]
    # without a scale, 0 and 1e-9 are far apart relative to their own size
    assert nm.find_clusters(lam, 1e-5) == [(0, 1)]
    # well-conditioned eigenvalues (tiny bounds) are told apart although close: 1 and 1 + 1e-7
    # with bounds 1e-12 are distinct, 0 and 1e-9 with bounds 1e-10 are one (1e-9 <= 10 (2e-10))
    bound = np.array([1e-12, 1e-12, 1e-12, 1e-12, 1e-10, 1e-10])
    assert nm.find_clusters(lam, 1e-5, scale=1.0, bound=bound) == [(4, 5)]
    assert nm.find_clusters(lam, 1e-5, scale=1.0, bound=bound, factor=1.0) == []
    assert nm.find_clusters(np.array([1.0, 2.0]), 1e-5) == []


def test_fan_lin_van_dooren_and_scales_by_hand():
    s = nm.fan_lin_van_dooren(4.0, 0.0, 9.0)
    assert (s.gamma, s.delta) == (1.5, 2.0 / 9.0)
    assert nm.fan_lin_van_dooren(2.0, 6.0, 0.0).gamma == 3.0  # K = 0: ||C|| / ||M||
    assert nm.fan_lin_van_dooren(2.0, 0.0, 0.0) == nm.Scaling(1.0, 0.5)
    assert nm.system_scaling(np.eye(2), np.zeros((2, 2)), 4 * np.eye(2)).gamma == 2.0
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.diag([4.0, 9.0]))
    # eigenvalues +-2i, +-3i: geometric mean of the moduli sqrt 6, bounds 2 and 3 (sharp here)
    assert_allclose(nm.natural_scale(sys), math.sqrt(6.0), rtol=1e-15)
    assert_allclose(nm.eigenvalue_bounds(sys), (2.0, 3.0), rtol=1e-15)
    rigid = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.diag([0.0, 9.0]))
    assert nm.eigenvalue_bounds(rigid)[0] == 0.0
    assert nm.natural_scale(rigid) == nm.system_scaling(rigid.M, rigid.C, rigid.K).gamma


def test_norms_and_scaling_of_extreme_data():
    """Coefficients anywhere in double range give finite parameters or a clear error."""
    assert nm.frobenius(1e-300 * np.eye(4)) == 2e-300  # numpy's norm squares the entries to 0
    assert nm.frobenius(1e300 * np.ones((2, 2))) == 2e300  # ... or to inf
    assert nm.frobenius(np.zeros((2, 2))) == 0.0
    s = nm.fan_lin_van_dooren(1e-300, 0.0, 1.0)  # M = 1e-300: eigenvalues +-1e150 i
    assert s.gamma == pytest.approx(1e150, rel=1e-15) and s.delta == 2.0
    s = nm.fan_lin_van_dooren(1e-300, 1e-300, 1e-300)
    assert (s.gamma, s.delta) == (1.0, pytest.approx(1e300, rel=1e-15))
    with pytest.raises(ComputationError, match=r"out of double range \(gamma\^2 about 10\^-600"):
        nm.fan_lin_van_dooren(1e300, 0.0, 1e-300)
    with pytest.raises(ComputationError, match=r"must be finite with \|\|M\|\| > 0"):
        nm.fan_lin_van_dooren(0.0, 1.0, 1.0)
    sys = pinlin.LinearizedSystem.from_matrices(1e-300 * np.eye(1), np.zeros((1, 1)), np.eye(1))
    m = pinlin.modal_analysis(sys)
    assert_allclose(m.eigenvalues, [1e150j, -1e150j], rtol=1e-15)
    assert m.error < 1e-15 and m.stability.kind == "marginally_stable"
    with pytest.raises(ComputationError, match="rescale the system"):
        pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices(1e300 * np.eye(1), None, 1e-300 * np.eye(1)))


def test_checked_exp_and_chunks():
    assert nm.checked_exp(np.log(2.0), "x") == pytest.approx(2.0, rel=1e-15)
    with pytest.raises(ComputationError, match="x overflows double precision"):
        nm.checked_exp(800.0, "x")
    with pytest.raises(ComputationError, match="y underflows double precision"):
        nm.checked_exp(-800.0, "y")
    with pytest.raises(ComputationError, match="underflows"):
        nm.checked_exp(np.array([0.0, -800.0]), "z", each=True)
    parts = list(nm.chunks(10, 4, budget=3 * 16 * 16))
    assert [(p.start, p.stop) for p in parts] == [(0, 3), (3, 6), (6, 9), (9, 10)]


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: nm.check_tolerance(0.0, "tol"), "tol: expected a finite positive number"),
        (lambda: nm.check_tolerance(float("nan"), "tol"), "tol: expected a finite positive number"),
        (lambda: nm.check_tolerance("small", "tol"), "tol: expected a positive number"),
        (lambda: nm.check_tolerance(True, "tol"), "tol: expected a positive number"),
        (lambda: nm.check_tolerance(1.0, "tol", upper=1.0), "tol: expected a number below 1"),
        (lambda: nm.check_integer(1.5, "k", low=1), "k: expected a positive integer"),
        (lambda: nm.check_integer(True, "k", low=0), "k: expected a non-negative integer"),
        (lambda: nm.check_integer(7, "k", low=1, high=6), r"k: expected an integer in \[1, 6\]"),
        (lambda: nm.check_radii([1.0, -1.0]), "radii: expected a non-empty list of finite positive radii"),
        (lambda: nm.complex_scalar("1", "lam"), r"lam: expected a number \(a real or complex number\)"),
        (lambda: nm.complex_scalar(np.ones(2), "lam"), "lam: expected a scalar"),
        (lambda: nm.complex_scalar(complex(1, np.inf), "lam"), "lam: expected a finite number"),
        (lambda: nm.complex_points([[1.0]], "s"), "s: expected a scalar or a 1-D array"),
        (lambda: nm.complex_points([], "s"), "s: expected at least one point"),
        (lambda: nm.complex_points([1.0, np.nan], "s"), "s: must be finite; entry 1"),
        (lambda: pinlin.linearization.system.check_system(np.eye(2)), "sys: expected a pinlin.LinearizedSystem"),
        (lambda: nm.check_uncertainty(-0.1), r"uncertainty: expected a relative uncertainty in \[0, 1\), got -0.1"),
        (lambda: nm.check_uncertainty("1e-3", "u"), r"u: expected a relative uncertainty in \[0, 1\), got '1e-3'"),
    ],
)
def test_checks_name_the_parameter(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_checks_return_canonical_values():
    assert nm.check_tolerance(1, "tol") == 1.0 and nm.check_integer(np.int64(3), "k", low=0) == 3
    assert nm.complex_scalar(np.float64(2.0), "lam") == 2 + 0j
    pts, scalar = nm.complex_points(1.5, "s")
    assert scalar and pts.dtype == complex and pts.tolist() == [1.5 + 0j]
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(3), None, np.eye(3))
    assert nm.dof_indices(sys, None, "dofs").tolist() == [0, 1, 2]
    assert nm.dof_indices(sys, [2, sys.dof_names[0]], "dofs").tolist() == [2, 0]
    with pytest.raises(ParameterError, match="dofs: unknown coordinate 'nope'"):
        nm.dof_indices(sys, "nope", "dofs")
    with pytest.raises(ParameterError, match="dofs: index 3 out of range"):
        nm.dof_indices(sys, 3, "dofs")


def test_rank_tolerances_are_two_named_decisions():
    assert nm.JORDAN_RANK_TOL == pinlin.spectral.RANK_TOL == 1e-8
    assert nm.ADJUGATE_RANK_TOL == 1e-12
    A = np.diag([1.0, 1e-9, 0.0])
    assert nm.kernel_dimension(A, 1e-8) == 2 and nm.kernel_dimension(A, 1e-12) == 1
    B = nm.null_basis(A, 1e-8)
    assert B.shape == (3, 2)
    assert_allclose(B.conj().T @ B, np.eye(2), atol=1e-15)
    assert_allclose(A @ B, 0.0, atol=1e-9)
