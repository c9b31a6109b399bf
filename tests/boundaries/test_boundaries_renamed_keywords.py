"""The boundary searches' deprecated ``tol=`` (now ``atol=``, the absolute accuracy asked of p*)."""

from __future__ import annotations

import pytest
from boundary_cases import double_pendulum, ziegler

import pinlin


def test_critical_parameter_tol_warns_and_still_works():
    new = pinlin.critical_parameter(ziegler(0.1), (0.5, 3.0), atol=1e-6)
    with pytest.warns(DeprecationWarning, match=r"critical_parameter\(tol=\.\.\.\) is deprecated .* use atol"):
        old = pinlin.critical_parameter(ziegler(0.1), (0.5, 3.0), tol=1e-6)
    assert old.value == new.value and old.error_bound == new.error_bound
    with pytest.raises(pinlin.ParameterError, match="tol: is the deprecated name of atol"):
        pinlin.critical_parameter(ziegler(0.1), (0.5, 3.0), tol=1e-6, atol=1e-6)


def test_stability_boundary_tol_warns_and_still_works():
    def func2(c, P):
        return double_pendulum(c)(P)

    new = pinlin.stability_boundary(func2, [0.3, 0.5], (1.0, 40.0), atol=1e-6)
    with pytest.warns(DeprecationWarning, match=r"stability_boundary\(tol=\.\.\.\) is deprecated .* use atol"):
        old = pinlin.stability_boundary(func2, [0.3, 0.5], (1.0, 40.0), tol=1e-6)
    assert old.p2.tolist() == new.p2.tolist()

