"""Multiple eigenvalues: clusters and their partial multiplicities (theory: spectrum).

The partial multiplicities m_1 >= m_2 >= ... of an eigenvalue lam0 (the
lengths of its Jordan chains) follow from the ranks of the block Toeplitz
matrices

.. math::
    T_k = \\begin{bmatrix} L & & \\\\ L' & L & \\\\ L''/2 & L' & L \\\\
          & \\ddots & & \\ddots \\end{bmatrix}  \\quad (k \\times k \\text{ blocks}),
    \\qquad \\dim\\ker T_k = \\sum_i \\min(m_i, k),

so dim ker T_k - dim ker T_{k-1} counts the chains of length >= k.  Ranks are
decided on the Fan-Lin-Van Dooren scaled problem (all blocks of size about one):
singular values below ``rank_tol`` times the size of the blocks,
max(|mu0|^2 ||M|| + |mu0| ||C|| + ||K||, 2 |mu0| ||M|| + ||C||, ||M||), count as zero.

Rounding splits an eigenvalue with chains of length p into p eigenvalues about
eta^(1/p) |lam| apart; :func:`pinlin.numerics.find_clusters` regroups computed
eigenvalues closer than ``cluster_tol`` (relative), and the Toeplitz ranks at
the cluster's mean (which is accurate to about eta, unlike its members) then
tell its structure (:func:`analyse_cluster`).

Most clusters of a real robot are semisimple (equal springs on identical
fingers, symmetric limbs).  For them :func:`semisimple_certificate` decides
dim ker L(center) = m without any singular value decomposition, from the
computed eigenpairs alone, in O(n m^2) operations instead of the SVDs of T_1
and T_2 (sizes n and 2n, O(n^3) each):

- at least m singular values of L(center) are small: for orthonormal columns
  Q spanning the cluster's unit vectors X, sigma_{n-m+1}(L) <= ||L Q||_2
  (interlacing) <= ||L X||_F / sigma_min(X), and ||L(center) x_i|| is at most
  eta_i w_i + d_i ||L'(lam_i)|| + d_i^2 ||M|| (d_i = |lam_i - center|): when
  that bound is below threshold / :data:`CERTIFICATE_MARGIN`, with sigma_min(X)
  from the m x m Gram matrix, no product with L is formed; on the
  symmetric and proportional paths (a symmetric definite pencil, vectors shared
  by the pairs) the eigenvalue is semisimple by theorem unless a pair's two
  roots fall into one cluster (a rigid-body zero or critical damping), and the
  residual is replaced by the members' distance to the center (plus their
  error bounds) times ||L'||;
- at most m are: with every other eigenvalue semisimple, the resolvent
  L(lam)^{-1} = sum_j x_j y_j^T / ((lam - lam_j) y_j^T L'(lam_j) x_j) splits
  into the cluster's m terms (rank m) and the rest, whose norm is at most
  sum_{j not in the cluster} s_j / (w_j (|center - lam_j| - r_j)) (s_j the
  sensitivity, w_j the weight, r_j the error bound of lam_j); when that sum is
  below 1 / (margin * threshold), sigma_{n-m}(L) > margin * threshold.

Then dims = (m,) and the partial multiplicities are (1, ..., 1), exactly what
the Toeplitz ranks give whenever dim ker T_1 = m (T_2 cannot change them then:
the counts of longer chains are capped by the algebraic multiplicity).  When a
test is not met with its margin (a defective cluster, nearly parallel
vectors, another eigenvalue within reach of the threshold) the cluster takes
the Toeplitz ranks as before.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError
from ..numerics.floating import EPS
from ..numerics.norms import frobenius
from ..numerics.rank import JORDAN_RANK_TOL, chains_from_kernels, kernel_dimension
from ..results import Result
from .problem import QuadraticProblem
from .projected import projected_pays, projected_structure

__all__ = ["Cluster", "ClusterEvidence", "analyse_cluster", "semisimple_certificate", "partial_multiplicities", "toeplitz", "derivative_blocks", "block_scale"]

#: A cluster closed under conjugation has members whose imaginary parts cancel
#: to a few ulps of their total: within this many eps its mean is taken real.
CONJUGATE_SUM_ULPS = 4.0

_CLUSTER_METHOD = "dim ker T_k of the block Toeplitz matrices at the cluster mean (scaled problem, SVD)"
_CERTIFIED_METHOD = (
    "semisimple certificate: ||L(center) Q|| below the rank threshold for orthonormal cluster vectors Q "
    "(bounded by the pairs' residuals and distances), "
    "the resolvent of the other eigenvalues below its inverse (no SVD)"
)
_PROJECTED_METHOD = (
    "dim ker T_k of the m x m pencil projected on the cluster's deflating subspace (inverse subspace "
    "iteration from the computed vectors); the other eigenvalues beyond the threshold's reach"
)
_STRUCTURE_METHOD = (
    "semisimple by structure (symmetric definite pencil, no pair's two roots in the cluster); the resolvent of "
    "the other eigenvalues below the inverse rank threshold (no SVD)"
)

#: Factor by which the two tests of :func:`semisimple_certificate` must clear the
#: rank threshold: rounding in the products and the first-order error bounds of
#: the other eigenvalues stay far inside it.
CERTIFICATE_MARGIN = 10.0

#: Smallest singular value of the cluster's unit vectors accepted by
#: :func:`semisimple_certificate`: nearly parallel vectors (a defective eigenvalue
#: split by rounding) do not span its eigenspace.
INDEPENDENCE_TOL = 1e-3


@dataclass(frozen=True, kw_only=True)
class Cluster(Result):
    """A group of computed eigenvalues taken as one multiple eigenvalue.

    Attributes
    ----------
    indices : tuple of int
        Positions of the members in ``modes.eigenvalues``.
    center : complex
        Mean of the members (accurate to about eta, unlike the members) [rad/s].
    algebraic : int
        Algebraic multiplicity (the number of members).
    geometric : int
        dim ker L(center) at the rank tolerance.
    partial : tuple of int
        Partial multiplicities (lengths of the Jordan chains), longest first.
    consistent : bool
        True when sum(partial) == algebraic; False flags a rank decision the
        tolerance could not make cleanly (see ``note``).
    kernel_dims : tuple of int
        dim ker T_k for k = 1, 2, ... as computed.
    note : str
    error : float
        Relative spread of the computed members, max |lam_i - center| /
        max(|center|, gamma) (gamma the Fan-Lin-Van Dooren scale): about
        eta^(1/p) for a defective eigenvalue with chains of length p.
    method : str
        How the structure was decided.
    elapsed : float
        Seconds spent on the rank decisions [s].
    """

    indices: tuple[int, ...]
    center: complex
    algebraic: int
    geometric: int
    partial: tuple[int, ...]
    consistent: bool
    kernel_dims: tuple[int, ...]
    note: str = ""
    error: float = float("nan")
    method: str = _CLUSTER_METHOD
    elapsed: float = 0.0

    @property
    def semisimple(self) -> bool:
        """Every chain has length one (geometric == algebraic multiplicity)."""
        return all(p == 1 for p in self.partial) and self.geometric == self.algebraic

    @property
    def index(self) -> int:
        """Length of the longest Jordan chain."""
        return max(self.partial) if self.partial else 1

    def __repr__(self) -> str:
        return (
            f"Cluster(center={self.center:.6g}, algebraic={self.algebraic}, partial={self.partial}, "
            f"consistent={self.consistent}, spread={self.error:.1e})"
        )


@dataclass(frozen=True, eq=False, kw_only=True)
class ClusterEvidence:
    """What the computed spectrum already says about its clusters (input of :func:`semisimple_certificate`).

    Attributes
    ----------
    right : (n, 2n) complex
        Unit right eigenvectors, in the order of the eigenvalues.
    sensitivity : (2n,) float
        w(lam) ||y|| / |y^T L'(lam) x| per eigenvalue (unit x) [rad/s].
    bound : (2n,) float
        First-order error bounds of the eigenvalues [rad/s].
    backward_error : (2n,) float
        eta = ||L(lam) x|| / (w(lam) ||x||) per pair.
    weight : (2n,) float
        w(lam) = |lam|^2 ||M|| + |lam| ||C|| + ||K||.
    mirrored : bool
        The eigenvalues come in pairs (2p, 2p + 1) sharing one real vector of a
        symmetric definite pencil (the symmetric and proportional paths).
    """

    right: np.ndarray
    sensitivity: np.ndarray
    bound: np.ndarray
    backward_error: np.ndarray
    weight: np.ndarray
    mirrored: bool = False


def derivative_blocks(Ms, Cs, Ks, mu0) -> list[np.ndarray]:
    """[L(mu0), L'(mu0), L''(mu0)/2] of the scaled problem."""
    L0 = (mu0 * mu0) * Ms + mu0 * Cs + Ks
    L1 = (2 * mu0) * Ms + Cs
    return [L0, L1, Ms.astype(complex)]


def toeplitz(blocks: Sequence[np.ndarray], k: int) -> np.ndarray:
    """The block lower-triangular Toeplitz matrix T_k from [L, L', L''/2] (zero beyond)."""
    n = blocks[0].shape[0]
    T = np.zeros((k * n, k * n), dtype=complex)
    for i in range(k):
        for j in range(max(0, i - 2), i + 1):
            T[i * n : (i + 1) * n, j * n : (j + 1) * n] = blocks[i - j]
    return T


def block_scale(Ms, Cs, Ks, mu0) -> float:
    """Size of the blocks of T_k: max(w(mu0), 2|mu0| ||M|| + ||C||, ||M||) (Frobenius norms).

    Rank decisions are relative to this, not to sigma_max(T_k), which is itself
    tiny when L(mu0) and L'(mu0) both vanish.
    """
    nM, nC, nK = (frobenius(a) for a in (Ms, Cs, Ks))
    a = abs(mu0)
    return max(a * a * nM + a * nC + nK, 2 * a * nM + nC, nM)


def partial_multiplicities(
    problem: QuadraticProblem,
    lam0: complex,
    *,
    max_length: int,
    rank_tol: float = JORDAN_RANK_TOL,
    max_total: int | None = None,
) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """Partial multiplicities of lam0 from dim ker T_k, k = 1, 2, ... (theory: spectrum).

    Stops when no chain is longer than k - 1, at k = ``max_length``, or when
    dim ker T_k exceeds ``max_total`` (the algebraic multiplicity, when known:
    the rank decisions are then confounded by other small singular values).

    Returns
    -------
    partial : tuple of int
        Chain lengths, longest first (empty when L(lam0) is nonsingular at rank_tol).
    kernel_dims : tuple of int
        dim ker T_k for the k computed.

    Raises
    ------
    ComputationError
        L(lam0) or its derivatives overflow double precision.
    """
    Ms, Cs, Ks = problem.scaled()
    mu0 = complex(lam0) / problem.scaling.gamma
    with np.errstate(over="ignore", invalid="ignore"):
        blocks = derivative_blocks(Ms, Cs, Ks, mu0)
    if not all(np.all(np.isfinite(b)) for b in blocks):
        raise ComputationError(
            f"L(lam) at lam = {complex(lam0):.6g} overflows double precision ({abs(mu0):.3g} times the eigenvalue "
            f"scale gamma = {problem.scaling.gamma:.3g}); rescale the system"
        )
    threshold = rank_tol * block_scale(Ms, Cs, Ks, mu0)
    return chains_from_kernels(
        lambda k: kernel_dimension(toeplitz(blocks, k), threshold), max_length, max_total
    )


def rank_threshold(problem: QuadraticProblem, lam0: complex, rank_tol: float) -> float:
    """The Toeplitz rank threshold of :func:`partial_multiplicities` in the units of L(lam0) (unscaled).

    .. math:: \\tau = \\text{rank\\_tol}\\,\\max(|\\lambda_0|^2 \\|M\\| + |\\lambda_0| \\|C\\| + \\|K\\|,
              \\gamma (2 |\\lambda_0| \\|M\\| + \\|C\\|), \\gamma^2 \\|M\\|)

    (the scaled problem's threshold divided by delta: L_s(mu) = delta L(gamma mu)).
    """
    nM, nC, nK = problem.norms
    g, a = problem.scaling.gamma, abs(lam0)
    return rank_tol * max(a * a * nM + a * nC + nK, g * (2 * a * nM + nC), g * g * nM)


def semisimple_certificate(
    problem: QuadraticProblem,
    lam: np.ndarray,
    indices: tuple[int, ...],
    center: complex,
    evidence: ClusterEvidence,
    rank_tol: float,
    *,
    distance: np.ndarray | None = None,
) -> str | None:
    """How dim ker L(center) = m (the cluster's size) was certified without an SVD, or None (see module doc).

    ``distance``: |lam_i - center| of the members, when the caller formed it.

    Returns
    -------
    str or None
        The method (structure or residual certificate) when both tests clear the
        rank threshold by :data:`CERTIFICATE_MARGIN`; None when either does not
        (then the Toeplitz ranks decide).
    """
    ii = np.array(indices, dtype=np.intp)
    tau = rank_threshold(problem, center, rank_tol)
    if ii.size > problem.n or not (math.isfinite(tau) and tau > 0):
        return None  # more members than dimensions: some chain is longer than one
    method = _CERTIFIED_METHOD
    # ||L(center) x_i|| <= ||L(lam_i) x_i|| + d_i ||L'(lam_i)|| + d_i^2 ||M|| (d_i = |lam_i - center|, unit x_i)
    nM, nC, _ = problem.norms
    members = lam.take(ii)
    d = np.abs(members - center) if distance is None else distance
    r = evidence.backward_error.take(ii) * evidence.weight.take(ii) + d * (2 * np.abs(members) * nM + nC) + d * d * nM
    if evidence.mirrored and not {i ^ 1 for i in indices}.intersection(indices):
        # semisimple by theorem: the exact eigenvalue's eigenspace has dimension m, and L(center) is within
        # (distance + error bound) ||L'|| of L at it on that space
        dist = d + evidence.bound.take(ii)
        if not np.max(dist * (2 * abs(center) * nM + nC + dist * nM)) <= tau / CERTIFICATE_MARGIN:
            return None
        method = _STRUCTURE_METHOD
    else:
        # Q = X R^-1 orthonormal: ||L Q||_2 <= ||L X||_F / sigma_min(X), sigma_min(X)^2 the least eigenvalue of X^H X
        X = evidence.right.take(ii, axis=1)
        gram_min = float(np.linalg.eigvalsh(X.conj().T @ X)[0])
        if not gram_min > INDEPENDENCE_TOL**2:
            return None
        if not math.sqrt(float(np.dot(r, r)) / gram_min) <= tau / CERTIFICATE_MARGIN:  # r r >= 0 or NaN
            return None
    out = np.ones(lam.shape[0], dtype=bool)
    out[ii] = False
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        gap = np.abs(lam[out] - center) - evidence.bound[out]
        if gap.size and not gap.min() > 0:
            return None
        rest = float(np.sum(evidence.sensitivity[out] / (evidence.weight[out] * gap)))
    if not rest * (CERTIFICATE_MARGIN * tau) < 1.0:  # also False for NaN or inf
        return None
    return method


def _projected(problem, lam, indices, center, evidence, rank_tol):
    """:func:`~pinlin.spectral.projected.projected_structure` at the Toeplitz threshold where it pays, or None."""
    if not projected_pays(problem.n, len(indices)):
        return None
    threshold = rank_threshold(problem, center, rank_tol)
    if not (np.isfinite(threshold) and threshold > 0):
        return None
    return projected_structure(problem, lam, indices, center, evidence, rank_tol, threshold)


def analyse_cluster(
    problem: QuadraticProblem,
    lam: np.ndarray,
    indices: tuple[int, ...],
    rank_tol: float,
    evidence: ClusterEvidence | None = None,
) -> Cluster:
    """The Jordan structure of one cluster of computed eigenvalues (see :class:`Cluster`).

    With ``evidence`` (the computed vectors and figures) a semisimple cluster is
    certified by :func:`semisimple_certificate` when it can be, and otherwise the
    ranks of the small pencil projected on the cluster's deflating subspace decide
    when they can (:func:`pinlin.spectral.projected.projected_structure`); the full
    Toeplitz ranks decide otherwise, and always without it.
    """
    t0 = time.perf_counter()
    members = lam[list(indices)]
    center = complex(members.mean())
    # a cluster closed under conjugation (members in exact conjugate pairs) has a real mean
    im = members.imag
    if abs(im.sum()) <= CONJUGATE_SUM_ULPS * EPS * np.abs(im).sum():
        center = complex(center.real, 0.0)
    m = len(indices)
    dist = np.abs(members - center)
    spread = float(dist.max() / max(abs(center), problem.scaling.gamma))
    how = None if evidence is None else semisimple_certificate(
        problem, lam, indices, center, evidence, rank_tol, distance=dist
    )
    if how is not None:
        return Cluster(
            indices=tuple(indices), center=center, algebraic=m, geometric=m, partial=(1,) * m,
            consistent=True, kernel_dims=(m,), error=spread, method=how, elapsed=time.perf_counter() - t0,
        )
    projected = None if evidence is None else _projected(problem, lam, indices, center, evidence, rank_tol)
    if projected is not None:
        return Cluster(
            indices=tuple(indices), center=center, algebraic=m, geometric=projected[1][0],
            partial=projected[0], consistent=True, kernel_dims=projected[1], error=spread,
            method=_PROJECTED_METHOD, elapsed=time.perf_counter() - t0,
        )
    partial, dims = partial_multiplicities(problem, center, max_length=m + 1, rank_tol=rank_tol, max_total=m)
    geometric = dims[0] if dims else 0
    total = sum(partial)
    consistent = total == m
    note = ""
    if not consistent:
        note = (
            f"Toeplitz ranks at rank_tol {rank_tol:g} give chains {partial} (total {total}) for "
            f"{m} clustered eigenvalues"
        )
    return Cluster(
        indices=tuple(indices), center=center, algebraic=m, geometric=geometric, partial=partial,
        consistent=consistent, kernel_dims=dims, note=note, error=spread, elapsed=time.perf_counter() - t0,
    )
