"""Double-precision constants and the checked return from logarithms (theory: error figures).

Determinants and adjugates of large systems are carried as ``mantissa *
exp(log_scale)``; :func:`checked_exp` is the one place where such a number
comes back to a plain double, and it raises instead of returning inf or a
silent zero.
"""

from __future__ import annotations

import numpy as np

from ..errors import ComputationError

__all__ = ["EPS", "LOG_MAX", "LOG_TINY", "checked_exp"]

#: Machine epsilon of double precision (unit roundoff times two).
EPS = float(np.finfo(float).eps)
#: Natural log of the largest positive double.
LOG_MAX = float(np.log(np.finfo(float).max))
#: Natural log of the smallest positive normal double.
LOG_TINY = float(np.log(np.finfo(float).tiny))


def checked_exp(log_value: np.ndarray | float, what: str, *, each: bool = False) -> np.ndarray:
    """``exp(log_value)``, raising when it overflows or underflows double precision.

    Underflow is an error when the largest value underflows (everything would be
    zero), or, with ``each=True``, when any finite value does.  NaN entries are
    ignored (and returned as NaN: callers pass them only for values they discard).

    Raises
    ------
    ComputationError
        Overflow, or underflow as described; the message names ``what``.
    """
    lv = np.asarray(log_value, dtype=float)
    finite = lv[np.isfinite(lv)]
    if finite.size and finite.max() > LOG_MAX:
        raise ComputationError(
            f"{what} overflows double precision (about 10^{finite.max() / np.log(10):.0f}); "
            f"rescale the system (units, for example mm and g instead of m and kg)"
        )
    low = finite.min() if each and finite.size else (finite.max() if finite.size else 0.0)
    if finite.size and low < LOG_TINY:
        raise ComputationError(
            f"{what} underflows double precision (about 10^{low / np.log(10):.0f}); "
            f"rescale the system (units, for example mm and g instead of m and kg)"
        )
    return np.exp(lv)
