"""The frequency-domain functions' deprecated ``tol=`` (now ``error_tol=``): it warns and still works."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import pinlin

SYS = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])


@pytest.mark.parametrize(
    "call",
    [
        lambda **kw: pinlin.flexibility(SYS, 0.7j, **kw),
        lambda **kw: pinlin.frequency_response(SYS, [0.5, 1.5], **kw).response,
        lambda **kw: pinlin.harmonic_response(SYS, [1.0, 0.0], [0.5, 1.5], **kw),
    ],
    ids=["flexibility", "frequency_response", "harmonic_response"],
)
def test_tol_is_the_deprecated_spelling_of_error_tol(call):
    new = call(error_tol=1e-6)
    with pytest.warns(DeprecationWarning, match=r"\(tol=\.\.\.\) is deprecated .* use error_tol=\.\.\."):
        old = call(tol=1e-6)
    assert_array_equal(np.asarray(old), np.asarray(new))
    with pytest.raises(pinlin.ParameterError, match="tol: is the deprecated name of error_tol"):
        call(tol=1e-6, error_tol=1e-6)


def test_the_renamed_threshold_still_decides_the_warning():
    with pytest.warns(pinlin.AccuracyWarning):
        pinlin.flexibility(SYS, 0.7j, method="modal", error_tol=1e-300)
    with pytest.warns(DeprecationWarning), pytest.warns(pinlin.AccuracyWarning):
        pinlin.flexibility(SYS, 0.7j, method="modal", tol=1e-300)
