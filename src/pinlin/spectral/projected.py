"""Jordan structure of a cluster from the pencil projected on its deflating subspace (theory: spectrum).

The block Toeplitz ranks of :mod:`pinlin.spectral.multiplicity` take the SVDs of
T_1, T_2, ..., T_{p+1} (sizes n, 2n, ..., (p+1)n) for a cluster with chains of
length p.  The chains of an eigenvalue of L are those of the scaled companion
pencil (A, B) = ([[-C_s, -K_s], [I, 0]], [[M_s, 0], [0, I]]) (a strong
linearization), and those live in the cluster's right deflating subspace: with
orthonormal Q (2n x m) spanning it and W spanning B Q,

.. math::  A Q = W A_{11} + R, \\qquad B Q = W B_{11},

the m x m pencil (A_11, B_11) has the cluster's eigenvalues and Jordan structure
exactly for the pencil (A - R Q^H, B).  The partial multiplicities are then the
ranks of the Toeplitz matrices of the small pencil P(mu) = A_11 - mu B_11 at the
cluster's mean (blocks P(mu_0) and -B_11; sizes m, 2m, ...).

The subspace: the computed vectors z_i = (mu_i x_i, x_i) of the members span it
only roughly when the cluster is defective (nearly parallel vectors, accurate to
about eta^(1/p)); a few steps of inverse subspace iteration with
(A - s B)^{-1} B, at a shift s beyond the cluster's spread and well inside the
distance to the other eigenvalues (their geometric mean), damp the rest by
|s - mu_0| / distance per step and keep the cluster's directions apart
(one LU of L(s), n x n, then O(n^2 m) per step).  The rank decisions are
accepted only when

- the residual R is below the rank threshold by :data:`PROJECTION_MARGIN`;
- no singular value of the small Toeplitz matrices lies within that margin
  of the threshold (else the decision is left to the full Toeplitz ranks);
- the chains add up to the cluster's size;
- the other eigenvalues cannot reach the full Toeplitz ranks' threshold: the
  part of T_k^{-1} from them (the Taylor coefficients of sum_j x_j y_j^T /
  ((lam - lam_j) y_j^T L'(lam_j) x_j) at the mean) has norm at most
  sum_{i<k} sum_j gamma^i s_j / (w_j g_j^(i+1)) (scaled units; s_j the
  sensitivity, w_j the weight, g_j = |center - lam_j| - r_j), which must stay
  below 1 / (margin * threshold), so that the full ranks would count the same.

Otherwise the cluster takes the full Toeplitz ranks (the caller's fallback).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from ..numerics.floating import EPS
from ..numerics.norms import frobenius
from ..numerics.rank import chains_from_kernels
from .problem import QuadraticProblem

__all__ = ["PROJECTION_MARGIN", "PROJECTION_STEPS", "PROJECTION_MIN_ORDER", "projected_pays", "projected_structure"]

#: Factor by which the projected decisions must clear the rank threshold (the
#: residual below it, every singular value outside [threshold / margin, threshold * margin]).
PROJECTION_MARGIN = 10.0

#: Most steps of inverse subspace iteration before the projected path gives up.
PROJECTION_STEPS = 6

#: Smallest n for which :func:`projected_pays`: below it the SVDs of T_1, T_2, T_3 (sizes n, 2n, 3n) take
#: less time than the projected path's fixed cost of numpy calls (about 0.5 ms).  Measured (one BLAS thread,
#: thread CPU, medians of interleaved calls) on chains (2, 2, 2) and (2, 1) mixed orthogonally into n modes:
#: projected 0.5 / 0.6 / 0.6 / 0.7 ms against full ranks 0.3 / 0.6 / 1.1 / 2.2 ms at n = 16 / 24 / 32 / 44.
PROJECTION_MIN_ORDER = 32

#: First step of the inverse iteration after which the residual is checked (the rate is about
#: sqrt(spread / distance) per step, below 1e-3 for a double root: three steps from a poor start).
FIRST_CHECK = 3

#: A member's vector whose component outside those before it is below this fraction of the
#: largest is replaced by a generic vector at the start of the iteration.
START_INDEPENDENCE = 1e-4

#: The golden angle [rad]: the phases of the generic start vectors.
GOLDEN_ANGLE = np.pi * (3.0 - np.sqrt(5.0))

#: LAPACK's complex LU factorization and solve: getrf reports an exactly singular L(s) in ``info``, where
#: scipy's ``lu_factor`` warns (read-only after import: shared by threads safely).
_LU = sla.get_lapack_funcs(("getrf", "getrs"), dtype=np.complex128)


def projected_pays(n: int, m: int) -> bool:
    """The projected path is worth trying for a cluster of m eigenvalues of an n x n problem.

    n of at least :data:`PROJECTION_MIN_ORDER` and a cluster of at most half the
    problem's size (its Toeplitz matrices, of sizes m, 2m, ..., smaller than the full
    ones of sizes n, 2n, ...).
    """
    return n >= PROJECTION_MIN_ORDER and 2 * m <= n


def projected_structure(
    problem: QuadraticProblem,
    lam: np.ndarray,
    indices: tuple[int, ...],
    center: complex,
    evidence,
    rank_tol: float,
    threshold: float,
) -> tuple[tuple[int, ...], tuple[int, ...]] | None:
    """(partial multiplicities, dim ker T_k) of a cluster from its projected pencil, or None (see module doc).

    ``evidence`` is the computed spectrum's
    :class:`~pinlin.spectral.multiplicity.ClusterEvidence`; ``threshold`` the full
    Toeplitz ranks' threshold in the units of L
    (:func:`~pinlin.spectral.multiplicity.rank_threshold`).  None: the projected
    decision is not certain, the full Toeplitz ranks decide.
    """
    ii = list(indices)
    m = len(ii)
    gamma = problem.scaling.gamma
    reach = _resolvent_reach(lam, ii, center, evidence, gamma, m + 1)
    if reach is None or not reach[1][0] * (PROJECTION_MARGIN * threshold) < 1.0:
        return None
    mu0 = complex(center) / gamma
    pencil = _projected_pencil(problem, lam[ii] / gamma, mu0, evidence.right[:, ii], reach[0], rank_tol)
    if pencil is None:
        return None
    A11, B11, residual = pencil
    N = A11 - mu0 * B11
    nB = frobenius(B11)
    tau = rank_tol * max(frobenius(A11) + abs(mu0) * nB, nB)
    if not residual * PROJECTION_MARGIN <= tau:
        return None
    low, high = tau / PROJECTION_MARGIN, tau * PROJECTION_MARGIN

    def kernel_dimension_of(k: int) -> int | None:
        s = np.linalg.svd(_pencil_toeplitz(N, B11, k), compute_uv=False)
        if np.count_nonzero((s > low) & (s < high)):
            return None
        return int(np.count_nonzero(s <= tau))

    out = chains_from_kernels(kernel_dimension_of, m + 1, m)
    if out is None or sum(out[0]) != m:
        return None
    if not reach[1][len(out[1]) - 1] * (PROJECTION_MARGIN * threshold) < 1.0:
        return None
    return out


def _resolvent_reach(lam, ii, center, evidence, gamma, k_max):
    """(least scaled distance of the other eigenvalues, bounds on the norm of their part of T_1^{-1} ...
    T_{k_max}^{-1} in units of 1 / L), or None when some other eigenvalue's error disk reaches the center."""
    out = np.ones(lam.shape[0], dtype=bool)
    out[ii] = False
    if not out.any():
        return np.inf, np.zeros(k_max)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        gap = np.abs(lam[out] - center) - evidence.bound[out]
        if not gap.min() > 0:
            return None
        term = evidence.sensitivity[out] / (evidence.weight[out] * gap)  # the Taylor coefficient i = 0
        ratio = gamma / gap
        sums = np.empty(k_max)
        for i in range(k_max):
            sums[i] = np.sum(term)
            term = term * ratio
        totals = np.cumsum(sums)
    if not np.all(np.isfinite(totals)):
        return None
    return float(gap.min()) / gamma, totals


