"""Multiple eigenvalues: clusters, partial multiplicities and Jordan chains (SPEC section 4).

A Jordan chain x_0, ..., x_{r-1} of L(lam) at lam0 satisfies

.. math::  \\sum_{j=0}^{i} \\frac{1}{j!} L^{(j)}(\\lambda_0)\\, x_{i-j} = 0,
           \\qquad i = 0, \\dots, r-1,\\quad x_0 \\ne 0,

and gives the free solutions exp(lam0 t) sum_{j<=i} t^j/j! x_{i-j}.  The
partial multiplicities m_1 >= m_2 >= ... of lam0 follow from the ranks of the
block Toeplitz matrices

.. math::
    T_k = \\begin{bmatrix} L & & \\\\ L' & L & \\\\ L''/2 & L' & L \\\\
          & \\ddots & & \\ddots \\end{bmatrix}  \\quad (k \\times k \\text{ blocks}),
    \\qquad \\dim\\ker T_k = \\sum_i \\min(m_i, k),

so dim ker T_k - dim ker T_{k-1} counts the chains of length >= k.  Ranks are
decided on the Fan-Lin-Van Dooren scaled problem (all blocks of size about one):
singular values below ``rank_tol`` times the size of the blocks,
max(|mu0|^2 ||M|| + |mu0| ||C|| + ||K||, 2 |mu0| ||M|| + ||C||, ||M||), count as zero.

Rounding splits an eigenvalue with chains of length p into p eigenvalues about
eta^(1/p) |lam| apart; :func:`find_clusters` regroups computed eigenvalues
closer than ``cluster_tol`` (relative), and the Toeplitz ranks at the cluster's
mean (which is accurate to about eta, unlike its members) then tell its
structure.
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

from ..errors import ParameterError
from .problem import QuadraticProblem, as_problem, check_tolerance

__all__ = [
    "CLUSTER_TOL",
    "RANK_TOL",
    "Cluster",
    "JordanChains",
    "find_clusters",
    "partial_multiplicities",
    "jordan_chains",
    "toeplitz",
]

#: Default relative distance below which computed eigenvalues form one cluster.
#: Rounding moves an eigenvalue with chains of length p by about eps^(1/p)
#: (1.5e-8 for p = 2, 6e-6 for p = 3, times its condition), so 1e-5 regroups
#: double and well-conditioned triple roots.
CLUSTER_TOL = 1e-5

#: Default relative singular value threshold of the rank decisions.
RANK_TOL = 1e-8


@dataclass(frozen=True)
class Cluster:
    """A group of computed eigenvalues taken as one multiple eigenvalue.

    Attributes
    ----------
    indices : tuple of int
        Positions of the members in ``modes.eigenvalues``.
    center : complex
        Mean of the members (accurate to about eta, unlike the members).
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
    """

    indices: tuple[int, ...]
    center: complex
    algebraic: int
    geometric: int
    partial: tuple[int, ...]
    consistent: bool
    kernel_dims: tuple[int, ...]
    note: str = ""

    @property
    def semisimple(self) -> bool:
        """Every chain has length one (geometric == algebraic multiplicity)."""
        return all(p == 1 for p in self.partial) and self.geometric == self.algebraic

    @property
    def index(self) -> int:
        """Length of the longest Jordan chain."""
        return max(self.partial) if self.partial else 1


def find_clusters(
    lam: np.ndarray, cluster_tol: float, scale: float, bound: np.ndarray | None = None, factor: float = 10.0
) -> list[tuple[int, ...]]:
    """Groups of eigenvalues that rounding cannot tell apart.

    lam_i and lam_j are linked when both

    .. math::
        |\\lambda_i - \\lambda_j| \\le \text{cluster\\_tol}\\,\\max(|\\lambda_i|, |\\lambda_j|, \text{scale})
        \\quad\text{and}\\quad
        |\\lambda_i - \\lambda_j| \\le \text{factor}\\,(r_i + r_j)

    with r the first-order error bounds (when given): close eigenvalues that
    are each well-conditioned enough to be told apart are distinct, not a
    multiple root.  (A defective eigenvalue has r = inf or, split by rounding,
    r about its own spread.)  Single linkage (connected components); ``scale``
    [rad/s] keeps the test meaningful near lam = 0 (pinlin passes the
    Fan-Lin-Van Dooren gamma).  Only groups of two or more are returned,
    sorted by their first index.
    """
    lam = np.asarray(lam, dtype=complex)
    k = lam.shape[0]
    a = np.abs(lam)
    dist = np.abs(lam[:, None] - lam[None, :])
    ref = np.maximum(np.maximum(a[:, None], a[None, :]), scale)
    adj = dist <= cluster_tol * ref
    if bound is not None:
        r = np.asarray(bound, dtype=float)
        with np.errstate(invalid="ignore"):
            adj &= dist <= factor * (r[:, None] + r[None, :])
    np.fill_diagonal(adj, False)
    if not adj.any():
        return []
    ncomp, labels = connected_components(csr_matrix(adj), directed=False)
    groups = {}
    for i in range(k):
        groups.setdefault(labels[i], []).append(i)
    return sorted((tuple(g) for g in groups.values() if len(g) > 1), key=lambda g: g[0])


def _derivative_blocks(Ms, Cs, Ks, mu0) -> list[np.ndarray]:
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


def _block_scale(Ms, Cs, Ks, mu0) -> float:
    """Size of the blocks of T_k: max(w(mu0), 2|mu0| ||M|| + ||C||, ||M||) (Frobenius norms).

    Rank decisions are relative to this, not to sigma_max(T_k), which is itself
    tiny when L(mu0) and L'(mu0) both vanish.
    """
    nM, nC, nK = (float(np.linalg.norm(a)) for a in (Ms, Cs, Ks))
    a = abs(mu0)
    return max(a * a * nM + a * nC + nK, 2 * a * nM + nC, nM)


def _kernel_dim(T: np.ndarray, threshold: float) -> int:
    s = np.linalg.svd(T, compute_uv=False)
    return int(np.sum(s <= threshold))


def partial_multiplicities(
    problem: QuadraticProblem,
    lam0: complex,
    *,
    max_length: int,
    rank_tol: float = RANK_TOL,
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
    """
    s = problem.scaling
    Ms, Cs, Ks = problem.scaled()
    mu0 = complex(lam0) / s.gamma
    blocks = _derivative_blocks(Ms, Cs, Ks, mu0)
    threshold = rank_tol * _block_scale(Ms, Cs, Ks, mu0)
    dims = [0]
    counts = []  # counts[k-1] = number of chains of length >= k
    for k in range(1, max_length + 1):
        dims.append(_kernel_dim(toeplitz(blocks, k), threshold))
        if max_total is not None and dims[k] > max_total:
            break
        c = dims[k] - dims[k - 1]
        if counts and c > counts[-1]:
            c = counts[-1]  # rank noise: the counts cannot increase
        if c <= 0:
            break
        counts.append(c)
    partial = []
    for length in range(len(counts), 0, -1):
        longer = counts[length] if length < len(counts) else 0
        partial += [length] * (counts[length - 1] - longer)
    return tuple(partial), tuple(dims[1:])


