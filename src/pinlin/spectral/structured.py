"""Cheaper exact solver paths for structured mechanical systems.

Each path solves an n-size problem instead of the 2n-size companion pencil
and returns the same :class:`~pinlin.spectral.qep.RawSpectrum`; the backward
error and condition number of every pair are then computed from the original
L(lam) exactly as for the general path, so a path is never trusted blindly.

================  =========================  =======================================
path              applies when               method
================  =========================  =======================================
``symmetric``     D = G = N = 0              eigh(S, M): lam = +-sqrt(-mu)
``squared``       D = G = 0, N != 0          QZ of (-K, M) in mu = lam^2 (size n)
``proportional``  G = N = 0, D M^-1 S        one eigh; per mode
                  = S M^-1 D                 lam^2 + d_j lam + k_j = 0
``general``       otherwise, tuple input     scaled companion QZ (size 2n)
================  =========================  =======================================

"Zero" means exactly zero, as :meth:`LinearizedSystem.is_zero` reports
(``pinlin.linearize`` already sets rounding noise of G and N to exact zeros).
With D = G = 0 the dynamic stiffness L(lam) = lam^2 M + K depends on lam^2
only, so the spectrum is symmetric under lam -> -lam; with K symmetric as
well L is symmetric and the right eigenvector is also the left one.
"""

from __future__ import annotations

import numpy as np

from ..errors import ComputationError
from ..numerics.norms import frobenius
from .problem import QuadraticProblem
from .qep import RawSpectrum, complex_columns, dggev, exact_pairs, products
from .refine import RefinedPencil, pencil_backward_errors, refined_eigh

__all__ = ["solve_symmetric", "solve_squared", "solve_proportional", "proportionality_defect", "PATHS"]

#: Names of the solver paths, in the order they are tried by ``method="auto"``.
PATHS = ("symmetric", "squared", "proportional", "general")

#: Mixing weight of D in the single eigh of the proportional path (an
#: irrational number, so that distinct (k_j, d_j) pairs get distinct keys).
_MIX = 0.6180339887498949


def _mirrored(lam_a, lam_b, X, MX, CX, KX) -> RawSpectrum:
    """One member of each pair with the shared real vectors, the other in ``second`` (see RawSpectrum)."""
    return RawSpectrum(
        lam=lam_a, P=np.stack([X, MX, CX, KX]), Y=None, block=np.zeros(lam_a.shape[0], dtype=int), second=lam_b
    )


def solve_symmetric(
    problem: QuadraticProblem, eigh_tol: float, factor: np.ndarray | None = None
) -> tuple[RawSpectrum, RefinedPencil]:
    """D = G = N = 0: (S - mu M) phi = 0 by eigh and Newton refinement, lam = +-sqrt(-mu), x = y = phi.

    mu > 0 gives the conjugate pair +-i sqrt(mu) (an undamped mode); mu < 0 the
    real pair -+sqrt(-mu) (divergence); mu = 0 a double zero (rigid-body mode).
    L(lam) = lam^2 M + S is symmetric: the left vectors are the right ones.
    ``factor``: M's lower Cholesky factor when the caller has it (see
    :func:`~pinlin.spectral.refine.refined_eigh`).

    Returns
    -------
    raw : RawSpectrum
    pencil : RefinedPencil
        The pencil's solution with its backward errors and the Newton steps taken
        (:func:`pinlin.spectral.refine.refined_eigh`); the caller switches to
        :func:`solve_squared` (QZ) when they stay above ``eigh_tol``.
    """
    sys = problem.system
    M, S = sys.M, sys.S
    pencil = refined_eigh(S, M, problem.norm_K, problem.norm_M, eigh_tol, factor=factor)
    mu = pencil.w
    root = np.sqrt(np.abs(mu))
    pos = mu > 0
    lam_a = np.where(pos, 1j * root, -root + 0j)
    lam_b = np.where(pos, -1j * root, root + 0j)
    return _mirrored(lam_a, lam_b, pencil.X, pencil.MX, np.zeros_like(pencil.MX), pencil.AX), pencil


def solve_squared(problem: QuadraticProblem) -> RawSpectrum:
    """D = G = 0: (K + mu M) x = 0 by QZ of size n, lam = +-sqrt(mu).

    L(lam) = lam^2 M + K, so each eigenvalue mu of the n-size pencil (-K, M)
    with vectors (x, y) gives the two eigenvalues +-sqrt(mu) of L with the same
    vectors.  A conjugate pair (mu, conj mu) gives the four eigenvalues
    +-sqrt(mu), +-conj(sqrt(mu)), arranged as two conjugate pairs.  When K is
    symmetric (N = 0) so is L, and QZ computes right vectors only.

    Raises
    ------
    ComputationError
        QZ failed or found an infinite eigenvalue (M numerically singular).
    """
    M, K = problem.M, problem.K
    symmetric = problem.symmetric
    alphar, alphai, beta, vl, vr = dggev(-K, M.copy(), left=not symmetric)
    if np.any(beta == 0):
        raise ComputationError("QZ of (-K, M) found an infinite eigenvalue: M is numerically singular")
    mu = exact_pairs(alphar, alphai, beta)
    P = complex_columns(products(problem, vr), alphai)
    Y = None if symmetric else complex_columns(vl, alphai, conjugate=True)
    # real mu: roots s and -s; complex mu (first of its pair): s and its conjugate
    # come from mu and conj(mu) -> build as pairs (s, conj s) and (-s, -conj s).
    lam_list, idx_list = [], []
    j = 0
    n = mu.shape[0]
    while j < n:
        if alphai[j] == 0:
            m = mu[j].real
            if m < 0:
                s = 1j * np.sqrt(-m)
                lam_list += [s, -s]
            else:
                s = np.sqrt(m) + 0j
                lam_list += [-s, s]
            idx_list += [j, j]
            j += 1
        else:
            s = np.sqrt(mu[j])  # principal root, Re s > 0
            lam_list += [s, np.conj(s), -s, -np.conj(s)]
            idx_list += [j, j + 1, j, j + 1]
            j += 2
    lam = np.array(lam_list, dtype=complex)
    idx = np.array(idx_list, dtype=int)
    P = P[..., idx]
    return RawSpectrum(lam=lam, P=P, Y=None if Y is None else Y[:, idx], block=np.zeros(lam.shape[0], dtype=int))


