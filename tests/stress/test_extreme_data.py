"""Extreme but finite data give a result or a PinlinError (theory: spectrum, error figures).

Coefficients of every size double precision holds, 1e-300 to 1e300, in every
combination: modal_analysis returns eigenvalues with finite error figures, or
refuses with a PinlinError saying the problem is out of double range; never
ZeroDivisionError, OverflowError, a LAPACK error, or NaN in a figure.
"""

from __future__ import annotations

import itertools
import warnings

import numpy as np
import pytest

import pinlin

SIZES_M = (1e-300, 1.0, 1e300)
SIZES_CK = (0.0, 1e-300, 1e-150, 1.0, 1e150, 1e300)


@pytest.mark.parametrize("mechanical", [True, False])
@pytest.mark.parametrize("sm", SIZES_M)
def test_every_scale_gives_a_result_or_a_pinlin_error(sm, mechanical):
    rng = np.random.default_rng(0)
    A = rng.standard_normal((2, 2))
    outcomes = {"result": 0, "refused": 0}
    for sc, sk in itertools.product(SIZES_CK, SIZES_CK):
        M = sm * (A @ A.T + 2 * np.eye(2))
        C, K = sc * rng.standard_normal((2, 2)), sk * rng.standard_normal((2, 2))
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # numpy's own norms in the constructor
                source = pinlin.LinearizedSystem.from_matrices(M, C, K) if mechanical else (M, C, K)
            m = pinlin.modal_analysis(source)
        except pinlin.PinlinError as exc:
            assert "rescale" in str(exc) or "singular" in str(exc), str(exc)
            outcomes["refused"] += 1
            continue
        outcomes["result"] += 1
        assert np.all(np.isfinite(m.eigenvalues))
        assert np.isfinite(m.error) and np.isfinite(m.stability.error)
        assert not np.any(np.isnan(m.error_bound)) and not np.any(np.isnan(m.condition))
    assert outcomes["result"] > 0


def test_the_issue_example_has_a_result():
    """from_matrices(1e-300 * eye(1), zeros((1, 1)), eye(1)): a ZeroDivisionError in pinlin 0.2."""
    m = pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices(1e-300 * np.eye(1), np.zeros((1, 1)), np.eye(1)))
    assert np.allclose(np.abs(m.eigenvalues), 1e150, rtol=1e-15) and m.error < 1e-15
