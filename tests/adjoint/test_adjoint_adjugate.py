"""The adjugate adj L(lam) (theory: adjoint).

References: cofactors as 50-digit mpmath determinants, LU determinants
(numpy), the spectral module's eigenvectors (a QEP solver) and hand algebra.
"""

import math
import pickle

import mpmath as mp
import numpy as np
import pytest
from numpy.polynomial import Polynomial
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import adj_entry_mp, adj_mp, angle, det_mp, poly_coefficients_mp, random_system
from pinlin.adjoint import (
    AdjugateMatrix,
    adjugate,
    adjugate_polynomial,
    adjugate_residual,
    adjugate_taylor,
)

SIZES = [1, 2, 3, 5, 8, 10]


def _residual(L, A, p):
    """||L A - p I|| / (||L|| ||A||), both orders, computed here from the definition."""
    eye = p * np.eye(L.shape[0])
    r = max(np.linalg.norm(L @ A - eye), np.linalg.norm(A @ L - eye))
    return r / (np.linalg.norm(L) * np.linalg.norm(A))


@pytest.mark.parametrize("n", SIZES)
def test_identity_at_ordinary_points(n):
    rng = np.random.default_rng(10 + n)
    sys = random_system(rng, n)
    for lam in rng.standard_normal(3) + 1j * rng.standard_normal(3):
        A = pinlin.adjugate(sys, lam)
        L = sys.dynamic_stiffness(lam)
        p = np.linalg.det(L)  # LU: not the SVD the adjugate uses
        assert _residual(L, np.asarray(A), p) < 1e-12
        assert A.residual < 1e-12
        assert_allclose(A.det, p, rtol=1e-12)


@pytest.mark.parametrize("n", [2, 3, 5])
def test_matches_50_digit_cofactors(n):
    rng = np.random.default_rng(20 + n)
    sys = random_system(rng, n)
    for lam in (0.7 - 0.2j, -1.3 + 2.1j):
        ref = adj_mp(sys, lam)
        A = adjugate(sys, lam)
        assert_allclose(np.asarray(A), ref, rtol=0, atol=1e-13 * np.linalg.norm(ref))
        assert_allclose(A.det, det_mp(sys, lam), rtol=1e-13)


@pytest.mark.parametrize("n", SIZES)
def test_at_eigenvalues_rank_one_with_spectral_eigenvectors(n):
    rng = np.random.default_rng(30 + n)
    sys = random_system(rng, n)
    modes = pinlin.modal_analysis(sys)
    for k, lam in enumerate(modes.eigenvalues):
        A = adjugate(sys, lam)
        L = sys.dynamic_stiffness(lam)
        plain = np.asarray(A)
        assert A.residual < 1e-12
        if n == 1:  # adj of a 1 x 1 matrix is [[1]]; L(lam_k) itself is rounding noise
            assert_allclose(plain, [[1.0]], atol=0)
            continue
        assert _residual(L, plain, det_mp(sys, lam)) < 1e-12
        sv = np.linalg.svd(plain, compute_uv=False)
        assert sv[1] / sv[0] < 1e-10  # rank one (paper Sec. 8)
        assert A.rank_one_defect < 1e-10
        col = plain[:, np.argmax(np.linalg.norm(plain, axis=0))]
        row = plain[np.argmax(np.linalg.norm(plain, axis=1)), :]
        assert angle(col, modes.right[:, k]) < 1e-10
        assert angle(row, modes.left[:, k]) < 1e-10


@pytest.mark.parametrize("n", [2, 4])
def test_trace_formula_for_p_prime(n):
    """p'(lam_k) = trace(adj L(lam_k) L'(lam_k)) against the derivative of the 50-digit polynomial."""
    rng = np.random.default_rng(40 + n)
    sys = random_system(rng, n)
    dp = Polynomial(poly_coefficients_mp(sys)).deriv()
    for lam in pinlin.modal_analysis(sys).eigenvalues:
        A = np.asarray(adjugate(sys, lam))
        value = np.trace(A @ (2 * lam * sys.M + sys.C))
        assert_allclose(value, dp(lam), rtol=1e-11)


