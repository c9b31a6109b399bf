"""Every error figure of the adjoint results, tested from both sides (theory: adjoint, error figures).

A figure checked only from above ("residual < 1e-12") passes when it is
reported as 0.  Each figure here is compared with its true value -- residuals
evaluated exactly in mpmath (50 digits) for the very arrays returned, true
coefficient errors against mpmath coefficients, closed forms -- so that it must
be positive where the truth is and within a stated factor of it:

- the adjugate's residual: within a factor 2 of the exact residual of the returned (adj L, p);
- the coefficient error bounds of p(lam), of adj L as a polynomial and of its Taylor coefficients:
  bounds (at least the true error) and at most 200 times max(true error, eps |coefficient|);
- the eigenvector backward errors and chain residuals from the adjugate: the exact ones, to 1e-6;
- the defect of check_free_response: the closed form eps / sqrt(1 + eps^2).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import DPS, L_mp, adj_entry_mp, poly_coefficients_mp, random_system
from pinlin.adjoint import (
    adjugate_chain,
    adjugate_eigenvectors,
    adjugate_polynomial,
    adjugate_residual,
    adjugate_taylor,
    characteristic_differential_equation,
    check_free_response,
)

EPS = np.finfo(float).eps
#: Measured coefficient error bounds exceed the true errors (floored at eps |c|) by 3 to 80 times:
#: the circle fits measure their noise on the extra points, a pessimistic but honest estimate.
BOUND_FACTOR = 200


def _mp(A):
    return mp.matrix([[mp.mpc(complex(z).real, complex(z).imag) for z in row] for row in np.atleast_2d(A)])


def _fro(A):
    return mp.sqrt(sum(abs(A[i, j]) ** 2 for i in range(A.rows) for j in range(A.cols)))


def exact_adjugate_residual(sys, lam, A, p) -> float:
    """max(||L A - p I||, ||A L - p I||) / (||L|| ||A||) of the given A and p, evaluated exactly."""
    with mp.workdps(DPS):
        L, Am = L_mp(sys, lam), _mp(A)
        pI = mp.mpc(complex(p).real, complex(p).imag) * mp.eye(sys.n)
        return float(max(_fro(L * Am - pI), _fro(Am * L - pI)) / (_fro(L) * _fro(Am)))


@pytest.mark.parametrize("seed", range(5))
def test_adjugate_residual_is_the_exact_residual_within_a_factor_2(seed):
    rng = np.random.default_rng(seed)
    sys = random_system(rng, int(rng.integers(2, 6)))
    lam = complex(rng.normal(), rng.normal())
    A = pinlin.adjugate(sys, lam)
    exact = exact_adjugate_residual(sys, lam, np.asarray(A), A.det)
    assert exact > 0 and A.residual > 0
    assert 0.5 * exact <= A.residual <= 2 * exact


def test_adjugate_residual_function_on_a_wrong_adjugate():
    sys = random_system(np.random.default_rng(7), 3)
    lam = 0.3 + 0.8j
    A = np.asarray(pinlin.adjugate(sys, lam))
    p = pinlin.adjugate(sys, lam).det
    wrong = A + 1e-7 * np.linalg.norm(A) * np.random.default_rng(8).standard_normal(A.shape)
    got = adjugate_residual(sys.dynamic_stiffness(lam), wrong, p)
    assert_allclose(got, exact_adjugate_residual(sys, lam, wrong, p), rtol=1e-7)


def test_characteristic_polynomial_error_bounds_from_both_sides():
    for seed in range(3):
        rng = np.random.default_rng(seed)
        sys = random_system(rng, int(rng.integers(2, 5)))
        p = pinlin.characteristic_polynomial(sys)
        ref = poly_coefficients_mp(sys)
        true = np.abs(p.coef - ref)
        assert np.all(true <= p.coef_error)  # a bound
        assert np.all(p.coef_error <= BOUND_FACTOR * np.maximum(true, EPS * np.abs(ref)))  # not a vacuous one
        normwise = np.linalg.norm(true) / np.linalg.norm(ref)
        assert normwise <= p.error <= BOUND_FACTOR * max(normwise, EPS)


def _mp_adjugate_coefficients(sys) -> np.ndarray:
    """A_k of adj L(lam) = sum_k A_k lam^k, interpolated exactly from mpmath cofactors at 2n - 1 nodes."""
    n, deg = sys.n, 2 * sys.n - 2
    out = np.zeros((deg + 1, n, n))
    with mp.workdps(DPS):
        nodes = [mp.mpf(j) - mp.mpf(deg) / 2 for j in range(deg + 1)]
        V = mp.matrix([[x**k for k in range(deg + 1)] for x in nodes])
        for r in range(n):
            for c in range(n):
                sol = mp.lu_solve(V, mp.matrix([adj_entry_mp(sys, x, r, c).real for x in nodes]))
                out[:, r, c] = [float(sol[k]) for k in range(deg + 1)]
    return out


def test_adjugate_polynomial_and_taylor_error_bounds_from_both_sides():
    for seed in range(2):
        sys = random_system(np.random.default_rng(seed), 3)
        P = adjugate_polynomial(sys)
        ref = _mp_adjugate_coefficients(sys)
        k = ref.shape[0]
        true = np.linalg.norm((P.coef - ref).reshape(k, -1), axis=1)
        size = np.linalg.norm(ref.reshape(k, -1), axis=1)
        assert np.all(true <= P.coef_error) and np.all(P.coef_error <= BOUND_FACTOR * np.maximum(true, EPS * size))
        lam0 = 0.3 - 0.2j
        T = adjugate_taylor(sys, lam0, 2)
        with mp.workdps(DPS):
            z = mp.mpc(lam0.real, lam0.imag)
            tc = np.array([[[complex(mp.diff(lambda x, s=sys, r=r, c=c: adj_entry_mp(s, x, r, c), z, j)
                                     / math.factorial(j)) for c in range(3)] for r in range(3)] for j in range(3)])
        trueT = np.linalg.norm((T.coef - tc).reshape(3, -1), axis=1)
        sizeT = np.linalg.norm(tc.reshape(3, -1), axis=1)
        assert np.all(trueT <= T.coef_error) and np.all(T.coef_error <= BOUND_FACTOR * np.maximum(trueT, EPS * sizeT))


def _exact_eta(sys, lam, x, left=False) -> float:
    with mp.workdps(DPS):
        L = L_mp(sys, lam)
        v = _mp(np.asarray(x)[:, None])
        r = L.T * v if left else L * v
        w = abs(mp.mpc(lam.real, lam.imag)) ** 2 * np.linalg.norm(sys.M) + abs(lam) * np.linalg.norm(sys.C)
        w += np.linalg.norm(sys.K)
        return float(_fro(r) / (w * _fro(v)))


def test_adjugate_eigenvector_backward_errors_are_the_exact_ones():
    """At a point 1e-10 (relative) off the eigenvalue the vectors have eta of that size: reported exactly."""
    sys = random_system(np.random.default_rng(11), 3)
    lam = pinlin.modal_analysis(sys).eigenvalues[0]
    for z, big in ((lam, False), (lam * (1 + 1e-10), True)):
        e = adjugate_eigenvectors(sys, z)
        exact_r, exact_l = _exact_eta(sys, z, e.right), _exact_eta(sys, z, e.left, left=True)
        if big:
            assert exact_r > 1e-12 and exact_l > 1e-12
            assert_allclose([e.backward_error_right, e.backward_error_left], [exact_r, exact_l], rtol=1e-6)
        else:
            assert abs(e.backward_error_right - exact_r) <= EPS and abs(e.backward_error_left - exact_l) <= EPS
        assert e.error == max(e.backward_error_right, e.backward_error_left)


def test_adjugate_chain_residual_is_the_exact_one():
    """The double root i sqrt 2 of M = I, K = [[3, 1], [-1, 1]], and a point 1e-9 off it."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])
    for lam0 in (1j * math.sqrt(2), 1j * math.sqrt(2) * (1 + 1e-9)):
        ch = adjugate_chain(sys, lam0, 2)
        x0, x1 = ch.vectors
        with mp.workdps(DPS):
            z = mp.mpc(lam0.real, lam0.imag)
            L = L_mp(sys, lam0)
            dL = 2 * z * mp.eye(2)
            v0, v1 = _mp(x0[:, None]), _mp(x1[:, None])
            w0 = abs(z) ** 2 * math.sqrt(2) + np.linalg.norm(sys.K)
            w1 = 2 * abs(z) * math.sqrt(2)
            exact = max(float(_fro(L * v0) / (w0 * _fro(v0))),
                        float(_fro(L * v1 + dL * v0) / (w0 * _fro(v1) + w1 * _fro(v0))))
        assert abs(ch.residual - exact) <= max(1e-6 * exact, EPS) and ch.error == ch.residual
        if lam0.imag != math.sqrt(2):
            assert exact > 1e-12  # the off point: a residual far above rounding, reported


def test_free_response_defect_is_the_closed_form():
    """x'' + 4 x = 0: cos 2t is a free solution; eps cos 5t lies outside the span of exp(+-2it) and, on
    whole periods sampled uniformly, is orthogonal to it: the relative defect is eps / sqrt(1 + eps^2)."""
    sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.0]], [[4.0]])
    t = np.linspace(0.0, 2 * np.pi, 64, endpoint=False)
    for eps in (1e-3, 1e-6):
        x = (np.cos(2 * t) + eps * np.cos(5 * t))[:, None]
        chk = check_free_response(sys, t, x, roots=[2j, -2j])
        assert_allclose(chk.error, eps / math.sqrt(1 + eps * eps), rtol=1e-8)
        assert chk.passed == (chk.error <= chk.tol)
    cde = characteristic_differential_equation(sys)
    assert cde.error == cde.polynomial.error > 0