def _projected_pencil(problem: QuadraticProblem, mu, mu0: complex, X, gap: float, rank_tol: float):
    """(A_11, B_11, ||R||_F) of the scaled companion pencil on the cluster's deflating subspace, or None.

    Starts from the members' vectors (mu_i x_i, x_i) and takes inverse subspace
    iteration steps at the shift mu_0 + rho, rho the geometric mean of the
    cluster's spread (at least sqrt(eps) |mu_0|, the split of a double root) and
    the distance ``gap`` to the other eigenvalues, until the residual is below
    rank_tol times the pencil's size over the margin squared.
    """
    Ms, Cs, Ks = problem.scaled()
    n = Ms.shape[0]
    size = max(abs(mu0), 1.0)
    spread = max(float(np.max(np.abs(mu - mu0))), np.sqrt(EPS) * size)
    rho = np.sqrt(spread * gap) if np.isfinite(gap) else 10.0 * spread
    if not rho <= gap / 4:
        return None  # the cluster is not apart from the rest of the spectrum
    shift = mu0 + rho
    scale = np.sqrt(frobenius(Ms) ** 2 + frobenius(Cs) ** 2 + frobenius(Ks) ** 2 + n)  # ||A||_F + ||B||_F, about
    target = rank_tol * scale / PROJECTION_MARGIN**2
    Q, replaced = _start(np.concatenate((X * mu, X)))
    lu = piv = None
    for step in range(PROJECTION_STEPS + 1):
        # the residual is checked on an unaltered start and from step FIRST_CHECK on (each check is two QRs)
        if (step == 0 and not replaced) or step >= FIRST_CHECK:
            pencil = _on_subspace(Ms, Cs, Ks, Q)
            if pencil[2] <= target:
                return pencil
        if step == PROJECTION_STEPS:
            return None
        getrf, getrs = _LU
        if lu is None:
            lu, piv, info = getrf((shift * shift) * Ms + shift * Cs + Ks)
            if info != 0:
                return None  # L(s) exactly singular: s is an eigenvalue
        # (A - s B) w = B q: L(s) w_2 = -(M q_1 + (C + s M) q_2), w_1 = q_2 + s w_2
        Q1, Q2 = Q[:n], Q[n:]
        W2, info = getrs(lu, piv, Ms @ Q1 + (Cs + shift * Ms) @ Q2)
        W2 = -W2
        if info != 0 or not np.isfinite(W2).all():
            return None
        Q, _ = np.linalg.qr(np.concatenate((Q2 + shift * W2, W2)))
    return None