def test_exactly_singular_points():
    """M = K = I: L(i) = 0 exactly, so adj L(i) = 0 for n >= 2 and [[1]] for n = 1."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(3), None, np.eye(3))
    A = adjugate(sys, 1j)
    assert_allclose(np.asarray(A), np.zeros((3, 3)), atol=0)
    assert A.det == 0 and A.residual == 0
    sys1 = pinlin.LinearizedSystem.from_matrices([[1.0]], None, [[1.0]])
    assert_allclose(np.asarray(adjugate(sys1, 1j)), [[1.0]], atol=0)
    # rank n - 2: L(i) = diag(0, 0, 3) for K = diag(1, 1, 4): adj is exactly zero
    sys2 = pinlin.LinearizedSystem.from_matrices(np.eye(3), None, np.diag([1.0, 1.0, 4.0]))
    assert_allclose(np.asarray(adjugate(sys2, 1j)), np.zeros((3, 3)), atol=1e-15)


def test_result_array_metadata_is_not_inherited():
    sys = random_system(np.random.default_rng(1), 3)
    A = adjugate(sys, 0.5)
    assert isinstance(A, AdjugateMatrix) and A.shape == (3, 3) and A.dtype == complex
    assert A.elapsed >= 0 and A.lam == 0.5 and A.log_scale == 0.0
    # a slice says nothing about the residual: it is a plain array (pinlin.results.ResultArray)
    assert type(A[0]) is np.ndarray and not hasattr(A[0], "residual")
    assert A.error == A.residual and not A.flags.writeable
    assert type(A + 1) is np.ndarray and type(A @ A) is np.ndarray
    back = pickle.loads(pickle.dumps(A))
    assert type(back) is np.ndarray
    assert_allclose(back, np.asarray(A), atol=0)


def test_huge_adjugate_raises_instead_of_overflowing():
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(40) * 1e20, None, np.eye(40))
    with pytest.raises(pinlin.ComputationError, match="overflows"):
        adjugate(sys, 1.0)
    # L(1) = (1e20 + 1) I: adj = (1e20 + 1)^39 I, det = (1e20 + 1)^40, both beyond double range
    A = adjugate(sys, 1.0, scaled=True)
    assert_allclose(A.log_scale, 39 * np.log(1e20 + 1), rtol=1e-15)
    assert_allclose(np.asarray(A), np.eye(40), rtol=0, atol=1e-14)
    assert_allclose(A.log_abs_det, 40 * np.log(1e20 + 1), rtol=1e-15)
    assert_allclose(A.det, 1e20 + 1, rtol=1e-12)  # det / exp(log_scale), through sums of 40 logs


def test_adjugate_residual_helper_against_hand_example():
    L = np.array([[2.0, 1.0], [1.0, 3.0]])
    A = np.array([[3.0, -1.0], [-1.0, 2.0]])  # adj by hand
    assert adjugate_residual(L, A, 5.0) < 1e-15
    assert adjugate_residual(L, A, 6.0) > 0.05
    with pytest.raises(pinlin.ParameterError, match="same shape"):
        adjugate_residual(L, np.eye(3), 5.0)


# ---------------------------------------------------------------------------- matrix polynomial


@pytest.mark.parametrize("n", [1, 2, 4])
def test_matrix_polynomial_coefficients(n):
    rng = np.random.default_rng(50 + n)
    sys = random_system(rng, n)
    P = adjugate_polynomial(sys)
    assert P.degree == 2 * n - 2 and P.coef.shape == (2 * n - 1, n, n)
    eye_sys = pinlin.LinearizedSystem.from_matrices(sys.M, None, None)
    assert_allclose(P.coef[-1], adj_mp(eye_sys, 1.0).real, rtol=0, atol=1e-13 * np.linalg.norm(P.coef[-1]))  # adj M
    assert_allclose(P.coef[0], adj_mp(sys, 0.0).real, rtol=0, atol=1e-13 * np.linalg.norm(P.coef[0]))  # adj K
    for lam in (0.3 + 0.4j, -2.0 + 1.0j):
        ref = adj_mp(sys, lam)
        assert_allclose(P(lam), ref, rtol=0, atol=1e-12 * np.linalg.norm(ref))
    assert 0 < P.error < 1e-13 and P.elapsed > 0


def test_matrix_polynomial_derivative_against_mpmath():
    sys = random_system(np.random.default_rng(61), 3)
    P = adjugate_polynomial(sys)
    lam = 0.4 - 0.9j
    with mp.workdps(50):
        for m in (1, 2):
            ref = np.array(
                [
                    [complex(mp.diff(lambda z, r=r, c=c: adj_entry_mp(sys, z, r, c), mp.mpc(lam), m)) for c in range(3)]
                    for r in range(3)
                ]
            )
            assert_allclose(P.deriv(m)(lam), ref, rtol=0, atol=1e-9 * np.linalg.norm(ref))
    assert P.deriv(99).coef.shape == (1, 3, 3) and not np.any(P.deriv(99).coef)


def test_taylor_coefficients_at_an_eigenvalue_match_hand_derivatives():
    """M = I, C = 0, K = [[3, 1], [-1, 1]]: adj L = [[lam^2 + 1, -1], [1, lam^2 + 3]] by hand."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])
    lam0 = 1j * math.sqrt(2)
    T = adjugate_taylor(sys, lam0, order=3)
    assert_allclose(T.coef[0], [[lam0**2 + 1, -1], [1, lam0**2 + 3]], rtol=0, atol=1e-14)
    assert_allclose(T.derivative(1), 2 * lam0 * np.eye(2), rtol=0, atol=1e-13)
    assert_allclose(T.derivative(2), 2 * np.eye(2), rtol=0, atol=1e-13)
    assert_allclose(T.coef[3], np.zeros((2, 2)), atol=0)  # beyond degree 2n - 2 = 2: exactly zero
    assert np.all(T.relative_error[:3] < 1e-13)


