"""Jordan chains of L(lam) at an eigenvalue (theory: spectrum).

A Jordan chain x_0, ..., x_{r-1} of L(lam) at lam0 satisfies

.. math::  \\sum_{j=0}^{i} \\frac{1}{j!} L^{(j)}(\\lambda_0)\\, x_{i-j} = 0,
           \\qquad i = 0, \\dots, r-1,\\quad x_0 \\ne 0,

and gives the free solutions exp(lam0 t) sum_{j<=i} t^j/j! x_{i-j}.  How many
chains of each length exist is decided by the block Toeplitz ranks of
:mod:`pinlin.spectral.multiplicity`; :func:`jordan_chains` then takes the
chains from the kernels of the same matrices.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from ..errors import AccuracyWarning, NotAnEigenvalueError
from ..numerics.accuracy import chain_residuals
from ..numerics.checks import check_integer, check_tolerance, complex_scalar
from ..numerics.clustering import CLUSTER_TOL, find_clusters
from ..numerics.rank import JORDAN_RANK_TOL, null_basis
from ..results import Result
from .multiplicity import (
    Cluster,
    analyse_cluster,
    block_scale,
    derivative_blocks,
    partial_multiplicities,
    toeplitz,
)
from .problem import as_problem
from .qep import solve_general

__all__ = [
    "CLUSTER_TOL",
    "RANK_TOL",
    "Cluster",
    "JordanChains",
    "find_clusters",
    "partial_multiplicities",
    "jordan_chains",
    "toeplitz",
    "analyse_cluster",
]

#: The default rank tolerance of the Jordan structure (the name of pinlin 0.1;
#: :data:`pinlin.numerics.JORDAN_RANK_TOL`).
RANK_TOL = JORDAN_RANK_TOL

_CHAINS_METHOD = (
    "kernels of the block Toeplitz matrices T_k on the Fan-Lin-Van Dooren scaled problem (SVD), "
    "heads orthonormalized"
)


@dataclass(frozen=True, repr=False, kw_only=True)
class JordanChains(Result):
    """Jordan chains of L at lam0; behaves as a list of chains (each a list of vectors).

    Attributes
    ----------
    lam0 : complex
        The eigenvalue [rad/s].
    chains : tuple of tuple of (n,) complex ndarray
        Canonical set: chain i is (x_0, ..., x_{m_i - 1}), longest first, with
        ||x_0|| = 1 and eigenvectors x_0 of different chains orthonormal; x_i
        carries the unit [s^i].
    partial : tuple of int
        Lengths of the chains found (the partial multiplicities when ``complete``).
    residuals : tuple of tuple of float
        For chain i and equation j the relative residual of
        :func:`pinlin.numerics.chain_residuals`.
    kernel_dims : tuple of int
        dim ker T_k for k = 1, 2, ...
    rank_tol : float
    elapsed : float
        Seconds spent in :func:`jordan_chains` [s].
    expected : tuple of int
        The partial multiplicities the Toeplitz ranks gave.
    complete : bool
        True when a chain of each expected length was found (``partial == expected``).
    notes : tuple of str
        What went wrong when ``complete`` is False.
    method : str
        How the chains were computed.
    error : float
        The largest relative chain residual (``max_residual``): the backward
        error of the chain equations.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[2.0]], [[1.0]])
    >>> chains = pinlin.jordan_chains(sys, -1.0)
    >>> len(chains), [len(chain) for chain in chains]
    (1, [2])
    >>> np.round(chains.chains[0][0], 6)
    array([1.+0.j])
    """

    lam0: complex
    chains: tuple[tuple[np.ndarray, ...], ...]
    partial: tuple[int, ...]
    residuals: tuple[tuple[float, ...], ...]
    kernel_dims: tuple[int, ...]
    rank_tol: float
    elapsed: float = 0.0
    expected: tuple[int, ...] | None = None
    notes: tuple[str, ...] = field(default=())
    method: str = _CHAINS_METHOD

    def __len__(self) -> int:
        return len(self.chains)

    def __getitem__(self, i):
        return list(self.chains[i])

    def __iter__(self) -> Iterator[list[np.ndarray]]:
        return (list(c) for c in self.chains)

    @property
    def algebraic(self) -> int:
        """Sum of the lengths of the chains found."""
        return sum(self.partial)

    @property
    def geometric(self) -> int:
        """Number of chains found."""
        return len(self.partial)

    @property
    def complete(self) -> bool:
        return self.expected is None or tuple(self.partial) == tuple(self.expected)

    @property
    def max_residual(self) -> float:
        return max((max(r) for r in self.residuals if r), default=0.0)

    @property
    def error(self) -> float:
        return self.max_residual

    def to_dict(self) -> dict:
        out = super().to_dict()
        out["complete"] = self.complete
        return out

    def __repr__(self) -> str:
        missing = "" if self.complete else f", INCOMPLETE (expected {self.expected})"
        return (
            f"JordanChains(lam0={self.lam0:.6g}, partial={self.partial}, max_residual={self.max_residual:.1e}"
            f"{missing})"
        )


def _chains_of_length(blocks, threshold, n, length, want, found, head_tol):
    """Up to ``want`` new scaled chains of ``length`` whose heads are independent of those in ``found``.

    Returns the chains and how many of the ``want`` had a head independent to ``head_tol``.
    """
    Z = null_basis(toeplitz(blocks, length), threshold)
    X0 = Z[:n]
    if found:
        Q, _ = np.linalg.qr(np.column_stack([c[0] for c in found]))
        X0 = X0 - Q @ (Q.conj().T @ X0)
    _, s, Vh = np.linalg.svd(X0, full_matrices=False)
    usable = int(np.sum(s[:want] > head_tol))
    stacked = Z @ Vh[:usable].conj().T
    new_chains = []
    for c in range(usable):
        new = [stacked[i * n : (i + 1) * n, c] for i in range(length)]
        # Gram-Schmidt on the heads, carried along the chains: a prefix of a
        # longer chain is a chain, so subtracting prefixes keeps the equations
        for _ in range(2):  # twice is enough
            for old in found + new_chains:
                coef = np.vdot(old[0], new[0])
                new = [v - coef * w for v, w in zip(new, old[:length])]
        nrm = np.linalg.norm(new[0])
        new_chains.append([v / nrm for v in new])
    return new_chains


def _not_an_eigenvalue(problem, lam0: complex, rank_tol: float) -> None:
    """Raise NotAnEigenvalueError for lam0, with the nearest eigenvalue (general solver) and the distance."""
    lam = solve_general(problem).lam
    j = int(np.argmin(np.abs(lam - lam0)))
    dist = float(abs(lam[j] - lam0))
    scale = max(abs(lam0), problem.scaling.gamma)
    raise NotAnEigenvalueError(
        f"lam0 = {lam0:.10g} is not an eigenvalue: L(lam0) is nonsingular at rank_tol {rank_tol:g}; the nearest "
        f"eigenvalue is {complex(lam[j]):.10g}, at distance {dist:.3e} ({dist / scale:.2e} relative to "
        f"max(|lam0|, gamma) = {scale:.3g})",
        lam=lam0,
        distance=dist / scale,
    )


def jordan_chains(sys, lam0, *, rank_tol: float = RANK_TOL, max_length: int | None = None) -> JordanChains:
    """A canonical set of Jordan chains of L(lam) = lam^2 M + lam C + K at lam0 (theory: spectrum).

    For each length k, from the longest down, the kernel of the block Toeplitz
    matrix T_k holds the stacked chains (x_0, ..., x_{k-1}) of length k; new
    chains are taken whose eigenvectors x_0 are independent of those already
    chosen (orthogonal complement, SVD; a head whose component outside the
    chosen ones is below ``rank_tol`` is not independent).  The computation
    runs on the Fan-Lin-Van Dooren scaled problem (lam = gamma mu); a chain of
    the scaled problem becomes one of L by x_i = x_i^s / gamma^i.

    When fewer chains are found than the Toeplitz ranks promise, the result
    says so (``complete`` False, ``expected``, ``notes``) and an
    :class:`~pinlin.AccuracyWarning` is issued: the chains are never dropped silently.

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

    Raises
    ------
    ParameterError
        lam0 not a finite number; bad tolerance or max_length; bad matrices.
    SingularMassError
        M of a tuple is singular.
    NotAnEigenvalueError
        L(lam0) is nonsingular at ``rank_tol``: lam0 is no eigenvalue.  The
        message gives the nearest eigenvalue and the distance to it;
        ``distance`` is that distance relative to max(|lam0|, gamma).

    Examples
    --------
    A critically damped oscillator, lam^2 + 2 lam + 1 = 0: lam = -1 is a double root with one eigenvector:

    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[2.0]], [[1.0]])
    >>> chains = pinlin.jordan_chains(sys, -1.0)
    >>> chains.partial, bool(chains.max_residual < 1e-12)
    ((2,), True)
    """
    t0 = time.perf_counter()
    problem = as_problem(sys)
    rank_tol = check_tolerance(rank_tol, "rank_tol", upper=1.0)
    lam0 = complex_scalar(lam0, "lam0")
    n = problem.n
    max_length = 2 * n if max_length is None else check_integer(max_length, "max_length", low=1)
    gamma = problem.scaling.gamma
    expected, dims = partial_multiplicities(problem, lam0, max_length=max_length, rank_tol=rank_tol)
    if not expected:
        _not_an_eigenvalue(problem, lam0, rank_tol)
    Ms, Cs, Ks = problem.scaled()
    blocks = derivative_blocks(Ms, Cs, Ks, lam0 / gamma)
    threshold = rank_tol * block_scale(Ms, Cs, Ks, lam0 / gamma)
    scaled: list[list[np.ndarray]] = []
    notes = []
    for length in sorted(set(expected), reverse=True):
        want = expected.count(length)
        new = _chains_of_length(blocks, threshold, n, length, want, scaled, rank_tol)
        if len(new) < want:
            notes.append(
                f"{want} chain(s) of length {length} expected from the Toeplitz ranks, {len(new)} found with "
                f"heads independent of the longer chains (rank_tol {rank_tol:g})"
            )
        scaled += new
    chains = [tuple(v / gamma**i for i, v in enumerate(c)) for c in scaled]
    residuals = tuple(chain_residuals(problem.M, problem.C, problem.K, lam0, c) for c in chains)
    result = JordanChains(
        lam0=lam0, chains=tuple(chains), partial=tuple(len(c) for c in chains), residuals=residuals,
        kernel_dims=dims, rank_tol=rank_tol, elapsed=time.perf_counter() - t0, expected=expected,
        notes=tuple(notes),
    )
    if notes:
        warnings.warn(f"jordan_chains at lam0 = {lam0:.6g}: " + "; ".join(notes), AccuracyWarning, stacklevel=2)
    return result
