"""Input check of the frequency responses: angular frequencies (theory: conventions).

Each raises a :class:`~pinlin.ParameterError` naming the parameter, the
expected and the found value or shape.  Checks shared beyond ``frf`` live in
:mod:`pinlin.numerics.checks`.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError

__all__ = ["real_frequencies"]


def real_frequencies(omega, label: str = "omega") -> tuple[np.ndarray, bool]:
    """Finite real angular frequencies [rad/s] as a 1-D float array, and whether a scalar was given.

    Raises
    ------
    ParameterError
        Not real numbers (complex, bool, text), more than one dimension, empty, or non-finite.
    """
    try:
        w = np.asarray(omega)
    except (TypeError, ValueError):
        raise ParameterError(label, "expected real angular frequencies [rad/s]") from None
    if w.dtype == object or not np.issubdtype(w.dtype, np.number) or np.iscomplexobj(w) or w.dtype == bool:
        raise ParameterError(label, f"expected real angular frequencies [rad/s], got {omega!r:.80} (dtype {w.dtype})")
    scalar = w.ndim == 0
    if w.ndim > 1 or w.size == 0:
        raise ParameterError(label, f"expected a number or a non-empty 1-D array, got shape {w.shape}")
    w = np.atleast_1d(w).astype(float)
    bad = ~np.isfinite(w)
    if np.any(bad):
        raise ParameterError(label, f"must be finite; entry {int(np.flatnonzero(bad)[0])} is {w[bad][0]}")
    return w, scalar
