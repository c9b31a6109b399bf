"""The result convention for the spectral results: Modes, Stability, Cluster, JordanChains.

Every result has ``elapsed`` [s], ``method``, ``error`` (one float with the
meaning its docstring gives) and a JSON-serializable ``to_dict()``; the figures
are recomputed here from their definitions, not read back from pinlin.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin import AccuracyWarning, LinearizedSystem
from pinlin.spectral import Cluster, JordanChains, Modes, Stability
from spectral_cases import double_pendulum, eta_reference, ring


def _complex(d):
    """Complex array back from the to_dict encoding {"re": [...], "im": [...]}."""
    return np.asarray(d["re"], dtype=float) + 1j * np.asarray(d["im"], dtype=float)


def _one_screen(text: str) -> None:
    assert "\n" not in text and len(text) < 240


def test_modes_follow_the_result_convention():
    sys = double_pendulum(P=4.0, c=0.05)
    m = pinlin.modal_analysis(sys)
    assert isinstance(m, Modes)
    # error: the largest backward error, recomputed from its definition
    eta = eta_reference(sys.M, sys.C, sys.K, m.eigenvalues, np.asarray(m.right))
    assert m.error == np.max(m.backward_error)
    # both are rounding-level: the products are formed differently, so they agree to a few eps
    assert_allclose(m.error, np.max(eta), rtol=0, atol=4 * np.finfo(float).eps)
    assert m.method == "general" and m.elapsed > 0
    _one_screen(repr(m))
    d = json.loads(json.dumps(m.to_dict()))
    assert d["type"] == "Modes" and d["method"] == "general" and d["method_reason"] == m.method.reason
    assert d["error"] == m.error and d["elapsed"] == m.elapsed
    assert "system" not in d and "matrices" not in d
    assert_allclose(_complex(d["eigenvalues"]), m.eigenvalues, rtol=0, atol=0)
    assert_allclose(_complex(d["right"]), m.right, rtol=0, atol=0)
    assert d["backward_error"] == m.backward_error.tolist() and d["condition"] == m.condition.tolist()
    assert d["stability"]["kind"] == m.stability.kind
    # the definiteness decisions travel with their numbers (one decision for modes and the report)
    S = d["structure"]["definiteness_S"]
    w = np.linalg.eigvalsh(sys.S)
    assert S["kind"] == m.structure.stiffness and S["negative"] == int(np.sum(w < 0))
    assert_allclose([S["min_eigenvalue"], S["max_eigenvalue"]], [w[0], w[-1]], rtol=1e-12)


def test_modes_to_dict_of_a_tuple_problem_without_mechanical_split():
    m = pinlin.modal_analysis((np.eye(2), np.zeros((2, 2)), np.diag([1.0, 4.0])))
    d = json.loads(json.dumps(m.to_dict()))
    assert d["constants"] is None and d["structure"]["damping"] is None
    assert_allclose(np.sort(np.abs(_complex(d["eigenvalues"]))), [1, 1, 2, 2], rtol=1e-14)


def test_stability_error_is_the_data_uncertainty_as_a_share_of_the_margin():
    # the damped double pendulum with its follower load (N != 0): decided by the spectrum, not a theorem
    v = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.1)).stability
    assert isinstance(v, Stability) and v.kind == "asymptotically_stable" and v.theorem is None
    assert v.uncertainty == 0.0 and 0 < v.margin < pinlin.spectral.MARGIN_CAP
    assert v.error == np.finfo(float).eps / v.margin
    assert 0 < v.error < 1  # decided: the verdict survives more than rounding
    assert f"margin {v.margin:.1e}" in v.reason
    assert v.method == "computed eigenvalues against their first-order error bounds"
    assert v.elapsed >= 0
    d = json.loads(json.dumps(v.to_dict()))
    assert d["kind"] == v.kind and d["error"] == v.error and d["reason"] == v.reason
    assert d["margin"] == v.margin and d["uncertainty"] == 0.0
    _one_screen(repr(v))
    # against a stated uncertainty the share is taken of it
    u = 1e-3 * v.margin
    w = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.1), uncertainty=u).stability
    assert w.kind == v.kind and w.uncertainty == u and w.error == pytest.approx(u / w.margin, rel=1e-15)


def test_stability_from_structure_alone_has_no_eigenvalue_and_its_margin():
    sys = LinearizedSystem.from_matrices(np.eye(2), np.eye(2), np.diag([1.0, 2.0]))
    v = pinlin.spectral.stability_from_structure(sys)
    assert v.kind == "asymptotically_stable" and v.eigenvalue is None
    assert v.method == "Thomson-Tait-Chetaev" and v.elapsed > 0
    # the margin is that of S > 0: (lambda_min - 2 eps ||S||) / ||S||, found by bisection from below
    exact = (1.0 - 2 * np.finfo(float).eps * 2.0) / 2.0
    assert exact * (1 - 1e-4) <= v.margin <= exact
    assert v.error == np.finfo(float).eps / v.margin
    json.dumps(v.to_dict())


def test_undecided_verdict_has_error_at_least_one():
    # general coefficients, roots exactly on the axis: only the bounds speak, and they cannot tell
    M = np.array([[1.0, 0.1], [0.0, 1.0]])
    K = np.array([[1.0, 0.0], [0.3, 4.0]])
    v = pinlin.modal_analysis((M, np.zeros((2, 2)), K)).stability
    assert v.kind == "undecided" and v.theorem is None
    assert abs(v.eigenvalue.real) <= v.error_bound
    assert v.error == 1.0  # the bound covers the whole distance to the axis


def test_cluster_error_is_the_relative_spread_of_its_members():
    omega = 3.0  # critically damped: lam0 = -omega, one chain of length 2
    sys = LinearizedSystem.from_matrices([[1.0]], [[2 * omega]], [[omega**2]])
    m = pinlin.modal_analysis(sys)
    (c,) = m.clusters
    assert isinstance(c, Cluster)
    members = m.eigenvalues[list(c.indices)]
    gamma = np.sqrt(omega**2)  # Fan-Lin-Van Dooren sqrt(||K|| / ||M||)
    assert_allclose(c.error, np.max(np.abs(members - c.center)) / max(abs(c.center), gamma), rtol=1e-14)
    assert c.error < 1e-6  # a double root splits by about sqrt(eps)
    assert "Toeplitz" in c.method and c.elapsed >= 0
    d = json.loads(json.dumps(c.to_dict()))
    assert d["partial"] == [2] and d["algebraic"] == 2 and d["consistent"] is True
    _one_screen(repr(c))


def test_jordan_chains_error_is_the_largest_chain_residual():
    omega = 3.0
    M, C, K = np.eye(1), np.array([[2 * omega]]), np.array([[omega**2]])
    ch = pinlin.jordan_chains((M, C, K), -omega)
    assert isinstance(ch, JordanChains) and ch.complete and ch.expected == ch.partial == (2,)
    x0, x1 = ch[0]
    # the chain equations written out: L x0 and L x1 + L' x0 (L = L' = 0 at -omega, L''/2 = 1)
    lam0 = -omega
    L = lam0**2 * M + lam0 * C + K
    dL = 2 * lam0 * M + C
    w0 = abs(lam0) ** 2 * 1 + abs(lam0) * 2 * omega + omega**2
    w1 = 2 * abs(lam0) + 2 * omega
    rho0 = np.linalg.norm(L @ x0) / (w0 * np.linalg.norm(x0))
    rho1 = np.linalg.norm(L @ x1 + dL @ x0) / (w0 * np.linalg.norm(x1) + w1 * np.linalg.norm(x0))
    assert_allclose(ch.residuals[0], [rho0, rho1], rtol=1e-12, atol=1e-300)
    assert ch.error == ch.max_residual == max(rho0, rho1)
    assert ch.elapsed > 0 and "Toeplitz" in ch.method
    d = json.loads(json.dumps(ch.to_dict()))
    assert d["complete"] is True and d["partial"] == [2] and len(d["chains"][0]) == 2
    assert_allclose(_complex(d["chains"][0][1]), x1, rtol=0, atol=0)
    _one_screen(repr(ch))


def test_jordan_chains_fewer_than_the_rank_test_found_are_reported():
    """A rank tolerance near one makes the Toeplitz ranks promise chains that do not exist."""
    rng = np.random.default_rng(0)
    for _ in range(5):
        A = rng.standard_normal((3, 3))
        M, C, K = A @ A.T + 3 * np.eye(3), rng.standard_normal((3, 3)), rng.standard_normal((3, 3))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ch = pinlin.jordan_chains((M, C, K), 0.0, rank_tol=0.9)
    assert not ch.complete and ch.partial != ch.expected
    assert sum(ch.partial) < sum(ch.expected)
    assert ch.notes and "expected from the Toeplitz ranks" in ch.notes[0]
    assert any(issubclass(w.category, AccuracyWarning) for w in caught)
    assert "INCOMPLETE" in repr(ch) and ch.to_dict()["complete"] is False


@pytest.mark.parametrize("make", [lambda: double_pendulum(P=4.0), lambda: ring(k=4.0, c=0.0, Omega=3.0)])
def test_every_spectral_result_is_json_serializable(make):
    m = pinlin.modal_analysis(make())
    text = json.dumps(m.to_dict())
    assert json.loads(text)["type"] == "Modes"
    for c in m.clusters:
        json.dumps(c.to_dict())