def proportionality_defect(problem: QuadraticProblem) -> float:
    """||D M^-1 S - S M^-1 D|| / (||D|| ||M^-1|| ||S||) (Frobenius; 2-norm for M^-1).

    Zero in exact arithmetic exactly when M^-1 D and M^-1 S commute, i.e. when
    the undamped modes also diagonalize D (Caughey and O'Kelly, 1965).
    """
    sys = problem.system
    D, S = sys.D, sys.S
    nd, ns = frobenius(D), frobenius(S)
    if nd == 0 or ns == 0:
        return 0.0
    MiS, MiD = np.split(np.linalg.solve(sys.M, np.hstack((S, D))), 2, axis=1)
    comm = D @ MiS - S @ MiD
    inv_norm = 1.0 / np.linalg.eigvalsh(sys.M)[0]
    return float(frobenius(comm) / nd / ns / inv_norm)


def solve_proportional(
    problem: QuadraticProblem, *, structure_tol: float, eigh_tol: float, eigh_ok: bool = True,
    factor: np.ndarray | None = None,
) -> tuple[RawSpectrum | None, float, str]:
    """G = N = 0 with proportional damping: modal decoupling.

    The modes phi_j of the pencil (S + t D, M) (t a fixed irrational weight)
    diagonalize S and D together when D M^-1 S = S M^-1 D; each mode then obeys

    .. math::  \\lambda^2 + d_j \\lambda + k_j = 0,\\qquad
               d_j = \\frac{\\phi_j^T D \\phi_j}{\\phi_j^T M \\phi_j},\\;
               k_j = \\frac{\\phi_j^T S \\phi_j}{\\phi_j^T M \\phi_j}

    solved without cancellation.  The modes come from ``eigh`` with Newton
    refinement (:func:`pinlin.spectral.refine.refined_eigh`); when their backward
    error stays above ``eigh_tol``, or ``eigh_ok`` is False (M too ill-conditioned
    for eigh, predicted by the caller), from QZ of the same n-size pencil instead.
    ``factor``: M's lower Cholesky factor when the caller has it.

    Returns
    -------
    raw : RawSpectrum or None
        None when some mode is not an eigenvector of both (S, M) and (D, M) to
        ``structure_tol``, or QZ returned complex modes.
    defect : float
        Largest relative residual ||D phi - d M phi|| / ((|d| ||M|| + ||D||) ||phi||),
        and the same for S.
    how : str
        "eigh", "eigh + Newton" or "QZ".
    """
    sys = problem.system
    M, D, S = sys.M, sys.D, sys.S
    nd, ns = frobenius(D), frobenius(S)
    # S + t D with t = _MIX ns / nd, formed as (_MIX ns) (D / nd): t alone may overflow
    A = S + (_MIX * ns) * (D / nd) if nd > 0 and ns > 0 else S + _MIX * D
    norm_M, norm_A = frobenius(M), frobenius(A)
    Phi = None
    if eigh_ok:
        pencil = refined_eigh(A, M, norm_A, norm_M, eigh_tol, factor=factor)
        if pencil.eta.max() <= eigh_tol:
            Phi, MP = pencil.X, pencil.MX
            how = "eigh" if pencil.steps == 0 else "eigh + Newton"
    if Phi is None:
        alphar, alphai, beta, _, vr = dggev(A.copy(), M.copy(), left=False)
        if np.any(alphai != 0) or np.any(beta == 0):
            return None, np.inf, "QZ"
        Phi = vr
        MP = M @ Phi
        how = "QZ"
    DP, SP = D @ Phi, S @ Phi
    m = np.einsum("ij,ij->j", Phi, MP)
    d = np.einsum("ij,ij->j", Phi, DP) / m
    k = np.einsum("ij,ij->j", Phi, SP) / m
    defect = float(max(np.max(pencil_backward_errors(d, Phi, MP, DP, nd, norm_M)),
                       np.max(pencil_backward_errors(k, Phi, MP, SP, ns, norm_M))))
    if defect > structure_tol:
        return None, defect, how
    disc = d * d - 4 * k
    sq = np.sqrt(np.abs(disc))
    lam_a = np.empty(d.shape, dtype=complex)
    lam_b = np.empty(d.shape, dtype=complex)
    cplx = disc < 0
    lam_a[cplx] = -d[cplx] / 2 + 0.5j * sq[cplx]
    lam_b[cplx] = np.conj(lam_a[cplx])
    real = ~cplx
    sign = np.where(d[real] >= 0, 1.0, -1.0)
    q = -(d[real] + sign * sq[real]) / 2  # the root of larger modulus, no cancellation
    with np.errstate(divide="ignore", invalid="ignore"):
        other = np.where(q != 0, k[real] / np.where(q != 0, q, 1.0), 0.0)
    lam_a[real] = np.minimum(q, other)
    lam_b[real] = np.maximum(q, other)
    raw = _mirrored(lam_a, lam_b, Phi, MP, DP, SP)
    # real roots of one mode differ in modulus and take different places in the order: stored in full
    return (raw if cplx.all() else raw.expanded()), defect, how
