"""Norms, in one home: the fast Frobenius norm of the assembly's hot paths, the wide-range one of the
error figures, and column norms without over- or underflow.

- :func:`fro` -- ``math.hypot`` up to :data:`SMALL_NORM` entries, else one dot product (rescaled
  only when the sum of squares overflows): the norm of the per-call linearization, where the fixed
  cost of a numpy reduction dominates;
- :func:`frobenius` -- exact over the whole floating-point range (entries from 1e-300 to 1e300):
  the weights of backward errors and condition numbers, where an underflowed square would bias the figure;
- :func:`coefficient_norms` -- (||M||, ||C||, ||K||) by :func:`frobenius`;
- :func:`column_norms` -- 2-norm of each column of a stack, by the same window rule.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["fro", "frobenius", "coefficient_norms", "column_norms", "SMALL_NORM", "SQUARES_WINDOW"]

#: Arrays of at most this many entries have their norm taken by ``math.hypot`` of a Python
#: list: for a 2 x 2 or 4 x 4 matrix that is a third of a numpy reduction's fixed cost.
SMALL_NORM = 32

#: Window of a plain sum of squares in which it is accurate: no square overflowed (an entry
#: above 1e140 squares beyond 1e280) and the squares that underflowed change it by less than
#: n^2 1e-28 relative.  Outside it the norm is taken of the matrix divided by its largest entry.
SQUARES_WINDOW = (1e-280, 1e280)


def fro(a: np.ndarray) -> float:
    """Frobenius norm, overflow-safe (cheaper than ``np.linalg.norm`` on small arrays).

    Up to :data:`SMALL_NORM` entries, ``math.hypot`` (overflow-safe and accurate by
    itself); else the square root of one dot product, and when its sum of squares
    overflows (entries beyond about 1e154; BLAS's dot does not warn) again from the scaled
    array.  Infinite or NaN entries give a non-finite norm either way.
    """
    if a.size <= SMALL_NORM:  # a vector's tolist is flat already: no ravel
        return math.hypot(*(a.tolist() if a.ndim == 1 else a.ravel().tolist()))
    square = np.vdot(a, a)  # flattens; one call
    if square < math.inf:  # False for inf and NaN
        return math.sqrt(square)
    flat = a.ravel()
    big = float(np.max(np.abs(flat)))
    if not math.isfinite(big) or big == 0.0:
        return big
    with np.errstate(over="ignore"):
        scaled = flat / big
        return big * math.sqrt(float(np.dot(scaled, scaled)))


def frobenius(A) -> float:
    r"""||A||_F without overflow or underflow of the squares (entries from 1e-300 to 1e300).

    .. math::  \|A\|_F = s\,\|A / s\|_F,\qquad s = \max_{ij} |a_{ij}|

    (the plain sum of squares where it is within :data:`SQUARES_WINDOW`).
    """
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        return _frobenius(np.asarray(A))


def _frobenius(A: np.ndarray) -> float:
    """:func:`frobenius` with floating-point warnings already silenced by the caller."""
    if A.size and A.dtype.kind == "f":
        flat = A.ravel()
        q = float(np.dot(flat, flat))
        if SQUARES_WINDOW[0] < q < SQUARES_WINDOW[1]:
            return math.sqrt(q)
    s = float(np.max(np.abs(A))) if A.size else 0.0
    if s == 0 or not math.isfinite(s):
        return s
    return float(s * np.linalg.norm(A / s))


def coefficient_norms(M, C, K) -> tuple[float, float, float]:
    """Frobenius norms (||M||, ||C||, ||K||): the weights of eta and kappa (theory: spectrum)."""
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        return _frobenius(np.asarray(M)), _frobenius(np.asarray(C)), _frobenius(np.asarray(K))


def column_norms(A: np.ndarray) -> np.ndarray:
    r"""2-norm of each column (axis -2) of a real or complex (..., n, k) array, without over- or underflow.

    .. math::  \|a\| = s\,\|a / s\|,\qquad s = \max_i |a_i|

    The plain sum of squares is used where it is safely in range (see
    ``SQUARES_WINDOW``), the scaled form above for the other columns.
    """
    A = np.asarray(A)
    if A.shape[-2] == 0:
        return np.zeros(A.shape[:-2] + A.shape[-1:])
    if np.iscomplexobj(A):
        if A.dtype == np.complex128 and A.flags.c_contiguous:  # (re, im) pairs as one real array
            f = A.view(float)
            pairs = np.einsum("...ij,...ij->...j", f, f)  # (no overflow warning: the window below decides)
            total = pairs[..., 0::2] + pairs[..., 1::2]
        else:
            total = np.einsum("...ij,...ij->...j", A.real, A.real) + np.einsum("...ij,...ij->...j", A.imag, A.imag)
    else:
        total = np.einsum("...ij,...ij->...j", A, A)
    lo, hi = SQUARES_WINDOW
    # every sum in the window (a NaN is not: the reductions propagate it and the comparisons fail)
    if not total.size or (lo < total.min() and total.max() < hi):
        return np.sqrt(total)
    ok = (total > lo) & (total < hi)
    s = np.max(np.abs(A), axis=-2)
    safe = np.where((s > 0) & np.isfinite(s), s, 1.0)
    # real divisions: a complex one may go through 1/s, which overflows for a subnormal s
    re = A.real / safe[..., None, :]
    scaled = np.einsum("...ij,...ij->...j", re, re)
    if np.iscomplexobj(A):
        im = A.imag / safe[..., None, :]
        scaled = scaled + np.einsum("...ij,...ij->...j", im, im)
    return np.where(ok, np.sqrt(np.where(ok, total, 0.0)), safe * np.sqrt(scaled))
