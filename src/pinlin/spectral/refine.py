"""Symmetric-definite pencils (A - w M) phi = 0 by eigh and Newton refinement (theory: spectrum).

``eigh(A, M)`` reduces the pencil with a Cholesky factor of M, so its backward
error grows like eps cond(M): 1e-12 to 1e-9 on pendulum chains of 20 to 200
links.  Newton's method for the equations X^T M X = I, X^T A X = W, in the form
of Ogita and Aishima ("Iterative refinement for symmetric eigenvalue
decomposition", Japan J. Indust. Appl. Math. 35, 2018) taken in the M inner
product, removes that error with matrix products only:

.. math::
    R = I - X^T M X,\\quad T = X^T A X,\\quad
    \\tilde w_i = \\frac{t_{ii}}{1 - r_{ii}},\\quad
    E_{ij} = \\frac{t_{ij} + \\tilde w_j r_{ij}}{\\tilde w_j - \\tilde w_i}\\ (i \\ne j),\\quad
    E_{ii} = \\frac{r_{ii}}{2},\\quad X \\leftarrow X + X E

(E_ij = r_ij / 2 where the two eigenvalues are too close for the first-order
update, see :data:`REFINE_COUPLING`).  Each step costs five products of size n,
against about fifteen n^3 flops of ``eigh`` itself, and squares the error; the
backward error of every pair is measured after each step, not assumed.

Column j of the update needs only column j of E, hence columns j of R and T
(symmetrized with their rows j) and the diagonal estimates w~: a step is taken
on the pairs whose backward error is still above the tolerance, the others are
kept (eigh leaves about 40 % of the pairs of a hanging chain above
1e-15 and one step all but a few).  With more than :data:`REFINE_PARTIAL` of
the pairs to refine the full step is cheaper (its products are shared).

When eps cond(M) exceeds :data:`EIGH_PREDICTION_LIMIT`, eigh's start is too
poor for Newton's method and the caller takes QZ directly (backward stable
whatever M's conditioning) instead of running eigh and discarding it.  cond(M)
is LAPACK's estimate from the Cholesky factor (:func:`mass_factor`: ``dpotrf``
and ``dpocon``, n^3/3 flops), and eigh reuses that factor: ``dsygst``, ``dsyevd``
and ``dtrsm``, the very steps of LAPACK's ``dsygvd`` after its own Cholesky
factorization (so the same results, bitwise, without factorizing M twice).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
from scipy.linalg.blas import dtrsm as _dtrsm
from scipy.linalg.lapack import dpocon as _dpocon
from scipy.linalg.lapack import dpotrf as _dpotrf
from scipy.linalg.lapack import dsyevd as _dsyevd
from scipy.linalg.lapack import dsygst as _dsygst
from scipy.linalg.lapack import dsygvd as _dsygvd

from ..numerics.floating import EPS

__all__ = [
    "MassFactor",
    "mass_factor",
    "RefinedPencil",
    "refined_eigh",
    "pencil_backward_errors",
    "eigh_predicted_ok",
    "REFINE_STEPS",
    "REFINE_COUPLING",
    "REFINE_PARTIAL",
    "EIGH_PREDICTION_LIMIT",
]

#: Largest number of Newton steps: each squares the relative error of the vectors; two took
#: every start up to eps cond(M) = 0.5 to rounding, one more is the margin.
REFINE_STEPS = 3

#: An off-diagonal correction |E_ij| above this means w_i and w_j are too close for the
#: first-order update: the pair is only re-orthogonalized (E_ij = r_ij / 2), as Ogita and
#: Aishima do for clusters; such pairs keep eigh's accuracy unless later steps separate them.
REFINE_COUPLING = 0.1

#: Share of the pairs above which a Newton step updates every column (five products of
#: size n) rather than only those above the tolerance (seven products of n x n by n x m).
REFINE_PARTIAL = 0.5

#: eps cond(M) above which eigh's start is too poor to be refined reliably: measured on six-link
#: chains with a near-massless tip link, eigh's backward error went from 5e-8 (eps cond(M) = 5e-4)
#: to 2e-5 (0.5), and two Newton steps took each to rounding; beyond 1e-2 M is within a factor
#: 1/(n eps cond(M)) < 100 of losing definiteness to rounding, and QZ is the safe choice.
EIGH_PREDICTION_LIMIT = 1e-2


@dataclass(frozen=True, eq=False)
class RefinedPencil:
    """Eigenvalues and M-orthonormal vectors of (A, M) with the products and backward errors.

    Attributes
    ----------
    w : (n,) float
        Eigenvalues (Rayleigh quotients of the returned vectors).
    X, MX, AX : (n, n) float
        Vectors (columns) and their products with M and A.
    eta : (n,) float
        Backward errors ||A x - w M x|| / ((|w| ||M|| + ||A||) ||x||), Frobenius norms.
    steps : int
        Newton steps taken.
    """

    w: np.ndarray
    X: np.ndarray
    MX: np.ndarray
    AX: np.ndarray
    eta: np.ndarray
    steps: int


@dataclass(frozen=True, eq=False)
class MassFactor:
    """The Cholesky factor of a symmetric M and the condition estimate that predicts eigh's accuracy.

    Attributes
    ----------
    lower : (n, n) float or None
        L with M = L L^T in the lower triangle (the upper one is not referenced); None
        when the factorization failed (M not numerically positive definite).
    condition : float
        LAPACK's estimate of cond_1(M) = ||M||_1 ||M^-1||_1 (``dpocon``: a lower bound on
        it, in practice within a factor of 3, and cond_2(M) <= cond_1(M) <= n cond_2(M) for
        symmetric M); inf when the factorization failed.
    """

    lower: np.ndarray | None
    condition: float


def mass_factor(M: np.ndarray) -> MassFactor:
    """:class:`MassFactor` of a finite symmetric M: ``dpotrf`` and ``dpocon`` (n^3/3 + O(n^2) flops)."""
    L, info = _dpotrf(M, lower=1, clean=0)
    if info != 0:
        return MassFactor(None, float("inf"))
    rcond, info = _dpocon(L, float(np.abs(M).sum(axis=0).max()), uplo="L")
    if info != 0 or not rcond > 0:
        return MassFactor(L, float("inf"))
    return MassFactor(L, float(1.0 / rcond))


def eigh_predicted_ok(cond_M: float, limit: float = EIGH_PREDICTION_LIMIT) -> bool:
    """Whether eigh's start can be refined to rounding: eps cond(M) <= ``limit``."""
    return bool(np.isfinite(cond_M) and EPS * cond_M <= limit)