def analyse_cluster(
    problem: QuadraticProblem, lam: np.ndarray, indices: tuple[int, ...], rank_tol: float
) -> Cluster:
    """The Jordan structure of one cluster of computed eigenvalues (see :class:`Cluster`)."""
    members = lam[list(indices)]
    center = complex(np.mean(members))
    # a cluster closed under conjugation (members in exact conjugate pairs) has a real mean
    if abs(np.sum(members.imag)) <= 4 * np.finfo(float).eps * np.sum(np.abs(members.imag)):
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
    return Cluster(tuple(indices), center, m, geometric, partial, consistent, dims, note)


# ---------------------------------------------------------------------------- chains


@dataclass(frozen=True)
class JordanChains:
    """Jordan chains of L at lam0; behaves as a list of chains (each a list of vectors).

    Attributes
    ----------
    lam0 : complex
        The eigenvalue [rad/s].
    chains : tuple of tuple of (n,) complex ndarray
        Canonical set: chain i is (x_0, ..., x_{m_i - 1}), longest first, with
        ||x_0|| = 1 and eigenvectors x_0 of different chains orthonormal.
    partial : tuple of int
        Chain lengths (the partial multiplicities).
    residuals : tuple of tuple of float
        For chain i and equation j, ||sum_l L^(l)/l! x_{j-l}|| / (w ||x||), with
        w = |lam0|^2 ||M|| + |lam0| ||C|| + ||K|| (and the derivative terms'
        weights), ||x|| the largest vector norm of the chain.
    kernel_dims : tuple of int
        dim ker T_k for k = 1, 2, ...
    rank_tol : float
    elapsed : float
        Seconds spent in :func:`jordan_chains`.
    """

    lam0: complex
    chains: tuple[tuple[np.ndarray, ...], ...]
    partial: tuple[int, ...]
    residuals: tuple[tuple[float, ...], ...]
    kernel_dims: tuple[int, ...]
    rank_tol: float
    elapsed: float = 0.0

    def __len__(self) -> int:
        return len(self.chains)

    def __getitem__(self, i):
        return list(self.chains[i])

    def __iter__(self) -> Iterator[list[np.ndarray]]:
        return (list(c) for c in self.chains)

    @property
    def algebraic(self) -> int:
        return sum(self.partial)

    @property
    def geometric(self) -> int:
        return len(self.partial)

    @property
    def max_residual(self) -> float:
        return max((max(r) for r in self.residuals if r), default=0.0)

    def __repr__(self) -> str:
        return f"JordanChains(lam0={self.lam0:.6g}, partial={self.partial}, max_residual={self.max_residual:.1e})"


def _null_basis(T: np.ndarray, threshold: float) -> np.ndarray:
    _, s, Vh = np.linalg.svd(T)
    r = int(np.sum(s > threshold))
    return Vh[r:].conj().T


