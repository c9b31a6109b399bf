"""stability_boundary: continuation of a boundary curve p2*(p1).

Reference: the damped flutter load of the double pendulum (theory: double pendulum) with equal joint dampers c, the smallest
positive root of the Routh-Hurwitz determinant (boundary_cases.damped_flutter_load); the curve over c is
also in tests/reference/test_reference_boundaries.py.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from boundary_cases import damped_flutter_load, double_pendulum, double_pendulum_theta
from numpy.testing import assert_allclose

import pinlin


def func2(c, P):
    return double_pendulum(c)(P)


def test_curve_follows_the_closed_form_and_the_predictor_pays():
    dampings = np.linspace(0.2, 1.0, 9)
    curve = pinlin.stability_boundary(func2, dampings, (1.0, 40.0))
    reference = [damped_flutter_load(double_pendulum_theta, c, 40.0) for c in dampings]
    assert_allclose(curve.p2, reference, rtol=1e-10)
    assert np.all(np.abs(curve.p2 - reference) <= curve.error_bound)
    counts = [p.evaluations for p in curve.points]
    assert curve.evaluations == sum(counts)
    # after the first points the brackets come from the extrapolated curve: narrower, cheaper
    assert np.mean(counts[3:]) < counts[0]
    assert curve.error == float(curve.error_bound.max())


def test_failures_are_recorded_or_raised():
    def flaky(c, P):
        if c == 0.5:
            raise pinlin.ParameterError("c", "no model at c = 0.5")
        return func2(c, P)

    curve = pinlin.stability_boundary(flaky, [0.3, 0.5, 0.7], (1.0, 40.0), on_error="record")
    assert curve.found.tolist() == [True, False, True]
    assert np.isnan(curve.p2[1]) and np.isinf(curve.error_bound[1]) and curve.points[1] is None
    (failure,) = curve.failures
    assert failure.index == 1 and failure.p1 == 0.5 and "SystemFunctionError" in failure.message
    assert "no model at c = 0.5" in failure.message
    json.dumps(curve.to_dict(), allow_nan=False)
    assert "found=2" in repr(curve)

    with pytest.raises(pinlin.SystemFunctionError, match="no model at c = 0.5") as info:
        pinlin.stability_boundary(flaky, [0.3, 0.5], (1.0, 40.0))
    assert any("p1 = 0.5" in note for note in getattr(info.value, "__notes__", ["p1 = 0.5"]))


def test_a_bracket_that_no_longer_holds_the_boundary():
    """At c = 3 the pendulum no longer flutters below P_0 (boundary_cases: divergence at det K = 0 only)."""
    with pytest.raises(pinlin.BracketError, match="at p1 = 3.0"):
        pinlin.stability_boundary(func2, [3.0], (1.0, 20.0))


def test_bad_input():
    with pytest.raises(pinlin.ParameterError, match="p1_values: expected a non-empty sequence of finite numbers"):
        pinlin.stability_boundary(func2, [], (1.0, 40.0))
    with pytest.raises(pinlin.ParameterError, match="p1_values: expected a non-empty"):
        pinlin.stability_boundary(func2, [0.1, np.nan], (1.0, 40.0))
    with pytest.raises(pinlin.ParameterError, match="p1_values: expected a sequence of numbers"):
        pinlin.stability_boundary(func2, ["a"], (1.0, 40.0))
    with pytest.raises(pinlin.ParameterError, match="on_error: expected one of"):
        pinlin.stability_boundary(func2, [0.1], (1.0, 40.0), on_error="ignore")
