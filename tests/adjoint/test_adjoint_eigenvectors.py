"""Eigenvectors, p'(lam_k) and Jordan chains read off the adjugate (paper Sec. 8, 9).

References: the spectral module (QEP solver), 50-digit polynomial coefficients,
and hand-derived vectors for M = I, K = [[3, 1], [-1, 1]] (a double root at
i sqrt 2 with one Jordan chain of length 2: p = (lam^2 + 2)^2).
"""

import math

import numpy as np
import pytest
from numpy.polynomial import Polynomial
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import angle, chain, poly_coefficients_mp, random_system
from pinlin.adjoint import adjugate_chain, adjugate_eigenvectors, chain_residual

JORDAN = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])
LAM_J = 1j * math.sqrt(2)


@pytest.mark.parametrize("n", [2, 5])
def test_simple_roots_against_spectral_module(n):
    rng = np.random.default_rng(500 + n)
    sys = random_system(rng, n)
    modes = pinlin.modal_analysis(sys)
    dp = Polynomial(poly_coefficients_mp(sys)).deriv()
    for k, lam in enumerate(modes.eigenvalues):
        e = pinlin.adjugate_eigenvectors(sys, lam)
        assert e.is_simple
        assert angle(e.right, modes.right[:, k]) < 1e-10
        # x y^T with y^T L' x = 1 is invariant under rescaling x: compare it as a whole
        ref = np.outer(modes.right[:, k], modes.left[:, k])
        assert_allclose(np.outer(e.right, e.left), ref, rtol=0, atol=1e-10 * np.linalg.norm(ref))
        assert_allclose(e.left @ (2 * lam * sys.M + sys.C) @ e.right, 1.0, rtol=1e-12)
        assert_allclose(e.derivative, dp(lam), rtol=1e-10)
        assert_allclose(e.log10_abs_derivative, np.log10(abs(dp(lam))), rtol=1e-12)
        assert_allclose(1 / e.simplicity, modes.condition[k], rtol=1e-8)  # theory: adjoint's kappa
        assert e.backward_error_right < 1e-14 and e.backward_error_left < 1e-14
        assert e.adjugate_residual < 1e-13


def test_large_badly_scaled_system_beyond_double_range():
    """100-link chain: adj L(lam_k) is about 1e480 at the fastest mode, its direction is not."""
    sys = chain(100)
    modes = pinlin.modal_analysis(sys)
    k = int(np.argmax(np.abs(modes.eigenvalues)))
    with pytest.raises(pinlin.ComputationError, match="overflows"):
        pinlin.adjugate(sys, modes.eigenvalues[k])
    A = pinlin.adjugate(sys, modes.eigenvalues[k], scaled=True)
    assert A.log_scale / np.log(10) > 300 and A.residual < 1e-14
    col = np.asarray(A)[:, np.argmax(np.linalg.norm(A, axis=0))]
    lam = modes.eigenvalues[k]
    weight = abs(lam) ** 2 * np.linalg.norm(sys.M) + abs(lam) * np.linalg.norm(sys.C) + np.linalg.norm(sys.K)
    assert np.linalg.norm(sys.dynamic_stiffness(lam) @ col) / (weight * np.linalg.norm(col)) < 1e-14
    # (the eigenvector itself is ill-conditioned here, mass ratio 1e8: the adjugate's column and
    # the spectral module's differ by 1e-5 in angle with both backward errors at 1e-16)
    e = adjugate_eigenvectors(sys, modes.eigenvalues[k])
    assert e.derivative is None and e.log10_abs_derivative > 300
    assert e.is_simple and e.backward_error_right < 1e-14 and e.backward_error_left < 1e-14
    assert_allclose(1 / e.simplicity, modes.condition[k], rtol=1e-6)
    # (2 lam M + C) x cancels to 1e-4 of its terms here: rounding of about kappa eps remains
    assert_allclose(e.left @ (2 * e.eigenvalue * sys.M + sys.C) @ e.right, 1.0, rtol=1e-8)


def test_defective_root_is_reported_not_simple():
    e = adjugate_eigenvectors(JORDAN, LAM_J)
    assert not e.is_simple
    assert e.simplicity < 1e-12
    assert abs(e.derivative) < 1e-12  # p'(lam0) = 0 at a double root
    # by hand: L(i sqrt 2) = [[1, 1], [-1, -1]], right null vector [1, -1], left [1, 1]
    assert angle(e.right, np.array([1.0, -1.0])) < 1e-14
    assert angle(e.left, np.array([1.0, 1.0])) < 1e-14
    assert_allclose(np.linalg.norm(e.left), 1.0, rtol=1e-15)


def test_chain_from_adjugate_derivatives_by_hand():
    """x0 = adj L(lam0) e_1 / ||.|| = [-1, 1]/sqrt 2, x1 = adj L'(lam0) e_1 / ||.|| = [2i, 0]."""
    ch = adjugate_chain(JORDAN, LAM_J, 2)
    assert len(ch.vectors) == 2
    assert_allclose(ch.vectors[0], np.array([-1.0, 1.0]) / math.sqrt(2), rtol=0, atol=1e-15)
    assert_allclose(ch.vectors[1], [2j, 0.0], rtol=0, atol=1e-13)
    # the chain equations, written out here: L x0 = 0, L x1 + L' x0 = 0
    L = JORDAN.dynamic_stiffness(LAM_J)
    dL = 2 * LAM_J * JORDAN.M
    assert_allclose(L @ ch.vectors[0], 0, atol=1e-15)
    assert_allclose(L @ ch.vectors[1] + dL @ ch.vectors[0], 0, atol=1e-13)
    assert ch.residual < 1e-14
    assert chain_residual(JORDAN, LAM_J, [np.array([1.0, 0.0])]) > 0.1  # not an eigenvector


def test_chain_when_the_adjugate_vanishes():
    """M = K = I (n = 2): lam = i is a semisimple double root, adj L(i) = 0 and adj L'(i) = 2i I."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    ch = adjugate_chain(sys, 1j, 2)
    assert len(ch.vectors) == 1
    assert_allclose(sys.dynamic_stiffness(1j) @ ch.vectors[0], 0, atol=0)
    assert_allclose(np.linalg.norm(ch.vectors[0]), 1.0, rtol=1e-14)


def test_errors():
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    with pytest.raises(pinlin.NotSimpleError, match="rank one") as info:
        adjugate_eigenvectors(sys, 1j)
    assert info.value.lam == 1j
    with pytest.raises(pinlin.NotAnEigenvalueError, match="not an eigenvalue") as info:
        adjugate_eigenvectors(JORDAN, 0.5)
    assert info.value.distance > 0.1
    with pytest.raises(pinlin.ParameterError, match="eigenvalue_tol"):
        adjugate_eigenvectors(JORDAN, LAM_J, eigenvalue_tol=-1.0)
    with pytest.raises(pinlin.ParameterError, match="multiplicity"):
        adjugate_chain(JORDAN, LAM_J, 0)
    with pytest.raises(pinlin.ParameterError, match="multiplicity"):
        adjugate_chain(JORDAN, LAM_J, 5)
    with pytest.raises(pinlin.ParameterError, match="finite"):
        adjugate_chain(JORDAN, complex(np.nan), 2)
    with pytest.raises(pinlin.NotSimpleError, match="vanish"):
        # rank n - 2 with n = 3 and a root of multiplicity 2: adj and adj' vanish at lam = i
        adjugate_chain(pinlin.LinearizedSystem.from_matrices(np.eye(3), None, np.eye(3)), 1j, 2)
