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

__all__ = ["JORDAN_RANK_TOL", "ADJUGATE_RANK_TOL", "kernel_dimension", "null_basis"]

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
