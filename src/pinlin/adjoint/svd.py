"""The adjugate by the singular value decomposition, in logarithms (theory: adjoint).

.. math::
    L = U \\operatorname{diag}(s) V^H,\\qquad
    \\operatorname{adj} L = \\det U \\,\\det V^H\\; V \\operatorname{diag}\\Bigl(\\prod_{j \\ne i} s_j\\Bigr) U^H

stays accurate where L is singular (at eigenvalues, where the adjugate of a
matrix of rank n - 1 is the rank-one matrix ``prod_{j<n} s_j v_n u_n^H`` up to
phase).  The products of singular values are formed in logarithms so that
nothing overflows before the final, checked conversion
(:func:`pinlin.numerics.checked_exp`).  Used by :func:`pinlin.adjoint.adjugate`,
the circle fits of the adjugate polynomial and the eigenvectors from the adjugate.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError

__all__ = ["SvdAdjugate", "svd_adjugate", "residual_scaled", "det_over_scale"]


@dataclass(frozen=True, kw_only=True)
class SvdAdjugate:
    """Batched SVD-form adjugates: ``adj = scaled * exp(log_scale)``, ``det = phase * exp(log_det)``."""

    scaled: np.ndarray  # (N, n, n), largest singular value 1
    log_scale: np.ndarray  # (N,)
    phase: np.ndarray  # (N,) complex, |phase| = 1
    log_det: np.ndarray  # (N,), -inf for an exactly singular L
    singular_values: np.ndarray  # (N, n) of L, descending
    log_norm: np.ndarray  # (N,) log ||L||_F


def svd_adjugate(L: np.ndarray) -> SvdAdjugate:
    """Adjugates of a stack of matrices (N, n, n) by the SVD form, in logarithms."""
    L = np.asarray(L, dtype=complex)
    N, n, _ = L.shape
    if not np.all(np.isfinite(L)):
        raise ComputationError(
            "L(lam) = lam^2 M + lam C + K overflows double precision at the point asked "
            "(|lam| too large for the data): rescale time or the units"
        )
    norm = np.linalg.norm(L.reshape(N, -1), axis=1)
    zero = norm == 0
    safe = np.where(zero, 1.0, norm)
    U, s, Vh = np.linalg.svd(L / safe[:, None, None])
    with np.errstate(divide="ignore"):
        log_s = np.log(s)
    nz = np.isfinite(log_s)
    n_zero = np.sum(~nz, axis=1)
    total = np.sum(np.where(nz, log_s, 0.0), axis=1)
    # log prod_{j != i} s_j: one exact zero kills every term but its own, two kill all
    log_d = np.where(nz, total[:, None] - np.where(nz, log_s, 0.0), total[:, None])
    log_d = np.where((n_zero[:, None] == 1) & nz, -np.inf, log_d)
    log_d = np.where(n_zero[:, None] >= 2, -np.inf, log_d)
    log_norm = np.log(safe)
    log_d = log_d + (n - 1) * log_norm[:, None]
    log_det = np.where(n_zero > 0, -np.inf, total + n * log_norm)
    log_scale = np.max(log_d, axis=1)
    finite = np.isfinite(log_scale)
    log_scale_safe = np.where(finite, log_scale, 0.0)
    with np.errstate(invalid="ignore"):
        w = np.where(np.isfinite(log_d), np.exp(log_d - log_scale_safe[:, None]), 0.0)
    phase = np.linalg.det(U) * np.linalg.det(Vh)
    phase = phase / np.abs(phase)
    V = np.conj(np.swapaxes(Vh, 1, 2))
    Uh = np.conj(np.swapaxes(U, 1, 2))
    scaled = phase[:, None, None] * np.matmul(V * w[:, None, :], Uh)
    if n == 1:  # adj of a 1 x 1 matrix is [[1]], also for L = 0
        scaled = np.ones((N, 1, 1), dtype=complex)
        log_scale = np.zeros(N)
    elif np.any(zero):
        scaled[zero] = 0.0
        log_scale = np.where(zero, -np.inf, log_scale)
    return SvdAdjugate(
        scaled=scaled, log_scale=log_scale, phase=phase, log_det=log_det, singular_values=s * safe[:, None],
        log_norm=log_norm,
    )


def residual_scaled(L: np.ndarray, A: np.ndarray, p_over_scale: complex) -> float:
    """``max(||L A - p I||, ||A L - p I||) / (||L|| ||A||)`` with A and p divided by a common scale."""
    nl = np.linalg.norm(L)
    na = np.linalg.norm(A)
    if nl == 0 or na == 0:
        return 0.0 if p_over_scale == 0 else float("inf")
    Ls = L / nl
    ps = p_over_scale / nl
    eye = ps * np.eye(L.shape[0])
    r1 = np.linalg.norm(Ls @ A - eye)
    r2 = np.linalg.norm(A @ Ls - eye)
    return float(max(r1, r2) / na)


def det_over_scale(f: SvdAdjugate, i: int = 0) -> complex:
    """``det L / exp(log_scale)`` of matrix i of ``f``: the p that goes with the scaled adjugate (0 if singular)."""
    if not (np.isfinite(f.log_det[i]) and np.isfinite(f.log_scale[i])):
        return 0j
    return complex(f.phase[i] * np.exp(f.log_det[i] - f.log_scale[i]))
