"""The modal expansion of the first-order state space: eigenvectors and Jordan chains (theory: flexibility, responses).

Built on the spectral module (:func:`pinlin.modal_analysis`,
:func:`pinlin.jordan_chains`); the modal method of the H(s) engine
(:mod:`pinlin.frf.engine`) and the free response (:mod:`pinlin.response.free`)
both evaluate it.

In first-order form z = (x, x'), z' = A z, a (semi)simple eigenvalue lam_k
with right vector x_k spans v_k = (x_k, lam_k x_k), and the normalized left
vector y_k (y_k^T L'(lam_k) x_k = 1) gives its coefficient in any state
w = (a, b):

.. math::  c_k = y_k^T \\left((\\lambda_k M + C)\\, a + M b\\right)

(the modal solution of the theory pages, theory: free response, is this with w = z(0)).  A Jordan chain
x_0, ..., x_{r-1} at lam0 spans v_i = (x_i, lam0 x_i + x_{i-1}) with
A v_i = lam0 v_i + v_{i-1}: the states of the free solutions
u_i(t) = exp(lam0 t) sum_{j<=i} t^j/j! x_{i-j}.  A defective eigenvalue has
no normalized left vectors; the coefficients of its chains are found from the
part of w that the (semi)simple modes leave, by least squares on the chain
basis.  A few steps of iterative refinement (the same map applied to the
residual w - V c) then make the coefficients reproduce w to rounding even when
the left vectors are less accurate than the right ones; the final residual is
reported.
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError, ParameterError
from ..linearization.system import LinearizedSystem
from ..numerics import system_scaling
from ..results import Result, persistent

__all__ = [
    "JordanBlock",
    "ModalExpansion",
    "modal_expansion",
    "check_modes",
    "complex_matmul",
    "conjugate_partners",
    "REFINE_STEPS",
    "CONJUGATE_TOL",
    "CHUNK_ROWS",
]

#: Relative distance |lam_j - conj(lam_k)| / |lam_k| within which two eigenvalues are a conjugate
#: pair: far above the rounding of a computed pair (about eps kappa), far below any physical gap.
CONJUGATE_TOL = 1e-10

#: Rows per block in :func:`complex_matmul` (see there why products are blocked).
CHUNK_ROWS = 1024

#: Steps of iterative refinement of the modal coefficients (see :meth:`ModalExpansion.coefficients`):
#: each step gains the digits the left vectors lose; two reach rounding level on the test cases.
REFINE_STEPS = 2

#: The attributes of a :func:`pinlin.modal_analysis` result that the expansion reads.
_MODES_ATTRIBUTES = ("eigenvalues", "right", "left", "left_normalized", "clusters", "matrices")


@persistent
@dataclass(frozen=True)
class JordanBlock:
    """One Jordan chain: eigenvalue lam0 [1/s] and vectors (n, r), columns x_0 ... x_{r-1}."""

    lam0: complex
    vectors: np.ndarray

    @property
    def length(self) -> int:
        return self.vectors.shape[1]

    def state_basis(self) -> np.ndarray:
        """(2n, r): v_i = (x_i, lam0 x_i + x_{i-1})."""
        X = self.vectors
        Xd = self.lam0 * X
        Xd[:, 1:] += X[:, :-1]
        return np.vstack([X, Xd])


@dataclass(frozen=True, repr=False, eq=False)
class ModalExpansion(Result):
    """Eigenvalues, vectors and chains of a system, ready for responses.

    Attributes
    ----------
    system : LinearizedSystem
    modes : Modes
        The modal analysis it was built from.
    lam : (k,) complex
        Semisimple eigenvalues [1/s] (members of a semisimple cluster take the
        cluster's mean, the accurate value of the multiple eigenvalue).
    right, left : (n, k) complex
        Their right vectors and normalized left vectors.
    blocks : tuple of JordanBlock
        The Jordan chains of the defective eigenvalues.
    chain_residual : float
        Largest relative residual of the chain equations (0 without chains).
    gamma : float
        Natural frequency scale sqrt(||K|| / ||M||) [1/s] (or ||C|| / ||M||, or 1:
        the Fan-Lin-Van Dooren gamma), weighting velocity against displacement
        in the least squares.
    partner : (k,) int ndarray or None
        For each semisimple mode, the index of its complex conjugate (itself for
        a real eigenvalue); None when the computed spectrum is not
        conjugate-symmetric to ``CONJUGATE_TOL``.  A real response then needs
        only one member of each pair (twice its real part).  Computed on first
        use (the frequency domain does not need it).
    elapsed : float
        Seconds spent in :func:`modal_expansion` (the modal analysis included
        when it was computed there).
    method : str
        ``"modal"`` (every eigenvalue semisimple) or ``"modal + Jordan chains"``.
    error : float
        The largest relative residual of the eigen-data used: the backward
        errors eta of the eigenpairs and the chain residuals.
    """

    system: LinearizedSystem
    modes: object
    lam: np.ndarray
    right: np.ndarray
    left: np.ndarray
    blocks: tuple[JordanBlock, ...]
    chain_residual: float
    gamma: float
    elapsed: float = 0.0
    method: str = "modal"

    _dict_exclude = ("system", "modes")

    @property
    def error(self) -> float:
        if self.modes is None:  # read back by pinlin.load: the modes are not kept, the figure is
            return self.__dict__["_loaded"]["error"]
        return max(float(np.max(self.modes.backward_error, initial=0.0)), float(self.chain_residual))

    @property
    def is_simple(self) -> bool:
        return not self.blocks

    @functools.cached_property
    def partner(self) -> np.ndarray | None:
        return conjugate_partners(self.lam)

    @functools.cached_property
    def state_sigma_min(self) -> float:
        """sigma_min of the scaled state basis [x_k; lam_k x_k / gamma] of the semisimple modes (formed once).

        ||z|| >= sigma_min ||coefficients|| for a state z = V c: a lower bound of a
        response's norm from its modal coefficients (:mod:`pinlin.frf.modal`).
        """
        X = self.right
        if X.shape[1] == 0:
            return 0.0
        return float(np.linalg.svd(np.vstack([X, X * (self.lam / self.gamma)]), compute_uv=False)[-1])

    @property
    def eigenvalues(self) -> np.ndarray:
        """Every eigenvalue that appears in a denominator: ``lam`` and each block's lam0 [1/s]."""
        return np.concatenate([self.lam, np.array([b.lam0 for b in self.blocks], dtype=complex)])

    def __repr__(self) -> str:
        return (
            f"ModalExpansion(n={self.right.shape[0]}, modes={self.lam.size}, "
            f"chains={[b.length for b in self.blocks]}, error={self.error:.1e}, elapsed={self.elapsed:.3g} s)"
        )

    def _first_guess(self, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients of a weighted state w = (a, b / gamma): semisimple modes by their left vectors,
        Jordan blocks by least squares on what those leave."""
        sys, n = self.system, self.system.n
        a, b = w[:n], w[n:] * self.gamma
        lam = self.lam if w.ndim == 1 else self.lam[:, None]
        c = self.left.T @ (sys.C @ a + sys.M @ b) + lam * (self.left.T @ (sys.M @ a))
        if not self.blocks:
            return c, np.zeros((0,) + w.shape[1:], dtype=complex)
        rest = w - self._basis_simple @ c
        d, *_ = np.linalg.lstsq(self._basis_chains, rest, rcond=None)
        return c, d

    @property
    def _basis_simple(self) -> np.ndarray:
        return np.vstack([self.right, (self.lam * self.right) / self.gamma])

    @property
    def _basis_chains(self) -> np.ndarray:
        if not self.blocks:
            return np.zeros((2 * self.system.n, 0), dtype=complex)
        V = np.hstack([blk.state_basis() for blk in self.blocks])
        V[self.system.n :] /= self.gamma
        return V

    def coefficients(
        self, a: np.ndarray, b: np.ndarray, refine: int = REFINE_STEPS
    ) -> tuple[np.ndarray, list[np.ndarray], float]:
        """Coefficients of the state w = (a, b) on the modes and chains ((n,) or (n, m) columns).

        The left-vector formula (theory: flexibility) (and least squares for the chains) gives
        a first guess; ``refine`` steps of iterative refinement, each applying
        the same formula to the residual w - V (c, d), then make the expansion
        reproduce w to rounding even where the left vectors are less accurate
        than the right ones (non-normal systems).

        Returns
        -------
        c : (k,) or (k, m) complex
            On the semisimple modes.
        d : list of (r,) or (r, m) complex
            On each Jordan block.
        residual : float
            ||w - V (c, d)|| / ||w|| (Frobenius), velocities weighted by 1/gamma.
        """
        w = np.concatenate([a, b / self.gamma]).astype(complex)
        Vs, Vd = self._basis_simple, self._basis_chains
        c, d = self._first_guess(w)
        for _ in range(refine):
            r = w - Vs @ c - Vd @ d
            dc, dd = self._first_guess(r)
            c, d = c + dc, d + dd
        norm_w = float(np.linalg.norm(w))
        residual = float(np.linalg.norm(w - Vs @ c - Vd @ d) / norm_w) if norm_w > 0 else 0.0
        out, start = [], 0
        for blk in self.blocks:
            out.append(d[start : start + blk.length])
            start += blk.length
        return c, out, residual


def complex_matmul(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """A @ B for complex A (p, k), B (k, m) through real products of size (rows, 2k) x (2k, 2m).

    The rows of A are taken ``CHUNK_ROWS`` at a time.  (Threaded BLAS products
    of tall, thin matrices -- complex ones especially -- can be slower by two
    orders of magnitude on a loaded machine than the same work in blocks.)
    """
    A = np.asarray(A, dtype=complex)
    B = np.asarray(B, dtype=complex)
    m = B.shape[1]
    Bb = np.block([[B.real, B.imag], [-B.imag, B.real]])
    out = np.empty((A.shape[0], m), dtype=complex)
    for start in range(0, A.shape[0], CHUNK_ROWS):
        a = A[start : start + CHUNK_ROWS]
        R = np.hstack([a.real, a.imag]) @ Bb
        out[start : start + CHUNK_ROWS] = R[:, :m] + 1j * R[:, m:]
    return out


def conjugate_partners(lam: np.ndarray, tol: float | None = None) -> np.ndarray | None:
    """Index of the conjugate of each eigenvalue (itself if real), or None if the set is not symmetric.

    Each eigenvalue with Im > 0, in turn, takes the nearest free conjugate of one with Im < 0;
    the pair must agree to ``tol`` (default ``CONJUGATE_TOL``) relative to |lam|.
    """
    tol = CONJUGATE_TOL if tol is None else tol
    partner = np.arange(lam.size)
    pos = np.flatnonzero(lam.imag > 0)
    neg = np.flatnonzero(lam.imag < 0)
    if pos.size != neg.size:
        return None
    gap = np.abs(lam[pos][:, None] - np.conj(lam[neg])[None, :])  # (pairs, pairs)
    for row, i in enumerate(pos):
        col = int(np.argmin(gap[row]))
        if not gap[row, col] <= tol * abs(lam[i]):  # (taken columns are inf)
            return None
        j = int(neg[col])
        partner[i], partner[j] = j, i
        gap[:, col] = np.inf
    return partner


def check_modes(sys: LinearizedSystem, modes):
    """``modes`` validated as a modal analysis of ``sys`` (or a fresh :func:`pinlin.modal_analysis`).

    Raises
    ------
    ParameterError
        ``modes`` is not a modal analysis, or is the analysis of another system
        (other size or other M, C, K).
    """
    if modes is None:
        from ..spectral import modal_analysis

        return modal_analysis(sys)
    missing = [a for a in _MODES_ATTRIBUTES if not hasattr(modes, a)]
    if missing:
        raise ParameterError("modes", f"expected the result of pinlin.modal_analysis, got {type(modes).__name__}")
    n = sys.n
    M, C, K = modes.matrices
    if np.shape(modes.right) != (n, 2 * n) or np.shape(M) != (n, n):
        raise ParameterError(
            "modes",
            f"the modal analysis given is of another system: expected eigenvectors of shape {(n, 2 * n)} "
            f"for n = {n}, got {np.shape(modes.right)}",
        )
    if not (np.array_equal(M, sys.M) and np.array_equal(C, sys.C) and np.array_equal(K, sys.K)):
        raise ParameterError("modes", "the modal analysis given is of another system (M, C, K differ)")
    return modes


def _chain_blocks(sys: LinearizedSystem, cluster) -> tuple[list[JordanBlock], float]:
    """The Jordan chains of one defective (or not normalizable) cluster, and their largest residual."""
    from ..spectral import jordan_chains

    chains = jordan_chains(sys, cluster.center)
    if chains.algebraic != cluster.algebraic:
        raise ComputationError(
            f"modal expansion: the eigenvalue cluster at {cluster.center:.6g} has algebraic "
            f"multiplicity {cluster.algebraic}, but its Jordan chains have total length "
            f"{chains.algebraic} (partial multiplicities {chains.partial}); the rank decisions are "
            f"ambiguous at this tolerance. Use method='direct' (frequency domain) or forced_response "
            f"(time domain, exact discretization) instead."
        )
    blocks = [JordanBlock(complex(chains.lam0), np.column_stack(chain).astype(complex)) for chain in chains]
    return blocks, float(chains.max_residual)


def modal_expansion(sys: LinearizedSystem, modes=None) -> ModalExpansion:
    """Build the expansion from ``pinlin.modal_analysis(sys)`` (or given ``modes``) and Jordan chains.

    Given ``modes`` (an immutable result), the expansion is kept with them and
    returned again by later calls with the same modes (their M, C, K are checked
    equal to ``sys``'s each time); its ``elapsed`` is that of the first build.

    Semisimple eigenvalues (single, or clusters whose left vectors were
    normalized) enter with their vectors; every other cluster enters through
    its Jordan chains (:func:`pinlin.jordan_chains`, theory: flexibility).

    Parameters
    ----------
    sys : LinearizedSystem
    modes : Modes, optional
        A modal analysis of ``sys`` to reuse (computed when omitted).

    Returns
    -------
    ModalExpansion

    Raises
    ------
    ParameterError
        ``modes`` is not a modal analysis of ``sys``.
    ComputationError
        The spectral analysis left an eigenvalue neither normalized nor in a
        cluster whose Jordan chains account for its multiplicity.
    """
    t0 = time.perf_counter()
    given = modes is not None
    modes = check_modes(sys, modes)
    cached = modes.__dict__.get("_expansion") if given and hasattr(modes, "__dict__") else None
    if cached is not None:  # the same modes (immutable) of the same M, C, K: the same expansion
        return cached
    lam = np.array(modes.eigenvalues, dtype=complex)
    normalized = np.asarray(modes.left_normalized)
    in_cluster = np.zeros(lam.size, dtype=bool)
    keep: list[int] = []
    blocks: list[JordanBlock] = []
    residual = 0.0
    for cluster in modes.clusters:
        idx = list(cluster.indices)
        in_cluster[idx] = True
        if cluster.semisimple and np.all(normalized[idx]):
            lam[idx] = cluster.center
            keep += idx
            continue
        found, res = _chain_blocks(sys, cluster)
        blocks += found
        residual = max(residual, res)
    lone = np.flatnonzero(~in_cluster)
    if not np.all(normalized[lone]):
        bad = lam[lone[~normalized[lone]]]
        raise ComputationError(
            f"modal expansion: eigenvalues {bad} have no normalized left vector and are not in a "
            f"cluster; the modal expansion does not apply (use method='direct' or forced_response)"
        )
    keep_idx = np.sort(np.concatenate([lone, np.array(keep, dtype=int)])).astype(int)
    expansion = ModalExpansion(
        system=sys,
        modes=modes,
        lam=lam[keep_idx],
        right=np.array(modes.right[:, keep_idx], dtype=complex),
        left=np.array(modes.left[:, keep_idx], dtype=complex),
        blocks=tuple(blocks),
        chain_residual=float(residual),
        gamma=system_scaling(sys.M, sys.C, sys.K).gamma,
        elapsed=time.perf_counter() - t0,
        method="modal" if not blocks else "modal + Jordan chains",
    )
    if given and hasattr(modes, "__dict__"):  # kept with the (immutable) modes for the next call
        modes.__dict__.setdefault("_expansion", expansion)
    return expansion
