"""Numerical rank decisions and their two default tolerances (theory: spectrum).

Two decisions with different needs, hence two names:

- :data:`JORDAN_RANK_TOL` decides which singular values of the block Toeplitz
  matrices T_k (Jordan structure) are zero.  It must be *large*: at a computed
  multiple eigenvalue of index p the singular values that are zero in exact
  arithmetic are left at about eta^(1/p) (1e-8 for a double root).
- :data:`ADJUGATE_RANK_TOL` decides that the second smallest singular value of
  L(lam) is *not* zero, so that adj L(lam) has rank one.  It must be *small*:
  L(lam) of a badly scaled system (mass ratios of 1e8 in a 50-link chain) has
  s_{n-1} down to 1e-9 s_1 at simple eigenvalues, while a multiple eigenvalue
  of geometric multiplicity 2 leaves it at rounding level (kappa eps s_1).
"""

from __future__ import annotations

import numpy as np

__all__ = ["JORDAN_RANK_TOL", "ADJUGATE_RANK_TOL", "kernel_dimension", "null_basis", "chains_from_kernels"]

#: Default relative singular value threshold of the Jordan (Toeplitz) rank decisions.
JORDAN_RANK_TOL = 1e-8
#: Default relative threshold above which s_{n-1}(L) makes adj L(lam) of rank one.
ADJUGATE_RANK_TOL = 1e-12


def kernel_dimension(A: np.ndarray, threshold: float) -> int:
    """Number of singular values of A at or below the absolute ``threshold``."""
    s = np.linalg.svd(A, compute_uv=False)
    return int(np.sum(s <= threshold))


def null_basis(A: np.ndarray, threshold: float) -> np.ndarray:
    """Orthonormal columns spanning the right singular vectors of singular values at or below ``threshold``."""
    _, s, Vh = np.linalg.svd(A)
    r = int(np.sum(s > threshold))
    return Vh[r:].conj().T


def chains_from_kernels(kernel_dimension_of, max_length: int, max_total: int | None = None):
    """Partial multiplicities from dim ker T_k, k = 1, 2, ... (theory: spectrum).

    ``kernel_dimension_of(k)`` gives dim ker T_k, or None when it cannot be decided;
    it is called for k = 1, 2, ... until no chain is longer than k - 1, k =
    ``max_length``, or dim ker T_k exceeds ``max_total``.  dim ker T_k -
    dim ker T_{k-1} counts the chains of length >= k; a count above the previous
    one is rank noise and is capped by it.

    Returns
    -------
    (partial, kernel_dims) or None
        Chain lengths longest first and dim ker T_k for the k computed; None when
        some kernel dimension was undecided.
    """
    dims = [0]
    counts: list[int] = []  # counts[k-1] = number of chains of length >= k
    for k in range(1, max_length + 1):
        d = kernel_dimension_of(k)
        if d is None:
            return None
        dims.append(d)
        if max_total is not None and d > max_total:
            break
        c = d - dims[k - 1]
        if counts and c > counts[-1]:
            c = counts[-1]
        if c <= 0:
            break
        counts.append(c)
    partial: list[int] = []
    for length in range(len(counts), 0, -1):
        longer = counts[length] if length < len(counts) else 0
        partial += [length] * (counts[length - 1] - longer)
    return tuple(partial), tuple(dims[1:])
