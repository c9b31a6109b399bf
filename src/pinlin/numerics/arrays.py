"""Read-only copies, and input checks of arrays over time and coordinates: time grids, coordinate vectors,
sampled signals.

Results and systems never share writable arrays: :func:`readonly` is the one way they copy.

Used by the frequency responses (force amplitudes), the time responses (initial
conditions, sampled forces) and the nonlinear simulation (time grids).  Each raises
a :class:`~pinlin.ParameterError` naming the parameter, the expected and the found
value or shape.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError

__all__ = ["readonly", "HALF", "check_times", "check_vector", "check_samples"]

#: 0.5 as a read-only 0-d float64 array, for halving small arrays in place (``A *= HALF``): the same
#: product as ``A *= 0.5``, bitwise, at about half the cost (numpy 2 promotes a Python float operand
#: on every call, which costs as much as the ufunc on a 9 x 9 matrix).
HALF = np.array(0.5)
HALF.flags.writeable = False


def readonly(a, dtype=None) -> np.ndarray | None:
    """A read-only copy of ``a`` (None stays None): results and systems never share writable arrays."""
    if a is None:
        return None
    out = np.array(a, dtype=dtype, copy=True)
    out.flags.writeable = False
    return out


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


def check_vector(value, n: int, label: str, *, complex_ok: bool = False, allow_none: bool = True) -> np.ndarray:
    """A finite vector of n real (or, with ``complex_ok``, complex) numbers; None gives zeros when allowed.

    Force amplitudes (:mod:`pinlin.frf`) and initial conditions (:mod:`pinlin.response`).

    Raises
    ------
    ParameterError
        None where not allowed, a callable, not numbers, another shape, or non-finite.
    """
    kind = "complex" if complex_ok else "real"
    if value is None and allow_none:
        return np.zeros(n, dtype=complex if complex_ok else float)
    if value is None or callable(value):
        raise ParameterError(label, f"expected {n} {kind} numbers (one per coordinate), got {value!r:.80}")
    try:
        arr = np.array(value, dtype=complex if complex_ok else float)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected {n} {kind} numbers (one per coordinate), got {value!r:.80}") from None
    if arr.shape != (n,):
        raise ParameterError(label, f"expected shape ({n},) (one value per coordinate), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ParameterError(label, f"must be finite, got {arr}")
    return arr
