"""The result convention of the frequency-domain results and the one H(s) engine behind them.

Each result is built on a small system; ``json.dumps(to_dict())`` must work, and
``error``, ``method`` and ``elapsed`` must mean what the docstrings say: the
relative defects are recomputed here from M, C, K with numpy (the normwise
backward error ||L X - B|| / (||L|| ||X|| + ||B||), Frobenius norms), and the
three functions built on the engine must give the same numbers.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.frf import ModalExpansion, modal_expansion
from response_cases import json_round_trip, timed

#: M, C, K with every matrix nonzero (gyroscopic and circulatory parts): simple, complex eigenvalues.
DAMPED = pinlin.LinearizedSystem.from_matrices(
    np.diag([2.0, 1.0]), [[0.3, 0.4], [-0.6, 0.2]], [[6.0, -1.6], [-2.4, 3.0]]
)
#: K a Jordan block: double roots with one chain of length 2 each.
JORDAN = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.2 * np.eye(2), [[2.0, 1.0], [0.0, 2.0]])
OMEGA = np.array([0.3, 1.1, 2.5, 4.0])


def _L(sys, s):
    return s * s * np.asarray(sys.M) + s * np.asarray(sys.C) + np.asarray(sys.K)


def _defect(sys, s, X, B):
    """The relative defect of L(s) X = B, Frobenius norms (theory: error figures)."""
    L = _L(sys, s)
    return np.linalg.norm(L @ X - B) / (np.linalg.norm(L) * np.linalg.norm(X) + np.linalg.norm(B))


#: Defects at the rounding level are compared in absolute terms: the order of the floating-point
#: operations (here numpy on L(s), there the engine's products) changes them by a few eps.
ROUNDING = 4 * np.finfo(float).eps


@pytest.mark.parametrize("method", ["direct", "modal"])
def test_flexibility_figures(method):
    s = np.array([0.5j, -0.2 + 1.5j])
    H, wall = timed(lambda: pinlin.flexibility(DAMPED, s, method=method))
    expected = [_defect(DAMPED, sk, np.asarray(H)[k], np.eye(2)) for k, sk in enumerate(s)]
    assert_allclose(H.defects, expected, rtol=0, atol=ROUNDING)
    assert H.error == max(H.defects) and H.error < 1e-15
    assert H.method == method and 0 < H.elapsed <= wall
    data = json_round_trip(H)
    assert_allclose(np.array(data["values"]["re"]) + 1j * np.array(data["values"]["im"]), np.asarray(H), rtol=0)
    assert_allclose(np.array(data["s"]["im"]), s.imag, rtol=0)
    assert data["distance"] is None if method == "direct" else len(data["distance"]) == 2
    assert len(repr(H).splitlines()) == 1 and "error=" in repr(H)


@pytest.mark.parametrize("method", ["direct", "modal"])
def test_frequency_response_figures(method):
    resp, wall = timed(lambda: pinlin.frequency_response(DAMPED, OMEGA, inputs=[1], method=method))
    H = resp.response[:, :, :]  # (outputs, inputs, frequencies)
    expected = [_defect(DAMPED, 1j * w, H[:, :, k], np.eye(2)[:, [1]]) for k, w in enumerate(OMEGA)]
    assert_allclose(resp.defects, expected, rtol=0, atol=ROUNDING)
    assert resp.error == max(resp.defects) and resp.method == method and 0 < resp.elapsed <= wall
    data = json_round_trip(resp)
    assert_allclose(np.array(data["response"]["re"]), resp.response.real, rtol=0)
    assert data["input_names"] == [DAMPED.dof_names[1]]
    unchecked = pinlin.frequency_response(DAMPED, OMEGA, outputs=0, method=method, check=False)
    assert unchecked.error is None and unchecked.defects is None and "unchecked" in repr(unchecked)
    assert json_round_trip(unchecked)["error"] is None


@pytest.mark.parametrize("method", ["direct", "modal"])
def test_harmonic_response_figures(method):
    F = np.array([1.0, 0.5j])
    X, wall = timed(lambda: pinlin.harmonic_response(DAMPED, F, OMEGA, method=method))
    expected = [_defect(DAMPED, 1j * w, np.asarray(X)[k], F) for k, w in enumerate(OMEGA)]
    assert_allclose(X.defects, expected, rtol=0, atol=ROUNDING)
    assert X.error == max(X.defects) and X.method == method and 0 < X.elapsed <= wall
    data = json_round_trip(X)
    assert "modes" not in data  # a back-reference, left out
    assert (data["projection_residual"] is None) == (method == "direct")
    assert_allclose(np.array(data["values"]["re"]), np.asarray(X).real, rtol=0)


def test_engine_norms_and_residuals_against_numpy():
    """The pieces of the defect, on a perturbed X (a residual far above rounding) and at points where the
    terms of ||L(s)|| cancel (M = I, K = 4 I: L(2i) = 0 exactly, L(2i + h) ~ 4i h I)."""
    from pinlin.frf.engine import residuals, stiffness_norms

    rng = np.random.default_rng(3)
    s = np.array([0.5j, -0.2 + 1.5j, 3.0 + 0.0j])
    B = rng.standard_normal((2, 3)) + 1j * rng.standard_normal((2, 3))
    X = rng.standard_normal((3, 2, 3)) + 1j * rng.standard_normal((3, 2, 3))
    expected = [np.linalg.norm(_L(DAMPED, sk) @ X[k] - B) for k, sk in enumerate(s)]
    assert_allclose(residuals(DAMPED, s, X, B), expected, rtol=1e-13)
    assert_allclose(stiffness_norms(DAMPED, s), [np.linalg.norm(_L(DAMPED, sk)) for sk in s], rtol=1e-13)
    osc = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, 4 * np.eye(2))
    near = np.array([2.0j, 2.0j + 1e-9, 2.0j + 1e-4])
    # documented: 1e-3 relative or better (the expansion is used where the cancellation costs less)
    assert_allclose(stiffness_norms(osc, near), [np.linalg.norm(_L(osc, sk)) for sk in near], rtol=1e-3, atol=0)
    assert stiffness_norms(osc, near[:1])[0] == 0.0  # recomputed from L(2i) = 0, not the expansion's rounding


def test_the_three_functions_share_one_engine():
    """H(i w) e_j from flexibility, frequency_response and harmonic_response: the same numbers, per method."""
    e1 = np.array([0.0, 1.0])
    for method in ("direct", "modal"):
        H = pinlin.flexibility(DAMPED, 1j * OMEGA, method=method)
        resp = pinlin.frequency_response(DAMPED, OMEGA, inputs=1, method=method)
        X = pinlin.harmonic_response(DAMPED, e1, OMEGA, method=method)
        assert_allclose(np.moveaxis(resp.response[:, 0, :], 0, -1), np.asarray(H)[:, :, 1], rtol=1e-14, atol=0)
        assert_allclose(np.asarray(X), np.asarray(H)[:, :, 1], rtol=1e-14, atol=0)
    # and the two methods agree (a defective system included: the modal method has Jordan blocks)
    for sys in (DAMPED, JORDAN):
        direct = pinlin.harmonic_response(sys, [1.0, -1.0], OMEGA)
        modal = pinlin.harmonic_response(sys, [1.0, -1.0], OMEGA, method="modal")
        assert_allclose(np.asarray(modal), np.asarray(direct), rtol=1e-12, atol=0)


def test_residues_figures():
    lam = pinlin.modal_analysis(DAMPED).eigenvalues[0]
    res, wall = timed(lambda: pinlin.residues(DAMPED, lam))
    assert "trapezoidal" in res.method and f"{res.n_points} points" in res.method
    assert 0 < res.elapsed <= wall
    # error: the largest bound errors_j / r^j relative to max ||R_j|| / r^j
    powers = res.radius ** np.arange(1, res.multiplicity + 1)
    size = max(np.linalg.norm(R) / p for R, p in zip(res, powers))
    assert res.error == pytest.approx(np.max(res.errors / powers) / size, rel=1e-12)
    data = json_round_trip(res)
    assert len(data["residues"]) == len(res) == 1
    R = np.array(data["residues"][0]["re"]) + 1j * np.array(data["residues"][0]["im"])
    assert_allclose(R, res[0], rtol=0)


def test_modal_expansion_figures():
    exp, wall = timed(lambda: modal_expansion(JORDAN))
    assert isinstance(exp, ModalExpansion) and exp.method == "modal + Jordan chains"
    assert [b.length for b in exp.blocks] == [2, 2] and exp.lam.size == 0
    assert exp.error == max(float(np.max(exp.modes.backward_error)), exp.chain_residual)
    assert exp.error < 1e-10 and 0 < exp.elapsed <= wall
    data = json_round_trip(exp)
    assert "system" not in data and "modes" not in data
    assert len(data["blocks"]) == 2
    simple = modal_expansion(DAMPED)
    assert simple.method == "modal" and simple.is_simple and simple.error == float(np.max(simple.modes.backward_error))


def test_bad_inputs_name_the_parameter():
    with pytest.raises(pinlin.ParameterError, match="tol"):
        pinlin.flexibility(DAMPED, 1.0j, error_tol=-1.0)
    with pytest.raises(pinlin.ParameterError, match="tol"):
        pinlin.frequency_response(DAMPED, OMEGA, error_tol=np.nan)
    with pytest.raises(pinlin.ParameterError, match=r"omega: expected real angular frequencies"):
        pinlin.harmonic_response(DAMPED, [1.0, 0.0], [1.0 + 2.0j])
    with pytest.raises(pinlin.ParameterError, match=r"omega: expected a number or a non-empty 1-D array"):
        pinlin.frequency_response(DAMPED, [])
    with pytest.raises(pinlin.ParameterError, match=r"F: expected 2 complex numbers"):
        pinlin.harmonic_response(DAMPED, lambda t: 0.0, 1.0)
    with pytest.raises(pinlin.ParameterError, match="modes: the modal analysis given is of another system"):
        pinlin.harmonic_response(DAMPED, [1.0, 0.0], 1.0, method="modal", modes=pinlin.modal_analysis(JORDAN))


def test_overflow_is_an_error_not_nan():
    """omega = 1e300 used to give NaN with error 0."""
    with pytest.raises(pinlin.ComputationError, match=r"overflows double precision at omega\[1\]"):
        pinlin.harmonic_response(DAMPED, [1.0, 0.0], [1.0, 1e300])
    with pytest.raises(pinlin.ComputationError, match="overflows"):
        pinlin.frequency_response(DAMPED, [1e300], method="modal")


def test_inaccurate_modal_result_warns_with_the_defect():
    with pytest.warns(pinlin.AccuracyWarning, match=r"flexibility \(modal\): relative defect .* > tol 1e-300"):
        pinlin.flexibility(DAMPED, 0.7j, method="modal", error_tol=1e-300)
