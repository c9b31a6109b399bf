"""The general solver: companion linearization, scaling and QZ (theory: spectrum).

For real M, C, K with M nonsingular, the first companion form of the scaled
problem (lambda = gamma mu, see :class:`~pinlin.spectral.problem.Scaling`)

.. math::
    A - \\mu B = \\begin{bmatrix} -C_s & -K_s \\\\ I & 0 \\end{bmatrix}
      - \\mu \\begin{bmatrix} M_s & 0 \\\\ 0 & I \\end{bmatrix},
    \\qquad z = \\begin{bmatrix} \\mu x \\\\ x \\end{bmatrix},
    \\qquad w = \\begin{bmatrix} y \\\\ (\\mu M_s + C_s)^T y \\end{bmatrix}

is solved by LAPACK's QZ (``dggev``, right and left vectors).  The eigenvector
of the quadratic problem is recovered from the block of z that gives the
smaller backward error (Higham, Li and Tisseur, "Backward error of polynomial
eigenproblems solved by linearization", SIAM J. Matrix Anal. Appl. 29, 2007);
the left eigenvector is the first block of w.  When M, C and K are exactly
symmetric, L(lam)^T = L(lam), so y = x (plain transpose) and QZ computes right
vectors only.

A heavily damped problem, tau = ||C|| / sqrt(||M|| ||K||) > :data:`TROPICAL_TAU`,
has eigenvalues of two sizes, about ||C|| / ||M|| and ||K|| / ||C||, that no single
scaling serves (the backward error of the Fan-Lin-Van Dooren scaled QZ grows
with tau, to 1e-8 at tau = 1e8).  It is then solved again with the tropical
scalings gamma+ = ||C|| / ||M|| and gamma- = ||K|| / ||C|| (Gaubert and Sharify,
2009; Hammarling, Munro and Tisseur, "An algorithm for the complete solution
of quadratic eigenvalue problems", ACM TOMS 39, 2013), and each eigentriple
(conjugate pairs together) is taken from the run where its backward error is
smallest.
"""

from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np
from scipy.linalg import lapack
from scipy.optimize import linear_sum_assignment

from ..errors import ComputationError
from ..numerics.accuracy import residual_figures
from ..numerics.scaling import Scaling
from .ordering import spectrum_order
from .problem import QuadraticProblem
from .raw import RawSpectrum

__all__ = [
    "RawSpectrum",
    "solve_general",
    "companion_pencil",
    "complex_columns",
    "exact_pairs",
    "tropical_scalings",
    "TROPICAL_TAU",
    "dggev",
]

#: Damping measure tau = ||C|| / sqrt(||M|| ||K||) above which the general path uses
#: tropical scaling (two QZ runs) instead of the single Fan-Lin-Van Dooren scaling.
TROPICAL_TAU = 10.0


def products(problem: QuadraticProblem, V: np.ndarray) -> np.ndarray:
    """(4, n, k) [V, M V, C V, K V] for real or complex V (n, k): one matrix product with the stacked coefficients."""
    n, k = V.shape
    out = np.empty((4, n, k), dtype=V.dtype)
    out[0] = V
    out[1:] = (problem.stacked @ V).reshape(3, n, k)
    return out


def companion_pencil(M, C, K) -> tuple[np.ndarray, np.ndarray]:
    """(A, B) of the first companion form [[-C, -K], [I, 0]] - mu [[M, 0], [0, I]]."""
    n = M.shape[0]
    A = np.zeros((2 * n, 2 * n))
    B = np.zeros((2 * n, 2 * n))
    A[:n, :n] = -C
    A[:n, n:] = -K
    idx = np.arange(n)
    A[n + idx, idx] = 1.0
    B[:n, :n] = M
    B[n + idx, n + idx] = 1.0
    return A, B


def complex_columns(R: np.ndarray, alphai: np.ndarray, conjugate: bool = False, first=None) -> np.ndarray:
    """LAPACK's real storage of eigenvectors -> complex columns (the last axis; leading axes are batches).

    A conjugate pair (alphai[j] > 0) is stored as columns j (real part) and j+1
    (imaginary part): v_j = R_j + i R_{j+1}, v_{j+1} = conj(v_j).  With
    ``conjugate`` the conjugates of those vectors are returned.  ``first``, the
    indices j (``(alphai > 0).nonzero()[0]``), may be passed when known.
    """
    out = R.astype(complex)
    if first is None:
        first = (alphai > 0).nonzero()[0]
    if first.size:
        second = first + 1
        re, im = R.take(first, axis=-1), R.take(second, axis=-1)
        if conjugate:
            im = -im
        out.imag[..., first] = im
        out.real[..., second] = re
        out.imag[..., second] = -im
    return out


