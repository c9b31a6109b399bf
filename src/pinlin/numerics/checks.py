"""Input checks shared by the analyses (theory: conventions: bad input raises a ParameterError naming it).

Every check takes the value first and its name (``label``) second, returns the
value in canonical form, and raises :class:`~pinlin.ParameterError` with the
name, what was expected and what was found.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence

import numpy as np

from ..errors import ParameterError

__all__ = [
    "check_tolerance",
    "check_uncertainty",
    "check_integer",
    "check_radii",
    "complex_scalar",
    "complex_points",
    "dof_indices",
]



def check_tolerance(value, label: str, *, upper: float | None = None) -> float:
    """A finite positive number (below ``upper`` when given), as float.

    Used for tolerances, safety factors and scales alike.

    Raises
    ------
    ParameterError
        Not a real number, not finite, not positive, or not below ``upper``.
    """
    if isinstance(value, (bool, str)):
        raise ParameterError(label, f"expected a positive number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected a positive number, got {value!r}") from None
    if not math.isfinite(v) or v <= 0:
        raise ParameterError(label, f"expected a finite positive number, got {value!r}")
    if upper is not None and v >= upper:
        raise ParameterError(label, f"expected a number below {upper:g}, got {v:g}")
    return v


def check_uncertainty(value, label: str = "uncertainty") -> float:
    """A relative data uncertainty: a finite number in [0, 1), as float (0: the data as stored).

    Raises
    ------
    ParameterError
        Not a real number, not finite, negative, or 1 or more.
    """
    if isinstance(value, (bool, str)):
        raise ParameterError(label, f"expected a relative uncertainty in [0, 1), got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected a relative uncertainty in [0, 1), got {value!r}") from None
    if not math.isfinite(v) or v < 0 or v >= 1:
        raise ParameterError(label, f"expected a relative uncertainty in [0, 1), got {value!r}")
    return v


def check_integer(value, label: str, *, low: int | None = None, high: int | None = None) -> int:
    """An integer (not a bool) in ``[low, high]`` (either bound optional), as int.

    Raises
    ------
    ParameterError
        Not an integer, or out of range.
    """
    ok = isinstance(value, (numbers.Integral, np.integer)) and not isinstance(value, (bool, np.bool_))
    if ok:
        v = int(value)
        ok = (low is None or v >= low) and (high is None or v <= high)
    if not ok:
        if high is None and low in (0, 1):
            what = "a non-negative integer" if low == 0 else "a positive integer"
        else:
            what = f"an integer in [{'-inf' if low is None else low}, {'inf' if high is None else high}]"
        raise ParameterError(label, f"expected {what}, got {value!r}")
    return v


def check_radii(radii, label: str = "radii") -> np.ndarray:
    """Contour radii [1/s]: a non-empty 1-D array of finite positive numbers.

    Raises
    ------
    ParameterError
        Anything else.
    """
    try:
        r = np.atleast_1d(np.asarray(radii, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected positive numbers, got {radii!r}") from None
    if r.ndim != 1 or r.size == 0 or not np.all(np.isfinite(r)) or np.any(r <= 0):
        raise ParameterError(label, f"expected a non-empty list of finite positive radii, got {radii!r}")
    return r


def complex_scalar(value, label: str) -> complex:
    """A finite complex scalar.

    Raises
    ------
    ParameterError
        An array of any other shape than (), not a number, a bool, or non-finite.
    """
    if isinstance(value, np.ndarray):
        if value.ndim != 0:
            raise ParameterError(label, f"expected a scalar, got an array of shape {value.shape}")
        value = value.item()
    if not isinstance(value, numbers.Number) or isinstance(value, bool):
        got = f"{type(value).__name__} {value!r:.40}"
        raise ParameterError(label, f"expected a number (a real or complex number), got {got}")
    z = complex(value)
    if not (np.isfinite(z.real) and np.isfinite(z.imag)):
        raise ParameterError(label, f"expected a finite number, got {value!r}")
    return z


def complex_points(values, label: str) -> tuple[np.ndarray, bool]:
    """Finite complex points as a 1-D array, and whether the input was a scalar.

    Raises
    ------
    ParameterError
        Not numbers, more than one dimension, empty, or non-finite.
    """
    try:
        arr = np.asarray(values)
    except (TypeError, ValueError):
        raise ParameterError(label, "expected a complex number or an array of them") from None
    if arr.dtype == object or not (np.issubdtype(arr.dtype, np.number)) or arr.dtype == bool:
        raise ParameterError(label, f"expected complex numbers, got dtype {arr.dtype}")
    if arr.ndim > 1:
        raise ParameterError(label, f"expected a scalar or a 1-D array, got shape {arr.shape}")
    scalar = arr.ndim == 0
    arr = np.atleast_1d(arr).astype(complex)
    if arr.size == 0:
        raise ParameterError(label, "expected at least one point, got an empty array")
    bad = ~np.isfinite(arr)
    if np.any(bad):
        raise ParameterError(label, f"must be finite; entry {int(np.flatnonzero(bad)[0])} is {arr[bad][0]}")
    return arr, scalar


def dof_indices(sys, which, label: str) -> np.ndarray:
    """Indices of the coordinates named or numbered in ``which`` (None: all of them).

    Raises
    ------
    ParameterError
        An unknown name, an index out of range, or an empty or non-list ``which``.
    """
    if which is None:
        return np.arange(sys.n)
    items = [which] if isinstance(which, (str, numbers.Integral)) else which
    if not isinstance(items, (Sequence, np.ndarray)) or len(items) == 0:
        raise ParameterError(label, f"expected a coordinate index or name, or a non-empty list of them, got {which!r}")
    out = []
    for item in items:
        if isinstance(item, str):
            if item not in sys.dof_names:
                raise ParameterError(label, f"unknown coordinate {item!r}; valid names: {list(sys.dof_names)}")
            out.append(sys.dof_names.index(item))
        elif isinstance(item, numbers.Integral) and not isinstance(item, bool):
            if not 0 <= int(item) < sys.n:
                raise ParameterError(label, f"index {item} out of range for n = {sys.n} coordinates")
            out.append(int(item))
        else:
            raise ParameterError(label, f"expected coordinate indices or names, got {item!r}")
    return np.asarray(out, dtype=int)
