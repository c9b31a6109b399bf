"""The one check of numeric parameters the model layer shares (elements, constraints): numbers, not text or flags.

numpy turns ``"5"`` and ``True`` into the numbers 5 and 1 without a word, so
``JointSpring("j", stiffness="5")`` would build a spring; a parameter given as
text or a boolean is a mistake (a scene built from strings read elsewhere, a
flag passed in the wrong place), refused here with the element and parameter named.
"""

from __future__ import annotations

import numbers

import numpy as np

from ..errors import ParameterError

__all__ = ["numeric_array", "numeric_scalar"]

#: numpy dtype kinds that are numbers pinlin accepts: signed and unsigned integers, floats.
_NUMBER_KINDS = "iuf"


def _refuse(value, label: str, what: str) -> ParameterError:
    return ParameterError(label, f"expected {what}, got {type(value).__name__} {value!r}")


def numeric_array(value, label: str, what: str = "a number or an array of numbers") -> np.ndarray:
    """``value`` as a float array; text, bytes, booleans, complex numbers and None (also inside sequences) refused.

    Finiteness, sign and shape are the caller's checks (they differ by parameter).

    Raises
    ------
    ParameterError
        Named ``label``: a string, bytes, a boolean, a complex number, None, or a
        sequence holding any of them, or something that is not numbers at all.
    """
    if isinstance(value, (str, bytes, bool, np.bool_)):
        raise _refuse(value, label, what)
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        raise _refuse(value, label, what) from None
    if arr.dtype.kind == "O":
        if not all(isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_)) for v in arr.flat):
            raise _refuse(value, label, what)
    elif arr.dtype.kind not in _NUMBER_KINDS:
        raise _refuse(value, label, what)
    try:
        return np.array(arr, dtype=float)
    except (TypeError, ValueError):
        raise _refuse(value, label, what) from None


def numeric_scalar(value, label: str) -> float:
    """One number as float (see :func:`numeric_array`); finiteness and sign are the caller's checks.

    Raises
    ------
    ParameterError
        Named ``label``: not a single real number (text, a boolean, a sequence, ...).
    """
    arr = numeric_array(value, label, "a number")
    if arr.ndim != 0:
        raise _refuse(value, label, "a number")
    return float(arr)