def exact_pairs(alphar: np.ndarray, alphai: np.ndarray, beta: np.ndarray, first=None) -> np.ndarray:
    """(alphar + i alphai) / beta with each pair (alphai[j] > 0, j + 1) made exactly conjugate.

    LAPACK's two betas of a pair may differ in the last bits; the vectors of a
    pair are conjugate by construction, so the eigenvalues must be too.
    ``first`` as in :func:`complex_columns`.
    """
    lam = np.empty(alphar.shape, dtype=complex)
    np.divide(alphar, beta, out=lam.real)
    np.divide(alphai, beta, out=lam.imag)
    if first is None:
        first = (alphai > 0).nonzero()[0]
    if first.size:
        lam[first + 1] = lam.take(first).conj()
    return lam


#: LAPACK's dggev needs a workspace of at least 8 n (its documented minimum).
_DGGEV_MIN_WORK = 8


@functools.lru_cache(maxsize=64)
def _dggev_lwork(size: int, left: bool) -> int:
    """LAPACK's optimal workspace of dggev for a pencil of this size (a pure function of the size: asked once)."""
    lwork = _DGGEV_MIN_WORK * size
    probe = np.eye(size)
    *_, work, info = lapack.dggev(probe, probe, compute_vl=int(left), compute_vr=1, lwork=-1)
    return max(lwork, int(work[0])) if info == 0 else lwork


def dggev(A: np.ndarray, B: np.ndarray, left: bool = True):
    """QZ of the real pencil (A, B) with right (and left) vectors; A and B are overwritten.

    Raises
    ------
    ComputationError
        LAPACK reports a failure.
    """
    alphar, alphai, beta, vl, vr, _, info = lapack.dggev(
        A, B, compute_vl=int(left), compute_vr=1, lwork=_dggev_lwork(A.shape[0], bool(left)),
        overwrite_a=1, overwrite_b=1,
    )
    if info != 0:
        raise ComputationError(f"LAPACK dggev (QZ) failed with info = {info} on a pencil of size {A.shape[0]}")
    return alphar, alphai, beta, vl, vr


def tropical_scalings(problem: QuadraticProblem, tau_max: float = TROPICAL_TAU) -> tuple[Scaling, Scaling] | None:
    """(gamma+ scaling, gamma- scaling) when tau = ||C|| / sqrt(||M|| ||K||) > tau_max, else None.

    gamma+ = ||C|| / ||M|| suits the large eigenvalues, gamma- = ||K|| / ||C|| the
    small ones; delta makes the largest scaled coefficient of size one.
    """
    nM, nC, nK = problem.norm_M, problem.norm_C, problem.norm_K
    if nK == 0 or nC == 0 or nC <= tau_max * np.sqrt(nM) * np.sqrt(nK):
        return None
    out = []
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        for gamma in (np.float64(nC) / nM, np.float64(nK) / nC):
            out.append(Scaling(float(gamma), float(1.0 / max(gamma * gamma * nM, gamma * nC, np.float64(nK)))))
    if any(problem.factors(s) is None for s in out):
        return None  # beyond double range: solve_general says so and keeps the Fan-Lin-Van Dooren run
    return out[0], out[1]


def solve_general(problem: QuadraticProblem, *, scaling: Scaling | None = None) -> RawSpectrum:
    """All 2n eigentriples of L(lam) by QZ on the scaled first companion form.

    Parameters
    ----------
    problem : QuadraticProblem
    scaling : Scaling, optional
        Default: the problem's Fan-Lin-Van Dooren scaling, or tropical scaling
        (two runs) when the problem is heavily damped (see the module doc);
        ``Scaling(1, 1)`` gives plain QZ on the unscaled pencil.

    Raises
    ------
    ComputationError
        QZ failed, or returned an infinite or non-finite eigenvalue (M is then
        numerically singular).
    """
    if scaling is not None:
        return _solve_scaled(problem, scaling)[0]
    tropical = tropical_scalings(problem)
    if tropical is None:
        raw = _solve_scaled(problem, problem.scaling)[0]
        tau = problem.norm_C / (np.sqrt(problem.norm_M) * np.sqrt(problem.norm_K)) if problem.norm_K else 0.0
        if tau > TROPICAL_TAU:  # heavily damped, yet no tropical scaling: their scales are out of range
            raw = replace(raw, note=(
                f"heavily damped (tau = {tau:.1e}), but the tropical scalings take the coefficients out of "
                f"double range: Fan-Lin-Van Dooren scaling only"
            ))
        return raw
    return _merge(problem, *tropical)


