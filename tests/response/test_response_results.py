"""The result convention of the time responses: FreeResponse, ForcedResponse, EnergyBudget.

Each result is built on a small system; ``json.dumps(to_dict())`` must work, and
``error``, ``method`` and ``elapsed`` must mean what the docstrings say.  The
figures behind ``error`` are recomputed here independently where they can be:
the initial defect from the returned x(t0), x'(t0); the exponential check from
``scipy.linalg.expm`` of the state matrix built in ``response_cases``; the
balance residual from the budget's own arrays.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

import pinlin
from response_cases import json_round_trip, state_matrix, timed

DAMPED = pinlin.LinearizedSystem.from_matrices(
    np.diag([2.0, 1.0]), [[0.3, 0.4], [-0.6, 0.2]], [[6.0, -1.6], [-2.4, 3.0]]
)
T = np.linspace(0.0, 2.0, 41)
X0, V0 = np.array([0.1, -0.2]), np.array([0.0, 0.3])


def test_free_response_figures():
    x, wall = timed(lambda: pinlin.free_response(DAMPED, T, X0, V0))
    assert x.error == max(x.defect, x.initial_defect, x.symmetry_defect) and x.error < 1e-12
    assert x.method == "modal" and 0 < x.elapsed <= wall
    # the initial defect, recomputed: T[0] = t0, so x(t0) and x'(t0) are the first rows
    g = np.sqrt(np.linalg.norm(DAMPED.K) / np.linalg.norm(DAMPED.M))
    rx = np.linalg.norm(X0) + np.linalg.norm(V0) / g
    rv = g * np.linalg.norm(X0) + np.linalg.norm(V0)
    initial = max(np.linalg.norm(np.asarray(x)[0] - X0) / rx, np.linalg.norm(x.xdot[0] - V0) / rv)
    assert x.initial_defect == pytest.approx(initial, rel=1e-6, abs=1e-17)
    data = json_round_trip(x)
    assert "modes" not in data and np.array(data["values"]).shape == (len(T), 2)
    assert_allclose(np.array(data["xdot"]), x.xdot, rtol=0)
    assert len(repr(x).splitlines()) == 1
    chains = pinlin.free_response(pinlin.LinearizedSystem.from_matrices([[1.0]], [[2.0]], [[1.0]]), T, [1.0])
    assert chains.method == "modal + Jordan chains"  # critically damped: lam = -1 double, one chain


def test_forced_response_figures():
    f = np.column_stack([np.sin(2.0 * T), np.zeros_like(T)])
    resp, wall = timed(lambda: pinlin.forced_response(DAMPED, T, f, X0, V0))
    assert resp.input_error is None and resp.error == resp.exponential_defect  # sampled force: exact reading
    A = state_matrix(DAMPED)
    h = T[1] - T[0]
    half = scipy.linalg.expm(A * h / 2)
    full = scipy.linalg.expm(A * h)
    assert resp.exponential_defect < 1e-14
    assert resp.exponential_defect == pytest.approx(
        np.linalg.norm(half @ half - full) / np.linalg.norm(full), rel=0.5, abs=1e-15
    )
    assert "exact discretization" in resp.method and 0 < resp.elapsed <= wall
    data = json_round_trip(resp)
    assert "system" not in data and "x_internal" not in data
    assert_allclose(np.array(data["x"]), resp.x, rtol=0)
    # a callable force: the interpolation error counts too
    coarse = pinlin.forced_response(DAMPED, T, lambda t: np.array([np.sin(5.0 * t), 0.0]), X0, V0, input_tol=1.0)
    assert coarse.input_error > 1e-4 and coarse.error == max(coarse.exponential_defect, coarse.input_error)


def test_energy_budget_figures():
    resp = pinlin.forced_response(DAMPED, T, np.column_stack([np.sin(2.0 * T), np.zeros_like(T)]), X0, V0)
    budget, wall = timed(lambda: pinlin.energy_budget(DAMPED, resp.t, resp.x, resp.xdot, resp.f))
    assert budget.error == budget.balance_residual
    assert budget.error == pytest.approx(np.max(np.abs(budget.residual)) / budget.scale, rel=1e-12)
    assert budget.error < 1e-8 and "Hermite" in budget.method and 0 < budget.elapsed <= wall
    data = json_round_trip(budget)
    assert_allclose(np.array(data["energy"]), budget.energy, rtol=0)
    with pytest.raises(pinlin.ParameterError, match="interpolation"):
        pinlin.energy_budget(DAMPED, T[:1], resp.x[:1], resp.xdot[:1], interpolation="quintic")


def test_bad_inputs_name_the_parameter():
    with pytest.raises(pinlin.ParameterError, match="t0: expected a time"):
        pinlin.free_response(DAMPED, T, X0, V0, t0="now")
    with pytest.raises(pinlin.ParameterError, match=r"substeps: expected .*integer"):
        pinlin.forced_response(DAMPED, T, lambda t: np.zeros(2), substeps=0)
    with pytest.raises(pinlin.ParameterError, match="input_tol"):
        pinlin.forced_response(DAMPED, T, input_tol=0.0)


def test_free_response_prints_its_summary():
    """Issue 17 part 6: print(resp) gives the one-line summary, not len(t) x n numbers."""
    sys_ = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    resp = pinlin.free_response(sys_, np.linspace(0, 1, 500), [1.0, 0.0], [0.0, 0.0])
    assert str(resp) == repr(resp) and "\n" not in str(resp)
    assert "t=[0, 1] s (500 points)" in str(resp) and "error=" in str(resp)
    assert str(resp[:2]).startswith("[[")  # a part is plain data and prints as numbers
