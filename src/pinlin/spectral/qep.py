"""The general solver: companion linearization, scaling and QZ (SPEC section 4).

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
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lapack

from ..errors import ComputationError
from .accuracy import backward_errors
from .problem import QuadraticProblem, Scaling

__all__ = ["RawSpectrum", "solve_general", "companion_pencil", "complex_columns", "exact_pairs"]


@dataclass(frozen=True, eq=False)
class RawSpectrum:
    """What a solver path hands to the result: eigenvalues, vectors and products.

    Attributes
    ----------
    lam : (2n,) complex
        Eigenvalues; complex ones come in exactly conjugate pairs.
    X, Y : (n, 2n) complex
        Right and left (y^T L = 0) eigenvectors, any scaling.
    MX, CX, KX : (n, 2n) complex
        Products of the original coefficients with X.
    block : (2n,) int
        Companion block the right vector was recovered from (1 or 2), 0 for
        structured paths.
    """

    lam: np.ndarray
    X: np.ndarray
    Y: np.ndarray
    MX: np.ndarray
    CX: np.ndarray
    KX: np.ndarray
    block: np.ndarray


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


def complex_columns(R: np.ndarray, alphai: np.ndarray, conjugate: bool = False) -> np.ndarray:
    """LAPACK's real storage of eigenvectors -> complex columns.

    A conjugate pair (alphai[j] > 0) is stored as columns j (real part) and j+1
    (imaginary part): v_j = R_j + i R_{j+1}, v_{j+1} = conj(v_j).  With
    ``conjugate`` the conjugates of those vectors are returned.
    """
    out = R.astype(complex)
    first = np.flatnonzero(alphai > 0)
    re, im = R[:, first], R[:, first + 1]
    sign = -1.0 if conjugate else 1.0
    out[:, first] = re + sign * 1j * im
    out[:, first + 1] = re - sign * 1j * im
    return out


def exact_pairs(alphar: np.ndarray, alphai: np.ndarray, beta: np.ndarray) -> np.ndarray:
    """(alphar + i alphai) / beta with each pair (alphai[j] > 0, j + 1) made exactly conjugate.

    LAPACK's two betas of a pair may differ in the last bits; the vectors of a
    pair are conjugate by construction, so the eigenvalues must be too.
    """
    lam = (alphar + 1j * alphai) / beta
    first = np.flatnonzero(alphai > 0)
    lam[first + 1] = np.conj(lam[first])
    return lam


def _dggev(A: np.ndarray, B: np.ndarray, left: bool = True):
    lwork = 8 * A.shape[0]
    vl = int(left)
    *_, work, info = lapack.dggev(A, B, compute_vl=vl, compute_vr=1, lwork=-1)
    if info == 0:
        lwork = max(lwork, int(work[0]))
    alphar, alphai, beta, vl, vr, _, info = lapack.dggev(
        A, B, compute_vl=vl, compute_vr=1, lwork=lwork, overwrite_a=1, overwrite_b=1
    )
    if info != 0:
        raise ComputationError(f"LAPACK dggev (QZ) failed with info = {info} on a pencil of size {A.shape[0]}")
    return alphar, alphai, beta, vl, vr


def solve_general(problem: QuadraticProblem, *, scaling: Scaling | None = None) -> RawSpectrum:
    """All 2n eigentriples of L(lam) by QZ on the scaled first companion form.

    Parameters
    ----------
    problem : QuadraticProblem
    scaling : Scaling, optional
        Default: the problem's Fan-Lin-Van Dooren scaling; ``Scaling(1, 1)``
        gives plain QZ on the unscaled pencil.

    Raises
    ------
    ComputationError
        QZ failed, or returned an infinite or non-finite eigenvalue (M is then
        numerically singular).
    """
    s = problem.scaling if scaling is None else scaling
    n = problem.n
    A, B = companion_pencil(*problem.scaled(s))
    # L(lam)^T = L(lam) when M, C, K are symmetric: the left vectors are the right ones
    symmetric = all(np.array_equal(X, X.T) for X in (problem.M, problem.C, problem.K))
    alphar, alphai, beta, vl, vr = _dggev(A, B, left=not symmetric)
    finite = (beta != 0) & np.isfinite(alphar) & np.isfinite(alphai)
    if not np.all(finite):
        raise ComputationError(
            f"QZ found {int(np.sum(~finite))} infinite eigenvalue(s): M is numerically singular "
            f"(||M|| = {problem.norm_M:.3g})"
        )
    lam = s.gamma * exact_pairs(alphar, alphai, beta)
    # right vectors: both blocks, real storage, one product per coefficient
    V = vr
    MV = problem.M @ V[:n]
    CV = problem.C @ V[:n]
    KV = problem.K @ V[:n]
    MW = problem.M @ V[n:]
    CW = problem.C @ V[n:]
    KW = problem.K @ V[n:]
    X1, MX1, CX1, KX1 = (complex_columns(R, alphai) for R in (V[:n], MV, CV, KV))
    X2, MX2, CX2, KX2 = (complex_columns(R, alphai) for R in (V[n:], MW, CW, KW))
    eta1 = backward_errors(problem, lam, X1, MX1, CX1, KX1)
    eta2 = backward_errors(problem, lam, X2, MX2, CX2, KX2)
    use1 = eta1 < eta2
    pick = use1[None, :]
    X = np.where(pick, X1, X2)
    MX = np.where(pick, MX1, MX2)
    CX = np.where(pick, CX1, CX2)
    KX = np.where(pick, KX1, KX2)
    Y = X.copy() if symmetric else complex_columns(vl[:n], alphai, conjugate=True)
    block = np.where(use1, 1, 2)
    return RawSpectrum(lam, X, Y, MX, CX, KX, block)
