"""The result convention for the adjoint results.

CharacteristicPolynomial, AdjugateMatrix, AdjugatePolynomial, AdjugateTaylor,
AdjugateEigenvectors, AdjugateChain, CharacteristicDifferentialEquation and
CDECheck each carry ``elapsed`` [s], ``method``, ``error`` with the meaning
their docstring states (recomputed here from the definition, against mpmath
where a reference value is involved) and a JSON-serializable ``to_dict()``.
"""

from __future__ import annotations

import json
import math

import numpy as np
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import adj_mp, det_mp, double_pendulum, poly_coefficients_mp, random_system
from pinlin.adjoint import (
    AdjugateChain,
    AdjugateEigenvectors,
    AdjugatePolynomial,
    AdjugateTaylor,
    CDECheck,
    CharacteristicDifferentialEquation,
    adjugate_chain,
    adjugate_eigenvectors,
    adjugate_polynomial,
    adjugate_taylor,
    characteristic_differential_equation,
    check_free_response,
)

EPS = np.finfo(float).eps
JORDAN = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])
LAM_J = 1j * math.sqrt(2)  # a double root with one chain of length 2 (see test_adjoint_eigenvectors)


def _complex(d):
    return np.asarray(d["re"], dtype=float) + 1j * np.asarray(d["im"], dtype=float)


def _convention(r, type_name: str) -> dict:
    """elapsed, method, error present; one-line repr; to_dict through JSON and back."""
    assert isinstance(r.elapsed, float) and r.elapsed >= 0
    assert isinstance(r.method, str) and r.method
    assert isinstance(r.error, float)
    text = repr(r)
    assert "\n" not in text and len(text) < 240
    d = json.loads(json.dumps(r.to_dict()))
    assert d["type"] == type_name and d["method"] == str(r.method) and d["elapsed"] == r.elapsed
    return d


def test_characteristic_polynomial():
    sys = double_pendulum()
    p = pinlin.characteristic_polynomial(sys)
    d = _convention(p, "CharacteristicPolynomial")
    assert p.error == np.linalg.norm(p.coef_error) / np.linalg.norm(p.coef)
    # the coefficients are within their stated bounds of the mpmath ones
    ref = poly_coefficients_mp(sys)
    assert np.all(np.abs(p.coef - ref) <= p.coef_error)
    assert d["coef"] == p.coef.tolist() and d["coef_error"] == p.coef_error.tolist() and d["error"] == p.error
    assert repr(p.deriv()).endswith("derived: no error figures)")


def test_adjugate_matrix_error_is_its_residual():
    sys = random_system(np.random.default_rng(3), 3)
    lam = 0.4 + 0.7j
    A = pinlin.adjugate(sys, lam)
    d = _convention(A, "AdjugateMatrix")
    L = sys.dynamic_stiffness(lam)
    p = det_mp(sys, lam)
    eye = p * np.eye(3)
    ref = max(np.linalg.norm(L @ A - eye), np.linalg.norm(A @ L - eye)) / (np.linalg.norm(L) * np.linalg.norm(A))
    assert A.error == A.residual
    assert_allclose(A.error, ref, rtol=0, atol=8 * EPS)
    assert_allclose(_complex(d["values"]), adj_mp(sys, lam), rtol=1e-13)
    assert d["residual"] == A.residual and d["lam"] == {"re": 0.4, "im": 0.7}


def test_adjugate_polynomial_and_taylor_errors_are_normwise_relative():
    sys = random_system(np.random.default_rng(4), 2)
    P = adjugate_polynomial(sys)
    assert isinstance(P, AdjugatePolynomial)
    d = _convention(P, "AdjugatePolynomial")
    assert P.error == np.linalg.norm(P.coef_error) / np.linalg.norm(P.coef)
    assert 0 < P.error < 1e-13
    assert_allclose(P(0.3 - 0.2j), adj_mp(sys, 0.3 - 0.2j), rtol=1e-13)
    assert np.asarray(d["coef"]).shape == P.coef.shape
    T = adjugate_taylor(sys, 0.3 - 0.2j, 2)
    assert isinstance(T, AdjugateTaylor)
    _convention(T, "AdjugateTaylor")
    assert T.error == np.linalg.norm(T.coef_error) / np.linalg.norm(T.coef)
    assert_allclose(T.coef[0], adj_mp(sys, 0.3 - 0.2j), rtol=1e-12)


def test_adjugate_eigenvectors_error_is_the_larger_backward_error():
    sys = double_pendulum()
    lam = pinlin.modal_analysis(sys).eigenvalues[0]
    e = adjugate_eigenvectors(sys, lam)
    assert isinstance(e, AdjugateEigenvectors)
    d = _convention(e, "AdjugateEigenvectors")
    L = sys.dynamic_stiffness(lam)
    w = abs(lam) ** 2 * np.linalg.norm(sys.M) + abs(lam) * np.linalg.norm(sys.C) + np.linalg.norm(sys.K)
    eta_r = np.linalg.norm(L @ e.right) / (w * np.linalg.norm(e.right))
    eta_l = np.linalg.norm(e.left @ L) / (w * np.linalg.norm(e.left))
    assert e.error == max(e.backward_error_right, e.backward_error_left)
    assert_allclose(e.error, max(eta_r, eta_l), rtol=0, atol=4 * EPS)
    assert_allclose(_complex(d["right"]), e.right, rtol=0, atol=0)


def test_adjugate_chain_error_is_its_chain_residual():
    ch = adjugate_chain(JORDAN, LAM_J, 2)
    assert isinstance(ch, AdjugateChain)
    _convention(ch, "AdjugateChain")
    x0, x1 = ch.vectors
    M, K = JORDAN.M, JORDAN.K
    L = LAM_J**2 * M + K
    dL = 2 * LAM_J * M
    w0 = abs(LAM_J) ** 2 * np.linalg.norm(M) + np.linalg.norm(K)
    w1 = 2 * abs(LAM_J) * np.linalg.norm(M)
    rho = max(
        np.linalg.norm(L @ x0) / (w0 * np.linalg.norm(x0)),
        np.linalg.norm(L @ x1 + dL @ x0) / (w0 * np.linalg.norm(x1) + w1 * np.linalg.norm(x0)),
    )
    assert ch.error == ch.residual
    assert_allclose(ch.error, rho, rtol=0, atol=4 * EPS)


def test_characteristic_differential_equation_and_its_check():
    sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])
    cde = characteristic_differential_equation(sys)
    assert isinstance(cde, CharacteristicDifferentialEquation)
    d = _convention(cde, "CharacteristicDifferentialEquation")
    assert cde.error == cde.polynomial.error and cde.elapsed == cde.polynomial.elapsed
    assert_allclose(d["polynomial"]["coef"], [4.0, 0.2, 1.0], rtol=1e-14)
    # x(t) = exp(-0.1 t) cos(w t), w^2 = 4 - 0.01: an exact free solution
    t = np.linspace(0.0, 5.0, 41)
    w = math.sqrt(4.0 - 0.01)
    x = (np.exp(-0.1 * t) * np.cos(w * t))[:, None]
    chk = check_free_response(sys, t, x)
    assert isinstance(chk, CDECheck)
    dc = _convention(chk, "CDECheck")
    assert chk.error == chk.max_defect and chk.passed and chk.error < 1e-10
    assert "roots of the characteristic polynomial" in chk.method
    assert dc["passed"] is True and dc["max_defect"] == chk.max_defect
