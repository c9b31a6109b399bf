"""Validation of the inputs of the time responses: time grids, vectors, samples (SPEC section 9).

Every check raises a :class:`~pinlin.ParameterError` naming the parameter and
giving the expected and the found shape or value.  The checks shared with the
other analyses (the system, tolerances) live in :mod:`pinlin.numerics.checks`,
the check of a vector of coordinates in :mod:`pinlin.frf._inputs` (the harmonic
force amplitude uses it too); they are re-exported here.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..frf._inputs import check_vector
from ..numerics import check_system, check_tolerance

__all__ = ["check_system", "check_times", "check_vector", "check_samples", "check_tolerance"]


def _real_array(value, label: str) -> np.ndarray:
    if callable(value):
        raise ParameterError(label, "expected an array of numbers, got a callable")
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected real numbers, got {value!r:.80}") from None
    return arr


def check_times(t, label: str = "t", *, min_points: int = 1) -> np.ndarray:
    """A 1-D, finite, strictly increasing time grid [s] with at least ``min_points`` points.

    Raises
    ------
    ParameterError
        Not real numbers, not 1-D, too few points, non-finite, or not strictly increasing.
    """
    arr = _real_array(t, label)
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim != 1:
        raise ParameterError(label, f"expected a 1-D array of times, got shape {arr.shape}")
    if arr.size < min_points:
        raise ParameterError(label, f"expected at least {min_points} time point(s), got {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise ParameterError(label, "times must be finite")
    if arr.size > 1 and not np.all(np.diff(arr) > 0):
        k = int(np.flatnonzero(np.diff(arr) <= 0)[0])
        raise ParameterError(
            label, f"times must be strictly increasing; {label}[{k + 1}] = {arr[k + 1]!r} <= {label}[{k}] = {arr[k]!r}"
        )
    return arr


def check_samples(value, rows: int, n: int, label: str) -> np.ndarray:
    """A finite (rows, n) array of samples, one row per time point.

    Raises
    ------
    ParameterError
        Not real numbers, another shape, or a non-finite row.
    """
    arr = _real_array(value, label)
    if arr.shape != (rows, n):
        raise ParameterError(label, f"expected shape ({rows}, {n}) (one row of {n} values per time point), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        k = int(np.flatnonzero(~np.all(np.isfinite(arr), axis=1))[0])
        raise ParameterError(label, f"must be finite; row {k} is {arr[k]}")
    return arr
