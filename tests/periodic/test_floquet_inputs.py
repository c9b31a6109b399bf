"""Bad input and failed integration: every handled case raises a pinlin error naming the argument."""

from __future__ import annotations

import numpy as np
import pytest

from pinlin.errors import IntegrationBudgetError, ParameterError, PinlinError, SingularMassError
from pinlin.periodic import floquet_analysis_matrices, floquet_from_first_order

I1, K1 = np.eye(1), np.array([[1.0]])


@pytest.mark.parametrize("period", [0.0, -1.0, np.nan, np.inf, "two", None])
def test_bad_period(period):
    with pytest.raises(ParameterError, match="period"):
        floquet_analysis_matrices(I1, None, K1, period)


@pytest.mark.parametrize("M, C, K, match", [
    ("mass", None, K1, "M: expected a callable"),
    (np.ones((2, 3)), None, np.eye(2), "M: expected a square"),
    (np.eye(2), None, np.eye(3), r"K: expected shape \(2, 2\)"),
    (I1, np.ones((2, 2)), K1, r"C: expected shape \(1, 1\)"),
    (I1, None, np.array([[1 + 1j]]), "K: expected a real matrix, got complex"),
    (I1, None, np.array([[np.nan]]), "K: non-finite"),
    (I1, None, lambda t: np.array([[1.0 if t < 1 else np.inf]]), r"K: non-finite entries at t = 1"),
    (I1, None, lambda t: np.eye(1 if t < 2 else 2), r"K: expected shape \(1, 1\) at t = 2"),
    (I1, None, lambda t: "x", "K: expected a real matrix at t = 0"),
])
def test_bad_coefficients(M, C, K, match):
    with pytest.raises(ParameterError, match=match):
        floquet_analysis_matrices(M, C, K, 3.0)


def test_callable_that_raises_is_chained():
    def K(t):
        raise ZeroDivisionError("boom")
    with pytest.raises(ParameterError, match="K: raised ZeroDivisionError at t = 0") as info:
        floquet_analysis_matrices(I1, None, K, 1.0)
    assert isinstance(info.value.__cause__, ZeroDivisionError)


def test_singular_mass():
    with pytest.raises(SingularMassError, match="M is singular at t = "):
        floquet_analysis_matrices(lambda t: np.zeros((1, 1)), None, K1, 1.0)


@pytest.mark.parametrize("option, value", [("rtol", 0.0), ("rtol", 0.1), ("stages", 1), ("stages", 2.5),
                                           ("growth", 1.0), ("harmonics", -1), ("safety", np.nan),
                                           ("conservative", "yes")])
def test_bad_options(option, value):
    with pytest.raises(ParameterError, match=option):
        floquet_analysis_matrices(I1, None, K1, 1.0, **{option: value})


def test_first_order_argument_checks():
    with pytest.raises(ParameterError, match="A: expected a square"):
        floquet_from_first_order(np.ones((2, 3)), 1.0)
    with pytest.raises(ParameterError, match="symplectic_form"):
        floquet_from_first_order(np.eye(2), 1.0, symplectic_form=np.eye(3))
    for rows in ([2], [0.5], [], [[0]]):
        with pytest.raises(ParameterError, match="rows"):
            floquet_from_first_order(np.eye(2), 1.0, rows=rows)


def test_step_budget():
    with pytest.raises(IntegrationBudgetError, match="max_steps reached") as info:
        floquet_analysis_matrices(I1, None, lambda t: np.array([[400.0 + np.cos(t)]]), 2 * np.pi, max_steps=5,
                                  sampling="nodes")
    err = info.value
    assert isinstance(err, PinlinError) and isinstance(err, RuntimeError)
    assert err.budget == "max_steps" and err.steps == 5 and 0 <= err.t_reached < err.t_end == 2 * np.pi


def test_step_budget_on_the_sampled_grid():
    # A = [[0, 1], [-401, 0]] at its fastest, balanced by powers of two to [[0, 16], [-401 / 16, 0]] (2-norm
    # 25.06); Gauss s = 6 has the error constant (6!)^4 / (12!^3 13) = 1.88e-16, so the first grid's step is
    # (1e-13 / 1.88e-16)^(1/13) / 25.06 = 0.0646 s: 98 steps over 2 pi, the first round alone over the budget
    with pytest.raises(IntegrationBudgetError, match="98 more needed \\(max_steps reached") as info:
        floquet_analysis_matrices(I1, None, lambda t: np.array([[400.0 + np.cos(t)]]), 2 * np.pi, max_steps=5)
    err = info.value
    assert err.budget == "max_steps" and err.steps == 0 and err.t_reached == 0.0 and err.t_end == 2 * np.pi


def test_time_budget():
    with pytest.raises(IntegrationBudgetError, match="max_time reached") as info:
        floquet_analysis_matrices(I1, None, lambda t: np.array([[4.0 + np.cos(t)]]), 2 * np.pi, max_time=0.0)
    assert info.value.budget == "max_time" and info.value.t_reached == 0.0