def _on_subspace(Ms, Cs, Ks, Q):
    """(A_11, B_11, ||R||_F): A Q = W A_11 + R and B Q = W B_11 (W, B_11 the QR factors of B Q)."""
    n = Ms.shape[0]
    Q1, Q2 = Q[:n], Q[n:]
    AQ = np.concatenate((-(Cs @ Q1) - Ks @ Q2, Q1))
    W, B11 = np.linalg.qr(np.concatenate((Ms @ Q1, Q2)))
    A11 = W.conj().T @ AQ
    return A11, B11, frobenius(AQ - W @ A11)


def _start(Z: np.ndarray) -> tuple[np.ndarray, bool]:
    """Orthonormal columns spanning the members' vectors, those nearly dependent on the ones before them
    replaced by generic vectors (True when some were).

    A defective cluster's computed vectors are nearly parallel (exactly equal when
    its members are): the iteration must start with a component along every
    direction of the subspace, which a vector left over from a rank-deficient
    QR need not have (it may lie in the other eigenvalues' subspace and stay there
    up to rounding).  The replacements exp(i phi j k) (phi the golden angle, k the
    column) lie in no invariant subspace but by coincidence.
    """
    Q, R = np.linalg.qr(Z)
    d = np.abs(np.diagonal(R))
    weak = np.flatnonzero(d <= START_INDEPENDENCE * d.max())
    if not weak.size:
        return Q, False
    Z = Z.copy()
    rows = np.arange(Z.shape[0])
    for k in weak:
        Z[:, k] = np.exp(1j * GOLDEN_ANGLE * (k + 1) * rows)
    return np.linalg.qr(Z)[0], True


def _pencil_toeplitz(N: np.ndarray, B: np.ndarray, k: int) -> np.ndarray:
    """T_k of P(mu) = A - mu B at mu_0 from P(mu_0) = N and P' = -B: N on the diagonal, -B below it."""
    m = N.shape[0]
    T = np.zeros((k * m, k * m), dtype=complex)
    for i in range(k):
        T[i * m : (i + 1) * m, i * m : (i + 1) * m] = N
        if i:
            T[i * m : (i + 1) * m, (i - 1) * m : i * m] = -B
    return T
