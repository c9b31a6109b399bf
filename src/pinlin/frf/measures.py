"""The measures of an evaluation of H(s) B: ||L(s)|| without forming L(s), and ||L(s) X - B|| (theory: error figures).

Used by every method of the engine (:mod:`pinlin.frf.engine`) for the relative
defect ||L X - B|| / (||L|| ||X|| + ||B||) and for the amplification test at a pole.
"""

from __future__ import annotations

import numpy as np

from ..errors import ComputationError
from ..linearization.system import LinearizedSystem
from ..numerics import CHUNK_BYTES, EPS, chunks

__all__ = ["NORM_CANCEL", "stiffness_stack", "stiffness_norms", "residuals"]

#: ||L(s)||_F^2 from its expansion in |s| and the six inner products of M, C, K is exact up to
#: about 10 eps W^2 (W = |s|^2 ||M|| + |s| ||C|| + ||K||); where ||L||^2 < NORM_CANCEL eps W^2 the
#: terms cancel (near a resonance of a proportional system) and the norm is recomputed from L(s)
#: itself, so that every norm used is accurate to 1e-3 relative or better.
NORM_CANCEL = 1e4
#: Copies of an (n, m) block alive at once in :func:`residuals` (X, M X, C X, K X and L X - B).
_BLOCK_COPIES = 5


def stiffness_stack(sys: LinearizedSystem, s: np.ndarray) -> np.ndarray:
    """L(s_k) = s_k^2 M + s_k C + K for a 1-D array of points: (len(s), n, n) complex."""
    z = np.asarray(s, dtype=complex)[:, None, None]
    with np.errstate(over="ignore", invalid="ignore"):  # (callers check ||L|| for overflow and raise)
        L = z * sys.M  # Horner, in place: (s M + C) s + K
        L += sys.C
        L *= z
        L += sys.K
    return L


def stiffness_norms(sys: LinearizedSystem, s: np.ndarray, values=None, label: str = "s") -> np.ndarray:
    """||L(s)||_F per point without forming L(s), except where its terms cancel (see NORM_CANCEL).

    .. math::
        \\|L(s)\\|_F^2 = |s|^4 \\langle M,M\\rangle + |s|^2 \\langle C,C\\rangle + \\langle K,K\\rangle
        + 2\\,\\mathrm{Re}(s^2 \\bar s) \\langle M,C\\rangle + 2\\,\\mathrm{Re}(s^2) \\langle M,K\\rangle
        + 2\\,\\mathrm{Re}(s) \\langle C,K\\rangle

    Raises
    ------
    ComputationError
        L(s) overflows double precision at some point.
    """
    values = s if values is None else values
    M, C, K = (np.asarray(A, dtype=float) for A in (sys.M, sys.C, sys.K))
    MM, CC, KK, MC, MK, CK = (float(np.vdot(A, B)) for A, B in ((M, M), (C, C), (K, K), (M, C), (M, K), (C, K)))
    a = np.abs(s)
    with np.errstate(over="ignore", invalid="ignore"):
        W = a * a * np.sqrt(MM) + a * np.sqrt(CC) + np.sqrt(KK)
        sq = (a**4 * MM + a * a * CC + KK + 2 * np.real(s * s * np.conj(s)) * MC + 2 * np.real(s * s) * MK
              + 2 * np.real(s) * CK)
    bad = ~(np.isfinite(W) & np.isfinite(sq))
    if np.any(bad):
        k = int(np.flatnonzero(bad)[0])
        raise ComputationError(
            f"L(s) overflows double precision at {label}[{k}] = {values[k]:.6g}: rescale the system "
            f"(units, or time in other units) or leave out such points"
        )
    out = np.sqrt(np.maximum(sq, 0.0))
    cancel = np.flatnonzero(sq < NORM_CANCEL * EPS * W * W)
    for sl in chunks(cancel.size, sys.n):
        idx = cancel[sl]
        out[idx] = np.linalg.norm(stiffness_stack(sys, s[idx]), axis=(1, 2))
    return out


def residuals(sys: LinearizedSystem, s: np.ndarray, X: np.ndarray, B: np.ndarray) -> np.ndarray:
    """||L(s) X(s) - B||_F per point for X (len(s), n, m): three real matrix products per block of points."""
    F, n, m = X.shape
    per = max(1, CHUNK_BYTES // (_BLOCK_COPIES * np.dtype(complex).itemsize * n * m))
    M, C, K = (np.asarray(A, dtype=float) for A in (sys.M, sys.C, sys.K))
    out = np.empty(F)
    for start in range(0, F, per):
        sl = slice(start, min(F, start + per))
        f = sl.stop - sl.start
        # columns ordered (point, input); complex numbers as pairs of reals for one real product each
        flat = np.ascontiguousarray(np.moveaxis(X[sl], 0, 1)).reshape(n, f * m).view(float)
        MX, CX, KX = ((A @ flat).view(complex) for A in (M, C, K))
        z = np.repeat(s[sl], m)
        R = (z * z) * MX + z * CX + KX - np.tile(B, (1, f))
        out[sl] = np.linalg.norm(R.reshape(n, f, m), axis=(0, 2))
    return out