def chain_residuals(problem: QuadraticProblem, lam0: complex, chain: Sequence[np.ndarray]) -> tuple[float, ...]:
    """Relative residuals of the chain equations (see :class:`JordanChains`)."""
    a = abs(lam0)
    blocks = [
        lam0 * lam0 * problem.M + lam0 * problem.C + problem.K,
        2 * lam0 * problem.M + problem.C,
        problem.M.astype(complex),
    ]
    weights = [problem.weight(lam0), 2 * a * problem.norm_M + problem.norm_C, problem.norm_M]
    scale = max(np.linalg.norm(x) for x in chain)
    out = []
    for i in range(len(chain)):
        r = sum(blocks[j] @ chain[i - j] for j in range(min(i, 2) + 1))
        w = sum(weights[j] * np.linalg.norm(chain[i - j]) for j in range(min(i, 2) + 1))
        out.append(float(np.linalg.norm(r) / max(w, np.finfo(float).tiny * scale)))
    return tuple(out)


def jordan_chains(sys, lam0, *, rank_tol: float = RANK_TOL, max_length: int | None = None) -> JordanChains:
    """A canonical set of Jordan chains of L(lam) = lam^2 M + lam C + K at lam0 (SPEC section 4).

    For each length k, from the longest down, the kernel of the block Toeplitz
    matrix T_k holds the stacked chains (x_0, ..., x_{k-1}) of length k; new
    chains are taken whose eigenvectors x_0 are independent of those already
    chosen (orthogonal complement, SVD).  The computation runs on the
    Fan-Lin-Van Dooren scaled problem (lam = gamma mu); a chain of the scaled
    problem becomes one of L by x_i = x_i^s / gamma^i (x_i carries a factor
    [s^i]).

    Parameters
    ----------
    sys : LinearizedSystem or tuple (M, C, K)
    lam0 : complex
        The eigenvalue [rad/s].  Use an exact value or an accurate one (the mean
        of a cluster, ``modes.clusters[i].center``); it is used as given.
    rank_tol : float
        Relative singular value threshold of the rank decisions, in (0, 1).
    max_length : int, optional
        Longest chain looked for (default 2n, the degree bound).

    Returns
    -------
    JordanChains
        Empty (no chains) when L(lam0) is nonsingular at ``rank_tol``.

    Raises
    ------
    ParameterError
        lam0 not a finite number; bad tolerance or max_length; bad matrices.
    """
    t0 = time.perf_counter()
    problem = as_problem(sys)
    rank_tol = check_tolerance("rank_tol", rank_tol)
    try:
        lam0 = complex(lam0)
    except (TypeError, ValueError):
        raise ParameterError("lam0", f"expected a number, got {lam0!r}") from None
    if not np.isfinite(lam0.real) or not np.isfinite(lam0.imag):
        raise ParameterError("lam0", f"expected a finite number, got {lam0!r}")
    n = problem.n
    if max_length is None:
        max_length = 2 * n
    if not isinstance(max_length, (int, np.integer)) or isinstance(max_length, bool) or max_length < 1:
        raise ParameterError("max_length", f"expected a positive integer, got {max_length!r}")
    gamma = problem.scaling.gamma
    partial, dims = partial_multiplicities(problem, lam0, max_length=int(max_length), rank_tol=rank_tol)
    Ms, Cs, Ks = problem.scaled()
    blocks = _derivative_blocks(Ms, Cs, Ks, lam0 / gamma)
    threshold = rank_tol * _block_scale(Ms, Cs, Ks, lam0 / gamma)
    scaled_chains: list[list[np.ndarray]] = []
    for length in sorted(set(partial), reverse=True):
        want = partial.count(length)
        Z = _null_basis(toeplitz(blocks, length), threshold)
        X0 = Z[:n]
        if scaled_chains:
            Q, _ = np.linalg.qr(np.column_stack([c[0] for c in scaled_chains]))
            X0 = X0 - Q @ (Q.conj().T @ X0)
        _, s, Vh = np.linalg.svd(X0, full_matrices=False)
        stacked = Z @ Vh[:want].conj().T
        for c in range(min(want, stacked.shape[1])):
            new = [stacked[i * n : (i + 1) * n, c] for i in range(length)]
            # Gram-Schmidt on the heads, carried along the chains: a prefix of a
            # longer chain is a chain, so subtracting prefixes keeps the equations
            for _ in range(2):  # twice is enough
                for old in scaled_chains:
                    coef = np.vdot(old[0], new[0])
                    new = [v - coef * w for v, w in zip(new, old[:length])]
            nrm = np.linalg.norm(new[0])
            scaled_chains.append([v / nrm for v in new])
    chains = [tuple(v / gamma**i for i, v in enumerate(c)) for c in scaled_chains]
    residuals = tuple(chain_residuals(problem, lam0, c) for c in chains)
    return JordanChains(
        lam0, tuple(chains), tuple(len(c) for c in chains), residuals, dims, rank_tol, time.perf_counter() - t0
    )
