"""Eigenvectors read off the adjugate at a root (theory: adjoint, paper Sec. 8 and 9).

At a simple root ``lam_k`` of ``p``, ``L(lam_k)`` has rank n - 1 and
``adj L(lam_k)`` rank one (paper Prop. 8.2):

.. math::
    \\operatorname{adj} L(\\lambda_k) = p'(\\lambda_k)\\, x_k y_k^T, \\qquad
    y_k^T L'(\\lambda_k) x_k = 1, \\qquad
    p'(\\lambda_k) = \\operatorname{tr}\\bigl(\\operatorname{adj} L(\\lambda_k) L'(\\lambda_k)\\bigr)

so its nonzero columns are right eigenvectors ``L x = 0`` and its nonzero rows
left ones ``y^T L = 0`` (plain transpose).  A multiple root with one Jordan
chain still gives a rank-one adjugate but ``p'(lam_k) = 0`` (no Lancaster
normalization); a root of geometric multiplicity >= 2 gives ``adj L = 0``.

At a root of multiplicity m and geometric multiplicity 1 the adjugate's Taylor
coefficients ``T_j = adj L^{(j)}(lam0) / j!`` satisfy, from
``sum_{j<=i} L^{(j)}/j! T_{i-j} = p^{(i)}/i! I = 0`` for i < m (paper Prop. 9.1),
the Jordan chain equations column by column: ``x_j = T_j e_c``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..errors import NotAnEigenvalueError, NotSimpleError
from ..linearization.system import check_system
from ..numerics import accuracy
from ..numerics.checks import check_integer, check_tolerance, complex_scalar
from ..numerics.rank import ADJUGATE_RANK_TOL
from ..results import Result
from .adjugate_series import adjugate_taylor
from .svd import det_over_scale, residual_scaled, svd_adjugate

__all__ = [
    "AdjugateEigenvectors",
    "adjugate_eigenvectors",
    "AdjugateChain",
    "adjugate_chain",
    "backward_error",
    "chain_residual",
]

#: Default: lam is accepted as an eigenvalue when s_n(L) <= EIGENVALUE_TOL * s_1(L): an
#: eigenvalue computed to about eta leaves s_n at eta s_1 (1e-8 for a root split by
#: rounding into a double one), while a point that is no eigenvalue leaves it at O(s_1).
EIGENVALUE_TOL = 1e-8
#: Default: the root is simple when its condition number kappa (theory: adjoint) is below
#: 1 / SIMPLE_TOL.  A computed double root has kappa of about 1/sqrt(eps) ~ 1e8.
SIMPLE_TOL = 1e-6
#: Default for :func:`adjugate_chain`: a Taylor coefficient T_j counts as zero when its
#: term on its circle is below this fraction of the largest term; the terms of a
#: vanishing coefficient are rounding of about eps times the largest, those of a
#: genuine one comparable to it, and 1e-8 (about sqrt(eps)) separates both.
ZERO_TOL = 1e-8
#: T_j also counts as zero when its norm is within this factor of its own error bound.
ZERO_ERROR_FACTOR = 2.0
#: Largest |log10 p'(lam)| returned as a number (beyond, ``derivative`` is None and
#: only ``log10_abs_derivative`` is given): 300 leaves a margin to the double range 1e308.
DERIVATIVE_LOG10_RANGE = 300.0


def backward_error(sys, lam: complex, x: np.ndarray, *, left: bool = False) -> float:
    """Normwise backward error of an eigenpair (theory: adjoint), Frobenius norms.

    .. math::  \\eta(x, \\lambda) = \\frac{\\|L(\\lambda) x\\|}
               {(|\\lambda|^2\\|M\\| + |\\lambda|\\|C\\| + \\|K\\|)\\,\\|x\\|}

    with ``x^T L(lam)`` in the numerator for a left eigenvector (``left=True``);
    :func:`pinlin.numerics.backward_error` on the system's matrices.
    """
    return accuracy.backward_error(sys.M, sys.C, sys.K, lam, x, left=left)


@dataclass(frozen=True, repr=False, kw_only=True)
class AdjugateEigenvectors(Result):
    """Eigenvectors at a root read off ``adj L(lam)`` (paper Sec. 8).

    Attributes
    ----------
    eigenvalue : complex
        The root lam [1/s] at which the adjugate was evaluated.
    right : (n,) complex ndarray
        Right eigenvector ``L x = 0``: the adjugate's largest column, unit 2-norm,
        largest entry real positive.
    left : (n,) complex ndarray
        Left eigenvector ``y^T L = 0``: the adjugate's largest row (transposed,
        not conjugated), scaled to ``y^T L'(lam) x = 1`` when the root is simple,
        else unit 2-norm.
    derivative : complex or None
        ``p'(lam) = trace(adj L(lam) L'(lam))``; None when its modulus is outside
        10^-300 ... 10^300 (large systems in SI units; see the next field).
    log10_abs_derivative : float
        ``log10 |p'(lam)|``, always available.
    singular_ratio : float
        ``s_n / s_1`` of ``L(lam)``: how singular L is at lam.
    rank_one_defect : float
        ``s_n / s_{n-1}`` of L = second / largest singular value of the adjugate.
    simplicity : float
        ``1 / kappa`` with the homogeneous condition number of theory: adjoint,
        ``kappa = sqrt(|a|^4 ||M||^2 + |a|^2 |b|^2 ||C||^2 + |b|^4 ||K||^2) /
        |y^T (2 a conj(b) M + (|b|^2 - |a|^2) C - 2 conj(a) b K) x|`` (lam = a / b,
        |a|^2 + |b|^2 = 1, unit x and y); 0 for a multiple root, where
        ``y^T L'(lam) x = 0``.
    is_simple : bool
        ``simplicity > simple_tol``: lam is a simple root and ``left`` is
        Lancaster-normalized.
    backward_error_right, backward_error_left : float
        eta of (x, lam) and (y, lam) (theory: adjoint).
    adjugate_residual : float
        Residual of ``L adj L = p I`` (theory: error figures).
    elapsed : float
        Seconds [s].
    method : str
    error : float
        The larger backward error of the two eigenpairs,
        ``max(backward_error_right, backward_error_left)`` (relative, theory: adjoint).
    """

    eigenvalue: complex
    right: np.ndarray
    left: np.ndarray
    derivative: complex | None
    log10_abs_derivative: float
    singular_ratio: float
    rank_one_defect: float
    simplicity: float
    is_simple: bool
    backward_error_right: float
    backward_error_left: float
    adjugate_residual: float
    elapsed: float
    method: str = "largest column and row of the rank-one adjugate adj L(lam) (SVD form)"

    @property
    def error(self) -> float:
        return max(self.backward_error_right, self.backward_error_left)

    def __repr__(self) -> str:
        return (
            f"AdjugateEigenvectors(eigenvalue={self.eigenvalue:.6g}, is_simple={self.is_simple}, "
            f"log10|p'|={self.log10_abs_derivative:.1f}, "
            f"eta=({self.backward_error_right:.1e}, {self.backward_error_left:.1e}))"
        )


def adjugate_eigenvectors(
    sys,
    lam,
    *,
    eigenvalue_tol: float = EIGENVALUE_TOL,
    rank_tol: float = ADJUGATE_RANK_TOL,
    simple_tol: float = SIMPLE_TOL,
) -> AdjugateEigenvectors:
    """Right and left eigenvectors and ``p'(lam)`` from the adjugate at a root lam (paper Sec. 8).

    .. math::
        \\operatorname{adj} L(\\lambda_k) = p'(\\lambda_k)\\,x_k y_k^T,\\quad
        p'(\\lambda_k) = \\operatorname{tr}(\\operatorname{adj} L(\\lambda_k) L'(\\lambda_k)),\\quad
        L'(\\lambda) = 2\\lambda M + C

    Parameters
    ----------
    sys : LinearizedSystem
    lam : complex
        An eigenvalue [1/s] (as accurate as possible: the eigenvectors' error is
        about the eigenvalue's error divided by the gap ``s_{n-1}(L)``).
    eigenvalue_tol : float
        lam is accepted as a root when ``s_n(L(lam)) <= eigenvalue_tol * s_1``.
    rank_tol : float
        The adjugate has rank one when ``s_{n-1}(L(lam)) > rank_tol * s_1``
        (default :data:`pinlin.numerics.ADJUGATE_RANK_TOL`).
    simple_tol : float
        The root is simple when ``1 / kappa > simple_tol`` (see ``simplicity``).

    Returns
    -------
    AdjugateEigenvectors

    Raises
    ------
    ParameterError
        Bad arguments.
    NotAnEigenvalueError
        ``L(lam)`` is not singular to ``eigenvalue_tol``.
    NotSimpleError
        The adjugate does not have rank one (geometric multiplicity >= 2): its
        columns do not determine an eigenvector.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> lam = pinlin.modal_analysis(sys).eigenvalues[0]
    >>> vectors = pinlin.adjugate_eigenvectors(sys, lam)
    >>> vectors.is_simple
    True
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam = complex_scalar(lam, "lam")
    for name, v in (("eigenvalue_tol", eigenvalue_tol), ("rank_tol", rank_tol), ("simple_tol", simple_tol)):
        check_tolerance(v, name)
    L = sys.dynamic_stiffness(lam).astype(complex)
    f = svd_adjugate(L[None])
    n = sys.n
    sv = f.singular_values[0]
    s = sv / sv[0] if sv[0] > 0 else np.zeros(n)
    ratio = float(s[-1])
    if ratio > eigenvalue_tol:
        raise NotAnEigenvalueError(
            f"lam = {lam:.10g} is not an eigenvalue: the smallest singular value of L(lam) is "
            f"{ratio:.2e} of the largest (eigenvalue_tol = {eigenvalue_tol:g})",
            lam=lam,
            distance=ratio,
        )
    if n > 1 and s[-2] <= rank_tol:
        raise NotSimpleError(
            f"adj L({lam:.10g}) does not have rank one: L has at least two singular values below "
            f"{rank_tol:g} of the largest ({s[-2]:.2e}, {s[-1]:.2e}); the eigenvalue has "
            f"geometric multiplicity >= 2 and the adjugate vanishes there (paper Sec. 9); use "
            f"pinlin.jordan_chains or pinlin.residues",
            lam=lam,
            measure=float(s[-2]),
        )
    # work on the scaled adjugate adj L / exp(log_scale): the adjugate of a large system can be
    # far beyond the overflow threshold although its direction (the eigenvectors) is not
    Aplain = f.scaled[0]
    log_scale = float(f.log_scale[0])
    residual = residual_scaled(L, Aplain, det_over_scale(f)) if n > 1 else 0.0
    col = int(np.argmax(np.linalg.norm(Aplain, axis=0)))
    row = int(np.argmax(np.linalg.norm(Aplain, axis=1)))
    x = Aplain[:, col].copy()
    y = Aplain[row, :].copy()
    x /= np.linalg.norm(x)
    big = int(np.argmax(np.abs(x)))
    x *= abs(x[big]) / x[big]
    y /= np.linalg.norm(y)
    dL = 2 * lam * sys.M + sys.C
    trace = complex(np.trace(Aplain @ dL))
    log10_deriv = (np.log(abs(trace)) + log_scale) / np.log(10) if trace != 0 else -np.inf
    deriv = trace * np.exp(log_scale) if abs(log10_deriv) < DERIVATIVE_LOG10_RANGE or trace == 0 else None
    yLx = complex(y @ dL @ x)
    simplicity = 1.0 / accuracy.condition_number(sys.M, sys.C, sys.K, lam, x, y)
    simple = bool(simplicity > simple_tol)
    if simple:
        y = y / yLx
    return AdjugateEigenvectors(
        eigenvalue=lam,
        right=x,
        left=y,
        derivative=deriv,
        log10_abs_derivative=float(log10_deriv),
        singular_ratio=ratio,
        rank_one_defect=float(s[-1] / s[-2]) if n > 1 and s[-2] > 0 else 0.0,
        simplicity=float(simplicity),
        is_simple=simple,
        backward_error_right=backward_error(sys, lam, x),
        backward_error_left=backward_error(sys, lam, y, left=True),
        adjugate_residual=float(residual),
        elapsed=time.perf_counter() - t0,
    )


def chain_residual(sys, lam0, vectors) -> float:
    """Relative residual of the Jordan chain equations (theory: adjoint): the largest over the equations.

    .. math::
        \\max_i \\frac{\\|\\sum_{j=0}^{i} L^{(j)}(\\lambda_0)/j!\\; x_{i-j}\\|}
        {\\sum_{j=0}^{i} w_j\\,\\|x_{i-j}\\|}

    with ``L^(0) = L``, ``L' = 2 lam0 M + C``, ``L''/2 = M`` and the weights
    ``w_j`` of :func:`pinlin.numerics.chain_residuals` (Frobenius-norm bounds of
    those blocks, as in eta).

    Raises
    ------
    ParameterError
        ``sys`` is not a LinearizedSystem or ``lam0`` not a finite scalar.
    """
    sys = check_system(sys)
    lam0 = complex_scalar(lam0, "lam0")
    return max(accuracy.chain_residuals(sys.M, sys.C, sys.K, lam0, vectors), default=0.0)


@dataclass(frozen=True, repr=False, kw_only=True)
class AdjugateChain(Result):
    """A Jordan chain ``x_0, ..., x_{r-1}`` at lam0 from the adjugate's Taylor coefficients (Sec. 9).

    Attributes
    ----------
    lam0 : complex
    vectors : list of (n,) complex ndarray
        ``x_j = T_{g+j} e_c / ||T_g e_c||`` for the column c with the largest
        ``||T_g e_c||``, where ``T_g`` is the first Taylor coefficient of the
        adjugate that does not vanish (g = 0 when lam0 has geometric multiplicity 1).
    multiplicity : int
        Algebraic multiplicity m used (zeros of p at lam0).
    residual : float
        :func:`chain_residual` of the vectors.
    taylor_error : (len(vectors),) ndarray
        Relative a-posteriori error of the Taylor coefficients used.
    elapsed : float
        Seconds [s].
    method : str
    error : float
        The chain residual (``residual``, relative).
    """

    lam0: complex
    vectors: list
    multiplicity: int
    residual: float
    taylor_error: np.ndarray
    elapsed: float
    method: str = "columns of the Taylor coefficients of the adjugate at lam0 (paper Prop. 9.1)"

    @property
    def error(self) -> float:
        return self.residual

    def __repr__(self) -> str:
        return (
            f"AdjugateChain(lam0={self.lam0:.6g}, length={len(self.vectors)}, "
            f"multiplicity={self.multiplicity}, residual={self.residual:.1e})"
        )


def adjugate_chain(sys, lam0, multiplicity: int, *, zero_tol: float = ZERO_TOL) -> AdjugateChain:
    """A Jordan chain at a root of multiplicity m from the adjugate's derivatives (paper Sec. 9).

    From ``sum_{j<=i} L^{(j)}/j! T_{i-j} = p^{(i)}(lam0)/i! I = 0`` for i < m
    (Prop. 9.1), the columns of the Taylor coefficients ``T_j`` of the adjugate
    form Jordan chains.  When ``T_0 = ... = T_{g-1} = 0`` (geometric multiplicity
    above one) the chain starts at ``T_g`` and has length ``m - g``.

    Parameters
    ----------
    sys : LinearizedSystem
    lam0 : complex
        The root [1/s].
    multiplicity : int
        Its algebraic multiplicity m (for example the number of computed
        eigenvalues in its cluster, or from :func:`pinlin.residues`).
    zero_tol : float
        ``T_j`` counts as zero when ``||T_j|| r_j^j <= zero_tol * max_i ||T_i|| r_i^i``
        (each term on the circle of radius ``r_j`` it was computed on, against the
        largest such term) or when ``||T_j||`` is within :data:`ZERO_ERROR_FACTOR`
        times its error bound.

    Raises
    ------
    ParameterError
        Bad arguments.
    NotSimpleError
        Every Taylor coefficient below m vanishes: no chain can be read off.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam0 = complex_scalar(lam0, "lam0")
    m = check_integer(multiplicity, "multiplicity", low=1, high=2 * sys.n)
    check_tolerance(zero_tol, "zero_tol")
    tay = adjugate_taylor(sys, lam0, m - 1)
    norms = np.linalg.norm(tay.coef.reshape(m, -1), axis=1)
    # compare each T_j on the scale of the radius it came from: T_j r^j vs the largest such term
    r = np.where(tay.radius > 0, tay.radius, 1.0)
    terms = norms * r ** np.arange(m)
    scale = terms.max() if terms.size else 0.0
    g = 0
    while g < m and (terms[g] <= zero_tol * scale or norms[g] <= ZERO_ERROR_FACTOR * tay.coef_error[g]):
        g += 1
    if g == m:
        raise NotSimpleError(
            f"the adjugate and its first {m - 1} derivatives vanish at lam0 = {lam0:.10g}: "
            f"no Jordan chain can be read off the adjugate; use pinlin.jordan_chains",
            lam=lam0,
            measure=float(scale),
        )
    col = int(np.argmax(np.linalg.norm(tay.coef[g], axis=0)))
    scale0 = np.linalg.norm(tay.coef[g][:, col])
    vectors = [tay.coef[j][:, col] / scale0 for j in range(g, m)]
    rel = tay.relative_error[g:m]
    return AdjugateChain(
        lam0=lam0,
        vectors=vectors,
        multiplicity=m,
        residual=chain_residual(sys, lam0, vectors),
        taylor_error=np.asarray(rel, dtype=float),
        elapsed=time.perf_counter() - t0,
    )

