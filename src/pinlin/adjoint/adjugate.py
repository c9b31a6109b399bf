"""The adjugate (classical adjoint) of the dynamic stiffness (theory: adjoint, paper Sec. 7-9).

.. math::
    L(\\lambda)\\,\\operatorname{adj} L(\\lambda) = \\operatorname{adj} L(\\lambda)\\,L(\\lambda)
    = p(\\lambda)\\, I, \\qquad
    \\operatorname{adj} L(\\lambda) = \\sum_{k=0}^{2n-2} A_k \\lambda^k

Evaluated through the singular value decomposition ``L = U diag(s) V^H``:

.. math::
    \\operatorname{adj} L = \\det U \\,\\det V^H\\; V \\operatorname{diag}\\Bigl(\\prod_{j \\ne i} s_j\\Bigr) U^H

which stays accurate where L is singular (at eigenvalues, where the adjugate of a
matrix of rank n - 1 is the rank-one matrix ``prod_{j<n} s_j v_n u_n^H`` up to
phase) and is computed in logarithms so that it never overflows before the
final, checked conversion (:mod:`pinlin.adjoint.svd`).  The error figure is the
residual of the defining identity, ``max(||L A - p I||, ||A L - p I||) / (||L|| ||A||)``
(Frobenius norms, theory: error figures).  The adjugate as a matrix polynomial and its
Taylor coefficients are in :mod:`pinlin.adjoint.adjugate_series` (re-exported here).
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import ParameterError
from ..linearization.system import check_system
from ..numerics.checks import complex_scalar
from ..numerics.floating import LOG_MAX, LOG_TINY, checked_exp
from ..results import ResultArray
from .adjugate_series import AdjugatePolynomial, AdjugateTaylor, adjugate_polynomial, adjugate_taylor
from .svd import det_over_scale, residual_scaled, svd_adjugate

__all__ = [
    "AdjugateMatrix",
    "adjugate",
    "adjugate_residual",
    "AdjugatePolynomial",
    "adjugate_polynomial",
    "AdjugateTaylor",
    "adjugate_taylor",
]

def adjugate_residual(L, A, p) -> float:
    """Relative residual of ``L A = A L = p I``: ``max(||LA - pI||, ||AL - pI||) / (||L|| ||A||)``.

    Parameters
    ----------
    L, A : (n, n) array_like
        A matrix and a candidate adjugate.
    p : complex
        A candidate ``det L``.

    Raises
    ------
    ParameterError
        L and A are not square matrices of one shape.
    """
    L = np.asarray(L, dtype=complex)
    A = np.asarray(A, dtype=complex)
    if L.ndim != 2 or L.shape[0] != L.shape[1] or A.shape != L.shape:
        raise ParameterError("L, A", f"expected two square matrices of the same shape, got {L.shape} and {A.shape}")
    na = np.linalg.norm(A)
    scale = na if na > 0 else 1.0
    return residual_scaled(L, A / scale, complex(p) / scale)


class AdjugateMatrix(ResultArray):
    """``adj L(lam)``: an (n, n) complex ndarray that also carries its error figures.

    The figures live on the returned array only (:class:`pinlin.results.ResultArray`):
    slices and arithmetic results are plain arrays without them.  The array is read-only.

    Attributes
    ----------
    lam : complex
        Where it was evaluated [1/s].
    det : complex or None
        ``p(lam) = det L(lam)`` from the same SVD (divided by ``exp(log_scale)``
        for a scaled adjugate); None when outside double range.
    log_abs_det : float
        ``log |det L(lam)|`` (natural logarithm; ``-inf`` when exactly singular).
    log_scale : float
        The adjugate is this array times ``exp(log_scale)`` (0 unless scaled).
    residual : float
        ``max(||L A - p I||, ||A L - p I||) / (||L|| ||A||)`` (theory: error figures).
    singular_values : (n,) ndarray
        Singular values of ``L(lam)``, descending.
    rank_one_defect : float
        ``s_n / s_{n-1}`` of L: the ratio of the second to the largest singular
        value of the adjugate.  Small at a root where the adjugate has rank one
        (paper Sec. 8); 0 for n = 1.
    method : str
    elapsed : float
        Seconds [s].
    error : float
        The relative residual of the defining identity (``residual``).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> A = pinlin.adjugate(sys, 1.0j)
    >>> A.shape, complex(np.round(A.det, 6))
    ((2, 2), (-0.01+0.2j))
    """

    _fields = (
        "lam",
        "det",
        "log_abs_det",
        "log_scale",
        "residual",
        "singular_values",
        "rank_one_defect",
        "method",
        "error",
        "elapsed",
    )

    def __new__(cls, values, **fields):
        if fields.get("error") is None:
            fields["error"] = fields.get("residual")
        return super().__new__(cls, values, **fields)


def adjugate(sys, lam, *, scaled: bool = False) -> AdjugateMatrix:
    """The adjugate ``adj L(lam)`` of the dynamic stiffness, also where L(lam) is singular.

    .. math::
        \\operatorname{adj} L = \\det U\\,\\det V^H\\, V \\operatorname{diag}\\Bigl(\\prod_{j\\ne i} s_j\\Bigr) U^H,
        \\qquad L(\\lambda) = U \\operatorname{diag}(s) V^H

    (theory: adjoint).  ``L adj L = adj L L = p(lam) I``; at a simple root its
    nonzero columns are right eigenvectors and its nonzero rows left ones
    (:func:`pinlin.adjoint.adjugate_eigenvectors`).

    Parameters
    ----------
    sys : LinearizedSystem
    lam : complex
        Point [1/s] (finite).
    scaled : bool
        Return ``adj L(lam) / exp(log_scale)`` (largest singular value 1) with
        the natural logarithm ``log_scale`` of the factor: for large systems whose
        adjugate is beyond double precision (a 100-link chain's reaches 1e480).

    Returns
    -------
    AdjugateMatrix
        (n, n) complex ndarray with ``det`` (of L, divided by ``exp(log_scale)``
        too when scaled; None when it is outside double range), ``log_abs_det``,
        ``log_scale`` (0 unless scaled), ``residual`` (= ``error``),
        ``singular_values``, ``rank_one_defect``, ``method``, ``elapsed``.

    Raises
    ------
    ParameterError
        ``sys`` is not a LinearizedSystem, ``lam`` not a finite scalar.
    ComputationError
        The adjugate over- or underflows double precision (and ``scaled`` is False).

    Examples
    --------
    For n = 2, adj [[a, b], [c, d]] = [[d, -b], [-c, a]]:

    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> A = pinlin.adjugate(sys, 1.0j)
    >>> np.round(np.asarray(A), 6)
    array([[1.+0.1j, 1.+0.j ],
           [1.+0.j , 1.+0.1j]])
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam = complex_scalar(lam, "lam")
    L = sys.dynamic_stiffness(lam).astype(complex)
    f = svd_adjugate(L[None])
    scale = float(f.log_scale[0])
    log_det = float(f.log_det[0])
    if not np.isfinite(scale):  # adj is exactly zero (L = 0 with n >= 2, or rank <= n - 2 exactly)
        A = np.zeros_like(L)
        det = 0.0 + 0.0j
        residual = residual_scaled(L, A, 0.0)
        log_scale = 0.0
    else:
        p_scaled = det_over_scale(f)
        residual = residual_scaled(L, f.scaled[0], p_scaled)
        if scaled:
            A, det, log_scale = f.scaled[0], p_scaled, scale
        else:
            A = f.scaled[0] * checked_exp(scale, f"adj L({lam:.6g})")
            log_scale = 0.0
            if not np.isfinite(log_det):
                det = 0.0j
            elif LOG_TINY < log_det < LOG_MAX:
                det = complex(f.phase[0] * np.exp(log_det))
            else:
                det = None
    s = f.singular_values[0]
    defect = float(s[-1] / s[-2]) if sys.n > 1 and s[-2] > 0 else (0.0 if sys.n == 1 else 1.0)
    return AdjugateMatrix(
        A,
        lam=lam,
        det=det,
        log_abs_det=log_det,
        log_scale=log_scale,
        residual=residual,
        singular_values=s,
        rank_one_defect=defect,
        method="SVD form, log-scaled",
        elapsed=time.perf_counter() - t0,
    )