def pencil_backward_errors(w, X, MX, AX, norm_A: float, norm_M: float) -> np.ndarray:
    """||A x_j - w_j M x_j|| / ((|w_j| ||M|| + ||A||) ||x_j||) per column (0 for an exact zero residual)."""
    R = AX - MX * w
    num = np.linalg.norm(R, axis=0)
    den = (np.abs(w) * norm_M + norm_A) * np.linalg.norm(X, axis=0)
    if np.count_nonzero(num) == num.size and np.count_nonzero(den > 0) == den.size:
        return num / den
    return np.where(num == 0, 0.0, num / np.where(den > 0, den, np.finfo(float).tiny))


def _newton_step(w, X, MX, AX) -> np.ndarray:
    """One Ogita-Aishima step in the M inner product: the refined vectors."""
    n = X.shape[1]
    R = -(X.T @ MX)
    R.reshape(-1)[:: n + 1] += 1.0  # the diagonal (a view of the contiguous product)
    T = X.T @ AX
    R = 0.5 * (R + R.T)  # symmetric in exact arithmetic
    T = 0.5 * (T + T.T)
    d = R.diagonal().copy()
    wt = T.diagonal() / (1.0 - d)
    gap = wt[None, :] - wt[:, None]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        E = (T + R * wt[None, :]) / gap
    close = ~(np.abs(E) <= REFINE_COUPLING)
    np.copyto(E, 0.5 * R, where=close)
    E.reshape(-1)[:: n + 1] = 0.5 * d
    return X + X @ E