def test_taylor_against_mpmath_at_random_eigenvalue():
    sys = random_system(np.random.default_rng(71), 3)
    lam = pinlin.modal_analysis(sys).eigenvalues[1]
    T = adjugate_taylor(sys, lam, order=2)
    with mp.workdps(50):
        for j in (1, 2):
            ref = np.array(
                [
                    [complex(mp.diff(lambda z, r=r, c=c: adj_entry_mp(sys, z, r, c), mp.mpc(lam), j)) for c in range(3)]
                    for r in range(3)
                ]
            )
            assert_allclose(T.derivative(j), ref, rtol=0, atol=1e-10 * np.linalg.norm(ref))
            assert T.coef_error[j] * math.factorial(j) < 1e-10 * np.linalg.norm(ref)


# ---------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("lam", "match"),
    [(np.inf, "finite"), (complex(np.nan, 1.0), "finite"), (np.ones(2), "scalar"), ("1.0", "complex number")],
)
def test_bad_lambda(lam, match):
    sys = random_system(np.random.default_rng(2), 2)
    with pytest.raises(pinlin.ParameterError, match=match):
        adjugate(sys, lam)
    with pytest.raises(pinlin.ParameterError, match=match):
        adjugate_taylor(sys, lam)


def test_bad_arguments():
    sys = random_system(np.random.default_rng(3), 2)
    with pytest.raises(pinlin.ParameterError, match="LinearizedSystem"):
        adjugate("not a system", 1.0)
    with pytest.raises(pinlin.ParameterError, match="order"):
        adjugate_taylor(sys, 1.0, order=-1)
    with pytest.raises(pinlin.ParameterError, match="radii"):
        adjugate_polynomial(sys, radii=[0.0])
    with pytest.raises(pinlin.ParameterError, match="n_points"):
        adjugate_polynomial(sys, n_points=2)
    P = adjugate_polynomial(sys)
    with pytest.raises(pinlin.ParameterError, match="m"):
        P.deriv(-1)
    with pytest.raises(pinlin.ParameterError, match="lam"):
        P(np.nan)
    with pytest.raises(pinlin.ParameterError, match="j"):
        adjugate_taylor(sys, 1.0, order=1).derivative(5)
