"""Multiple eigenvalues: clusters and their partial multiplicities (SPEC section 4).

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
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError
from ..numerics.floating import EPS
from ..numerics.norms import frobenius
from ..numerics.rank import JORDAN_RANK_TOL, kernel_dimension
from ..results import Result
from .problem import QuadraticProblem

__all__ = ["Cluster", "analyse_cluster", "partial_multiplicities", "toeplitz", "derivative_blocks", "block_scale"]

#: A cluster closed under conjugation has members whose imaginary parts cancel
#: to a few ulps of their total: within this many eps its mean is taken real.
CONJUGATE_SUM_ULPS = 4.0

_CLUSTER_METHOD = "dim ker T_k of the block Toeplitz matrices at the cluster mean (scaled problem, SVD)"


@dataclass(frozen=True)
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
    """Partial multiplicities of lam0 from dim ker T_k, k = 1, 2, ... (SPEC section 4).

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
    dims = [0]
    counts: list[int] = []  # counts[k-1] = number of chains of length >= k
    for k in range(1, max_length + 1):
        dims.append(kernel_dimension(toeplitz(blocks, k), threshold))
        if max_total is not None and dims[k] > max_total:
            break
        c = dims[k] - dims[k - 1]
        if counts and c > counts[-1]:
            c = counts[-1]  # rank noise: the counts cannot increase
        if c <= 0:
            break
        counts.append(c)
    partial: list[int] = []
    for length in range(len(counts), 0, -1):
        longer = counts[length] if length < len(counts) else 0
        partial += [length] * (counts[length - 1] - longer)
    return tuple(partial), tuple(dims[1:])


def analyse_cluster(
    problem: QuadraticProblem, lam: np.ndarray, indices: tuple[int, ...], rank_tol: float
) -> Cluster:
    """The Jordan structure of one cluster of computed eigenvalues (see :class:`Cluster`)."""
    t0 = time.perf_counter()
    members = lam[list(indices)]
    center = complex(np.mean(members))
    # a cluster closed under conjugation (members in exact conjugate pairs) has a real mean
    if abs(np.sum(members.imag)) <= CONJUGATE_SUM_ULPS * EPS * np.sum(np.abs(members.imag)):
        center = complex(center.real, 0.0)
    m = len(indices)
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
    spread = float(np.max(np.abs(members - center)) / max(abs(center), problem.scaling.gamma))
    return Cluster(
        tuple(indices), center, m, geometric, partial, consistent, dims, note,
        error=spread, elapsed=time.perf_counter() - t0,
    )
