"""critical_parameter: how it searches, what it reports, and every bad-input path.

The accuracy against closed forms is in tests/reference/test_reference_boundaries.py; here the same families
(boundary_cases) exercise the mechanisms, the counts, the re-planning and the errors.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from boundary_cases import (
    DP,
    ZIEGLER_FLUTTER,
    double_pendulum,
    double_pendulum_theta,
    undamped_loads,
    ziegler,
)
from numpy.testing import assert_allclose
from scipy.linalg import block_diag

import pinlin

P_F, P_D = undamped_loads(double_pendulum_theta)
T = np.array([[1.0, 0.0], [1.0, 1.0]])


def test_coalescence_of_an_undamped_column():
    r = pinlin.critical_parameter(ziegler(), (0.5, 3.0))
    assert r.mechanism == "coalescence" and r.kind == "flutter"
    assert r.verdicts == ("marginally_stable", "flutter") and r.verified
    assert abs(r.value - ZIEGLER_FLUTTER) <= r.error_bound <= 1e-12
    # the double eigenvalue on the axis: lam^2 = mu = -(7 - 2 P_f) / 4 = -1 / sqrt(2)
    assert_allclose(r.eigenvalue, 1j * 2**-0.25, rtol=1e-10)
    assert r.evaluations <= 10 and r.bracket[0] <= r.value <= r.bracket[1]


def test_transversal_crossing_of_a_damped_column():
    r = pinlin.critical_parameter(ziegler(0.1), (0.5, 3.0))
    assert r.mechanism == "crossing" and r.kind == "flutter" and r.verdicts[0] == "asymptotically_stable"
    assert abs(r.eigenvalue.real) == 0.0 and r.eigenvalue.imag > 0
    assert "Newton" in r.method and "hermite" in r.steps


def test_flutter_to_divergence_is_a_coalescence_on_the_real_axis():
    """P_d: the complex quadruple lands on the real axis; between two unstable verdicts the kind is divergence."""
    r = pinlin.critical_parameter(double_pendulum(), (20.0, 38.0))
    assert r.verdicts == ("flutter", "divergence") and r.kind == "divergence" and r.mechanism == "coalescence"
    assert abs(r.value - P_D) <= r.error_bound
    assert r.eigenvalue.imag == 0 and r.eigenvalue.real > 0


def test_a_bracket_holding_several_boundaries_is_planned_again():
    """(0, 45): stable at 0, divergence at 45 (beyond P_0); the flutter verdict met inside becomes the upper end."""
    r = pinlin.critical_parameter(double_pendulum(), (0.0, 45.0))
    assert abs(r.value - P_F) <= r.error_bound and r.mechanism == "coalescence"
    assert any("planned again" in note for note in r.notes)
    assert r.evaluations <= 12


def test_bisection_is_the_baseline():
    tol = 1e-12 * P_F
    fast = pinlin.critical_parameter(double_pendulum(), (10.0, 20.0), atol=tol)
    slow = pinlin.critical_parameter(double_pendulum(), (10.0, 20.0), atol=tol, method="bisection")
    assert slow.mechanism == "bisection" and slow.method == "bisection on the stability verdict"
    assert abs(slow.value - P_F) <= slow.error_bound <= tol
    assert abs(fast.value - P_F) <= fast.error_bound
    assert fast.evaluations <= 10 < 30 < slow.evaluations


def test_exact_derivative_and_tolerance():
    l1 = DP["l1"]

    def derivative(P):
        return np.zeros((2, 2)), np.zeros((2, 2)), T.T @ np.array([[-l1, l1], [0.0, 0.0]]) @ T

    exact = pinlin.critical_parameter(double_pendulum(1e-2), (1.0, 40.0), derivative=derivative)
    secant = pinlin.critical_parameter(double_pendulum(1e-2), (1.0, 40.0))
    assert_allclose(exact.value, secant.value, rtol=1e-12)
    loose = pinlin.critical_parameter(double_pendulum(1e-2), (1.0, 40.0), atol=1e-4)
    assert abs(loose.value - secant.value) <= loose.error_bound
    assert loose.function_calls <= secant.function_calls


def test_without_verification():
    r = pinlin.critical_parameter(ziegler(), (0.5, 3.0), verify_result=False)
    assert not r.verified and "verification" not in r.steps
    assert abs(r.value - ZIEGLER_FLUTTER) <= r.error_bound


def test_result_convention():
    r = pinlin.critical_parameter(ziegler(), (0.5, 3.0))
    data = r.to_dict()
    assert list(data)[:4] == ["type", "method", "error", "elapsed"]
    assert data["error"] == r.error_bound and data["value"] == r.value
    json.dumps(data, allow_nan=False)
    assert repr(r).startswith("CriticalParameter(value=2.08578643762") and len(repr(r)) < 300


# ----------------------------------------------------------------------------- bad input


def test_bracket_errors():
    with pytest.raises(pinlin.BracketError, match="both ends of the bracket .* 'stable'") as info:
        pinlin.critical_parameter(double_pendulum(), (1.0, 16.0))
    assert info.value.verdicts == ("marginally_stable", "marginally_stable")
    with pytest.raises(pinlin.BracketError, match="both ends .* 'flutter'"):
        pinlin.critical_parameter(double_pendulum(), (17.0, 30.0))
    with pytest.raises(pinlin.BracketError, match="'undecided'"):
        pinlin.critical_parameter(double_pendulum(), (P_F, 30.0))
    with pytest.raises(pinlin.BracketError, match="ends are equal"):
        pinlin.critical_parameter(double_pendulum(), (3.0, 3.0))
    with pytest.raises(pinlin.BracketError, match=r"expected a bracket \(p_low, p_high\)"):
        pinlin.critical_parameter(double_pendulum(), 3.0)
    with pytest.raises(pinlin.ParameterError, match=r"bracket\[1\]: expected a finite number"):
        pinlin.critical_parameter(double_pendulum(), (3.0, np.inf))


def _undecided_band(p):
    """A damped oscillator that loses its damper at p = 0 beside a damped circulatory pair that flutters for
    p > ~0.55: the spectrum is not symmetric, so between them the undamped oscillator's verdict is "undecided"
    over a whole interval (no theorem decides, and its eigenvalues sit on the axis within their bounds)."""
    D = block_diag([[0.2 * max(-p, 0.0)]], 0.05 * np.eye(2))
    K = block_diag([[1.0]], np.array([[2.0, p], [-p, 3.0]]))
    return pinlin.LinearizedSystem.from_matrices(np.eye(3), D, K)


def test_boundary_not_isolated():
    assert pinlin.modal_analysis(_undecided_band(0.3)).stability.kind == "undecided"
    with pytest.raises(pinlin.BoundaryNotIsolatedError, match="stays 'undecided'.*not isolated") as info:
        pinlin.critical_parameter(_undecided_band, (-0.5, 2.0))
    lo, hi = info.value.interval
    assert -0.5 <= lo < 0.3 < hi <= 2.0  # the undecided band [0, ~0.55] is met inside it
    with pytest.raises(pinlin.BoundaryNotIsolatedError, match="is 'undecided' over"):
        pinlin.critical_parameter(_undecided_band, (-0.5, 2.0), method="bisection")


def test_func_that_raises_or_changes_size():
    def fails_inside(P):
        if 5.0 < P < 30.0:
            raise pinlin.ConvergenceError("no equilibrium", [1.0])
        return double_pendulum()(P)

    with pytest.raises(pinlin.SystemFunctionError, match=r"func\(.*\) raised ConvergenceError: no equilibrium") as info:
        pinlin.critical_parameter(fails_inside, (1.0, 35.0))
    assert 5.0 < info.value.p < 30.0 and isinstance(info.value.__cause__, pinlin.ConvergenceError)

    def grows(P):
        if P < 16.0:
            return double_pendulum()(P)
        return pinlin.LinearizedSystem.from_matrices(np.eye(3), None, np.diag([1.0, 1.0, -1.0]))

    with pytest.raises(pinlin.SystemFunctionError, match="different sizes or coordinates: n = 2"):
        pinlin.critical_parameter(grows, (10.0, 20.0))

    with pytest.raises(pinlin.SystemFunctionError, match="returned NoneType"):
        pinlin.critical_parameter(lambda P: None, (10.0, 20.0))


def test_bad_options_and_budget():
    with pytest.raises(pinlin.ParameterError, match="method: expected one of"):
        pinlin.critical_parameter(ziegler(), (0.5, 3.0), method="secant")
    with pytest.raises(pinlin.ParameterError, match="tol: expected a positive absolute tolerance"):
        pinlin.critical_parameter(ziegler(), (0.5, 3.0), atol=-1.0)
    with pytest.raises(pinlin.ParameterError, match="max_evaluations: expected an integer >= 3"):
        pinlin.critical_parameter(ziegler(), (0.5, 3.0), max_evaluations=2)
    with pytest.raises(pinlin.ConvergenceError, match="modal analyses"):
        pinlin.critical_parameter(double_pendulum(1e-2), (1.0, 40.0), max_evaluations=4)
