"""numpy.linalg's eigvalsh, singular values and solve for double matrices, without the wrappers' checks (issue 27).

On the 8 x 8 to 17 x 17 matrices of a modal analysis the Python of ``numpy.linalg``
(conversions, type resolution, a second error-state context) costs about as much as
LAPACK itself: 7.4 against 4.7 us for ``eigvalsh`` of an 8 x 8 complex matrix.  These
functions call the same gufuncs (``numpy.linalg._umath_linalg``: the same LAPACK
routines with the same arguments, so the same numbers to the last bit) with the same
error handling (a LAPACK failure raises :class:`numpy.linalg.LinAlgError`), for 2-D
float64 or complex128 arrays; anything else, or a numpy without those gufuncs, goes
through ``numpy.linalg`` itself.
"""

from __future__ import annotations

import numpy as np

try:  # the gufuncs behind numpy.linalg (numpy.linalg._umath_linalg in numpy 1.x and 2.x)
    from numpy.linalg import _umath_linalg as gufuncs
except ImportError:  # pragma: no cover - a numpy without the module: the public functions
    gufuncs = None
if gufuncs is not None and not all(hasattr(gufuncs, name) for name in ("eigvalsh_lo", "svd", "solve")):
    gufuncs = None  # pragma: no cover - a numpy whose internal names differ: the public functions

__all__ = ["eigvalsh", "singular_values", "solve"]

#: The signature of each supported dtype's gufunc call (numpy.linalg's for double input).
_KIND = {np.dtype(np.float64): "d", np.dtype(np.complex128): "D"}


def _failed(err, flag):
    raise np.linalg.LinAlgError(f"LAPACK did not succeed ({err})")


def _errors():
    """numpy.linalg's error state around its gufuncs: an invalid result raises LinAlgError, the rest is silent."""
    return np.errstate(call=_failed, invalid="call", over="ignore", divide="ignore", under="ignore")


def eigvalsh(a: np.ndarray) -> np.ndarray:
    """``numpy.linalg.eigvalsh(a)`` (lower triangle) of a square 2-D matrix: ascending eigenvalues."""
    kind = _KIND.get(a.dtype) if gufuncs is not None and a.ndim == 2 else None
    if kind is None or a.shape[0] != a.shape[1]:
        return np.linalg.eigvalsh(a)
    with _errors():
        return gufuncs.eigvalsh_lo(a, signature=kind + "->d")


def singular_values(a: np.ndarray) -> np.ndarray:
    """``numpy.linalg.svd(a, compute_uv=False)`` of a 2-D matrix: descending singular values."""
    kind = _KIND.get(a.dtype) if gufuncs is not None and a.ndim == 2 else None
    if kind is None:
        return np.linalg.svd(a, compute_uv=False)
    with _errors():
        return gufuncs.svd(a, signature=kind + "->d")


def solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``numpy.linalg.solve(a, b)`` for a square 2-D ``a`` and a 2-D ``b`` of its dtype (LU with pivoting)."""
    kind = _KIND.get(a.dtype) if gufuncs is not None and a.ndim == 2 and b.ndim == 2 else None
    if kind is None or b.dtype != a.dtype or a.shape[0] != a.shape[1]:
        return np.linalg.solve(a, b)
    with _errors():
        return gufuncs.solve(a, b, signature=kind * 2 + "->" + kind)