def _merge(problem: QuadraticProblem, plus: Scaling, minus: Scaling) -> RawSpectrum:
    """Each eigentriple from the run (Fan-Lin-Van Dooren, gamma+ or gamma-) with the smallest backward error.

    The Fan-Lin-Van Dooren run serves the eigenvalues of size sqrt(||K|| / ||M||)
    that a heavily damped problem may also have (damping concentrated on a few
    coordinates).  Runs are paired with the base run by an optimal assignment of
    eigenvalues; a conjugate pair is replaced only by an exactly conjugate pair,
    so pairs stay exact conjugates.
    """
    runs = [_solve_scaled(problem, s, allow_infinite=True) for s in (problem.scaling, plus, minus)]
    finite = [bool(np.all(np.isfinite(r.lam))) for r, _ in runs]
    if not any(finite[:2]):
        k = int(np.sum(~np.isfinite(runs[0][0].lam)))
        raise ComputationError(
            f"QZ found {k} infinite eigenvalue(s): M is numerically singular (||M|| = {problem.norm_M:.3g})"
        )
    base = 0 if finite[0] else 1
    cur, cur_eta = runs[base]
    source = np.full(cur.lam.shape[0], base)
    for k, (other, other_eta) in enumerate(runs):
        if k == base:
            continue
        with np.errstate(invalid="ignore"):
            cost = np.abs(cur.lam[:, None] - other.lam[None, :])
        ok = np.isfinite(cost)
        big = 2.0 * float(np.max(cost[ok], initial=0.0)) + 1.0  # no overflow in the assignment's sums
        _, partner = linear_sum_assignment(np.where(ok, cost, big))
        take = np.zeros(cur.lam.shape[0], dtype=bool)
        done = np.zeros(cur.lam.shape[0], dtype=bool)
        for i in range(cur.lam.shape[0]):
            if done[i]:
                continue
            group = [i]
            if cur.lam[i].imag != 0:  # its exact conjugate in the current spectrum
                mates = np.flatnonzero((cur.lam == np.conj(cur.lam[i])) & ~done)
                mates = mates[mates != i]
                if mates.size:
                    group.append(int(mates[0]))
            done[group] = True
            js = partner[group]
            if len(group) == 2 and other.lam[js[0]] != np.conj(other.lam[js[1]]):
                continue
            if np.max(other_eta[js]) < np.max(cur_eta[group]):
                take[group] = True
        Y = None
        if cur.Y is not None:
            Y = np.where(take, other.Y[:, partner], cur.Y)
        cur_eta = np.where(take, other_eta[partner], cur_eta)
        cur = replace(cur, lam=np.where(take, other.lam[partner], cur.lam), P=np.where(take, other.P[..., partner], cur.P),
                      Y=Y, block=np.where(take, other.block[partner], cur.block), eta=cur_eta, norm_x=None, weight=None,
                      ordered=False)
        source = np.where(take, k, source)
    tau = problem.norm_C / (np.sqrt(problem.norm_M) * np.sqrt(problem.norm_K))
    counts = [int(np.sum(source == k)) for k in range(3)]
    note = (
        f"heavily damped (tau = ||C||/sqrt(||M|| ||K||) = {tau:.1e} > {TROPICAL_TAU:g}): QZ with the "
        f"Fan-Lin-Van Dooren gamma = {problem.scaling.gamma:.3g} and the tropical gamma+ = {plus.gamma:.3g}, "
        f"gamma- = {minus.gamma:.3g}; each eigenpair from the run with the smallest backward error "
        f"({counts[0]}, {counts[1]} and {counts[2]} eigenvalues)"
    )
    return replace(cur, note=note)


def scaled_companion(problem: QuadraticProblem, s: Scaling) -> tuple[np.ndarray, np.ndarray]:
    """(A, B) of :func:`companion_pencil` for the coefficients scaled by ``s``, formed in place.

    Raises
    ------
    ComputationError
        A scaled coefficient is out of double range (see :meth:`QuadraticProblem.factors`).
    """
    f = problem.factors(s)
    if f is None:
        problem.scaled(s)  # raises the range error with its message
    n = problem.n
    A = np.zeros((2 * n, 2 * n))
    B = np.zeros((2 * n, 2 * n))
    np.multiply(problem.C, -f[1], out=A[:n, :n])
    np.multiply(problem.K, -f[2], out=A[:n, n:])
    np.multiply(problem.M, f[0], out=B[:n, :n])
    # the identity blocks: entries (n + i, i) of A and (n + i, n + i) of B, i < n, in the flat C-order arrays
    A.reshape(-1)[2 * n * n :: 2 * n + 1] = 1.0
    B.reshape(-1)[2 * n * n + n :: 2 * n + 1] = 1.0
    return A, B