def _newton_columns(X, MX, AX, J) -> np.ndarray:
    """Columns J of one Ogita-Aishima step (the others unchanged): the refined X[:, J].

    R[:, J] and T[:, J] symmetrized with their rows J, (R + R^T)/2 = I - (X^T M X_J + (M X)^T X_J)/2
    (M and A symmetric), and the diagonal estimates w~_i = x_i^T A x_i / x_i^T M x_i of every pair.
    """
    XJ = X[:, J]
    diagonal = (J, np.arange(J.size))  # entries (j, column of j) of the n x m blocks
    R = -0.5 * (X.T @ MX[:, J] + MX.T @ XJ)
    d = R[diagonal] + 1.0
    R[diagonal] = d
    T = 0.5 * (X.T @ AX[:, J] + AX.T @ XJ)
    wt = np.einsum("ij,ij->j", X, AX) / np.einsum("ij,ij->j", X, MX)
    wJ = wt[J][None, :]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        E = (T + R * wJ) / (wJ - wt[:, None])
    close = ~(np.abs(E) <= REFINE_COUPLING)
    np.copyto(E, 0.5 * R, where=close)
    E[diagonal] = 0.5 * d
    return XJ + X @ E


def _eigh(A, M, factor):
    """(w, X, info) of LAPACK's ``dsygvd`` (itype 1, lower), from M's lower Cholesky factor when given."""
    if factor is None:
        return _dsygvd(A, M, itype=1, jobz="V", uplo="L")
    reduced, info = _dsygst(A, factor, itype=1, lower=1)
    if info != 0:
        return None, None, info
    w, Z, info = _dsyevd(reduced, compute_v=1, lower=1, overwrite_a=1)
    if info != 0:
        return None, None, info
    return w, _dtrsm(1.0, factor, Z, lower=1, trans_a=1, overwrite_b=1), 0


def refined_eigh(
    A, M, norm_A: float, norm_M: float, tol: float, max_steps: int = REFINE_STEPS, factor: np.ndarray | None = None
) -> RefinedPencil:
    """(A - w M) x = 0 by ``eigh`` and up to ``max_steps`` Newton steps, until every backward error <= ``tol``.

    Each step refines the pairs whose backward error is above ``tol`` (all of them, by the
    full step, when they are more than :data:`REFINE_PARTIAL` of the pairs); every backward
    error is measured again after it.

    Parameters
    ----------
    A, M : (n, n) float
        A symmetric, M symmetric positive definite.
    norm_A, norm_M : float
        Frobenius norms (the weights of the backward errors).
    tol : float
        The backward error the pairs must reach; refinement stops there.
    max_steps : int
        Newton steps allowed.
    factor : (n, n) float, optional
        The lower Cholesky factor of M (:attr:`MassFactor.lower`) when the caller has it:
        eigh then continues from it (the steps of ``dsygvd`` after its factorization).

    Returns
    -------
    RefinedPencil
        The caller checks ``eta`` against ``tol`` (refinement may stop short of it).
    """
    w, X, info = _eigh(A, M, factor)
    if info != 0:  # LAPACK's divide and conquer failed: scipy's driver (it raises a LinAlgError on a real failure)
        w, X = sla.eigh(A, M, check_finite=False)
    MX, AX = M @ X, A @ X
    eta = pencil_backward_errors(w, X, MX, AX, norm_A, norm_M)
    steps = 0
    n = X.shape[1]
    while steps < max_steps and eta.max() > tol:
        J = (eta > tol).nonzero()[0]
        if J.size > REFINE_PARTIAL * n:
            X = _newton_step(w, X, MX, AX)
            MX, AX = M @ X, A @ X
            w = np.einsum("ij,ij->j", X, AX) / np.einsum("ij,ij->j", X, MX)
            eta = pencil_backward_errors(w, X, MX, AX, norm_A, norm_M)
        else:
            XJ = _newton_columns(X, MX, AX, J)
            MXJ, AXJ = M @ XJ, A @ XJ
            wJ = np.einsum("ij,ij->j", XJ, AXJ) / np.einsum("ij,ij->j", XJ, MXJ)
            X[:, J], MX[:, J], AX[:, J], w[J] = XJ, MXJ, AXJ, wJ  # arrays of this call: updated in place
            eta[J] = pencil_backward_errors(wJ, XJ, MXJ, AXJ, norm_A, norm_M)
        steps += 1
    return RefinedPencil(w, X, MX, AX, eta, steps)