def _solve_scaled(
    problem: QuadraticProblem, s: Scaling, *, allow_infinite: bool = False
) -> tuple[RawSpectrum, np.ndarray]:
    """QZ on the companion form scaled by ``s``: the raw spectrum and each pair's backward error.

    The right vector is taken from the block of z = (mu x, x) with the smaller
    backward error; both blocks and their products with M, C, K come from one
    matrix product and one conversion to complex columns.  With
    ``allow_infinite`` an infinite eigenvalue (the gamma- run of tropical
    scaling can push the large ones there) gets lam = inf and eta = inf instead
    of an error.

    Raises
    ------
    ComputationError
        QZ failed, or found an infinite eigenvalue (without ``allow_infinite``).
    """
    n = problem.n
    A, B = scaled_companion(problem, s)
    # L(lam)^T = L(lam) when M, C, K are symmetric: the left vectors are the right ones
    symmetric = problem.symmetric
    alphar, alphai, beta, vl, vr = dggev(A, B, left=not symmetric)
    first = (alphai > 0).nonzero()[0]
    if np.count_nonzero(beta) == beta.size:
        lam = exact_pairs(alphar, alphai, beta, first)
        lam *= s.gamma
        finite = np.isfinite(lam)
        all_finite = np.count_nonzero(finite) == finite.size
    else:
        finite = beta != 0
        all_finite = False
    if not all_finite:
        if not allow_infinite:
            raise ComputationError(
                f"QZ found {int(np.sum(~finite))} infinite eigenvalue(s): M is numerically singular "
                f"(||M|| = {problem.norm_M:.3g})"
            )
        finite &= np.isfinite(alphar) & np.isfinite(alphai)
        with np.errstate(divide="ignore", invalid="ignore"):
            lam = s.gamma * exact_pairs(alphar, alphai, np.where(finite, beta, 1.0))
        lam[~finite] = np.inf
    # right (both blocks of z = (mu x, x)) and left vectors to complex columns in one conversion
    Z = complex_columns(vr if symmetric else np.concatenate((vr, vl[:n])), alphai, first=first)
    if all_finite:  # in the order of the result from here on (every later step works column by column)
        perm, at = spectrum_order(lam)
        lam, Z = lam.take(perm), Z.take(perm, axis=1)
    # the two blocks side by side, (n, 4n), and their products with M, C, K from one real product
    # (a real matrix acts on the real and imaginary parts: the complex columns viewed as pairs)
    both = np.empty((4, n, 4 * n), dtype=complex)
    both[0, :, : 2 * n] = Z[:n]
    both[0, :, 2 * n :] = Z[n : 2 * n]
    both[1:] = (problem.stacked @ both[0].view(float)).view(complex).reshape(3, n, 4 * n)
    lam2 = np.concatenate((lam, lam))
    if all_finite:
        eta, nx, w = residual_figures(lam2, *both, problem.norms)
    else:
        with np.errstate(invalid="ignore", over="ignore"):  # lam = inf (allow_infinite): eta is set to inf below
            eta, nx, w = residual_figures(lam2, *both, problem.norms)
    eta, nx = eta.reshape(2, 2 * n), nx.reshape(2, 2 * n)
    use1 = eta[0] < eta[1]
    blocks = both.reshape(4, n, 2, 2 * n)  # [quantity, row, block, column]
    P = np.where(use1, blocks[:, :, 0], blocks[:, :, 1])
    Y = None if symmetric else Z[2 * n :].conj()
    best = np.where(use1, eta[0], eta[1])
    if not all_finite:
        best = np.where(finite, best, np.inf)
    block, norm_x, w = np.where(use1, 1, 2), np.where(use1, nx[0], nx[1]), w[: 2 * n]
    if all_finite:  # a pair's second member: the conjugate vectors and the first's figures, exactly
        mate = at + 1
        if 2 * at.size == lam.shape[0]:  # every eigenvalue in a pair: at = 0, 2, 4, ... (slices, the same columns)
            at, mate = slice(0, None, 2), slice(1, None, 2)
        P[..., mate] = P[..., at].conj()
        if Y is not None:
            Y[:, mate] = Y[:, at].conj()
        for a in (block, best, norm_x, w):
            a[mate] = a[at]
    raw = RawSpectrum(lam=lam, P=P, Y=Y, block=block, eta=best, norm_x=norm_x, weight=w, ordered=all_finite)
    return raw, best
