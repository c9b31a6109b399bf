"""The dynamic flexibility H(s) = L(s)^-1 and the spectral form of the adjugate (theory: flexibility, paper Sec. 10).

.. math::
    H(s) = L(s)^{-1} = \\frac{\\operatorname{adj} L(s)}{p(s)}
         = \\sum_{k=1}^{2n} \\frac{x_k y_k^T}{s - \\lambda_k}
    \\quad (L \\text{ simple},\\ y_k^T L'(\\lambda_k) x_k = 1)

with Jordan-block terms for defective eigenvalues (:mod:`pinlin.frf.engine`),
and, multiplying by ``p(s) = det M prod_k (s - lam_k)`` (paper Corollary 10.2),

.. math::
    \\operatorname{adj} L(s) = \\det M \\sum_k x_k y_k^T \\prod_{j \\ne k} (s - \\lambda_j).
"""

from __future__ import annotations

import time
import warnings

import numpy as np

from ..adjoint.adjugate import AdjugateMatrix, adjugate_residual
from ..errors import NotSimpleError
from ..errors.deprecated import renamed_keywords
from ..linearization.system import check_system
from ..numerics import (
    LOG_MAX,
    LOG_TINY,
    check_tolerance,
    checked_exp,
    complex_points,
    complex_scalar,
)
from ..results import ResultArray
from .engine import DEFAULT_METHOD, DEFAULT_TOL, per_point, solve, warn_inaccurate
from .expansion import check_modes

__all__ = ["FlexibilityArray", "flexibility", "flexibility_columns", "modal_adjugate", "check_modes"]


class FlexibilityArray(ResultArray):
    """``H(s)``: (n, n) for a scalar s, (len(s), n, n) otherwise (points first, like numpy's matrix stacks).

    A read-only complex ndarray; the figures below live on the returned array
    only (slices and arithmetic results are plain arrays).

    Attributes
    ----------
    s : complex or (len(s),) complex ndarray
        Evaluation points [1/s] (a scalar for a scalar input).
    defects : float or (len(s),) ndarray
        Relative defect ``||L(s) H - I|| / (||L(s)|| ||H|| + ||I||)`` per point
        (Frobenius norms; the normwise backward error, :mod:`pinlin.frf.engine`;
        the modal method on many points gives it exactly at sampled ones and an
        upper bound elsewhere).
    distance : float, (len(s),) ndarray or None
        Distance [1/s] of each point to the nearest computed eigenvalue; None
        without a modal analysis.
    error : float
        ``max(defects)``.
    method : str
        ``"direct"`` (LU per point), ``"modal"`` or ``"modal + Jordan chains"``.
    elapsed : float
        Seconds.
    residual
        Deprecated alias of ``defects`` (pinlin 0.1).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> H = pinlin.flexibility(sys, [0.5j, 1.0j, 2.0j])
    >>> H.shape, H.method, bool(H.error < 1e-12)
    ((3, 2, 2), 'direct', True)
    """

    _fields = ("s", "defects", "distance", "method", "error", "elapsed")

    @property
    def residual(self):
        warnings.warn("FlexibilityArray.residual is now .defects", DeprecationWarning, stacklevel=2)
        return self.defects


def flexibility_columns(sys, s, *, rows=None, cols=None, method: str = DEFAULT_METHOD, modes=None, check: bool = True):
    """``H(s)[rows][:, cols]`` for many points, with the relative defect per point.

    Returns ``(H, defects)`` with H of shape (len(s), len(rows), len(cols));
    ``defects`` is None with ``check=False``.  Kept for code written against
    pinlin 0.1; :func:`pinlin.frf.engine.solve` is the engine.

    Raises
    ------
    ParameterError, ComputationError
        As :func:`flexibility`.
    """
    sys = check_system(sys)
    pts, _ = complex_points(s, "s")
    n = sys.n
    cols = np.arange(n) if cols is None else np.asarray(cols, dtype=int)
    B = np.eye(n)[:, cols]
    out = solve(sys, pts, B, method=method, modes=modes, rows=rows, check=check)
    return out.X, out.defects


@renamed_keywords(tol="error_tol")
def flexibility(
    sys, s, *, method: str = DEFAULT_METHOD, modes=None, error_tol: float = DEFAULT_TOL
) -> FlexibilityArray:
    """The dynamic flexibility ``H(s) = L(s)^-1`` [rad/(N m), m/N], vectorized over s (theory: flexibility).

    .. math::  H(s) = (s^2 M + s C + K)^{-1} = \\sum_k \\frac{x_k y_k^T}{s - \\lambda_k}
               + \\text{(Jordan-block terms)}

    Parameters
    ----------
    sys : LinearizedSystem
    s : complex or 1-D array of complex
        Points [1/s] (``s = i omega`` for a harmonic response), finite.
    method : {"direct", "modal"}
        "direct" (default): LU factorization of L(s) at every point, backward
        stable.  "modal": the modal expansion of ``modes`` (eigenpairs with
        Lancaster-normalized left vectors, Jordan chains for defective
        eigenvalues), see :mod:`pinlin.frf.engine`.
    modes : Modes, optional
        Result of :func:`pinlin.modal_analysis` (computed for ``method="modal"``
        when omitted; with "direct" it only gives ``distance``).
    error_tol : float
        An :class:`~pinlin.AccuracyWarning` is issued when ``error`` exceeds it
        (``tol`` is its deprecated spelling).

    Returns
    -------
    FlexibilityArray
        (n, n) for a scalar s, (len(s), n, n) otherwise, complex, with
        ``defects`` (per point), ``error``, ``distance``, ``method``, ``elapsed``.

    Raises
    ------
    ParameterError
        Bad ``sys``, ``s`` (shape, non-finite), ``method``, ``modes`` or ``error_tol``,
        or a point at an eigenvalue (a pole of H).
    ComputationError
        L(s) overflows; the modal expansion does not apply to these modes.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> H = pinlin.flexibility(sys, 1.0j)
    >>> np.round(np.asarray(H), 6)
    array([[ 0.249377-5.012469j, -0.249377-4.987531j],
           [-0.249377-4.987531j,  0.249377-5.012469j]])
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    pts, scalar = complex_points(s, "s")
    error_tol = check_tolerance(error_tol, "error_tol")
    out = solve(sys, pts, np.eye(sys.n), method=method, modes=modes)
    warn_inaccurate("flexibility", method, out.defects, error_tol, "s", pts, exact=out.exact)
    return FlexibilityArray(
        out.X[0] if scalar else out.X,
        s=per_point(pts, scalar),
        defects=per_point(out.defects, scalar),
        distance=per_point(out.distance, scalar),
        error=out.error,
        method=method if out.expansion is None else out.expansion.method,
        elapsed=time.perf_counter() - t0,
    )


def _modal_weights(lam: complex, ev: np.ndarray, log_det_m: float, sign_m: float):
    """Weights det M prod_{j != k} (lam - lam_j), in logarithms: (scaled weights, log scale, det parts)."""
    diff = lam - ev
    with np.errstate(divide="ignore"):
        logd = np.log(np.abs(diff))
    phase = np.where(diff != 0, diff / np.where(diff != 0, np.abs(diff), 1.0), 0.0)
    zero = ~np.isfinite(logd)
    finite_sum = float(np.sum(logd[~zero]))
    total_phase = complex(np.prod(phase[~zero]))
    if zero.sum() >= 2:
        weights_log = np.full(ev.size, -np.inf)
    elif zero.sum() == 1:
        weights_log = np.where(zero, finite_sum, -np.inf)
    else:
        weights_log = finite_sum - logd
    # weight_k = det M prod_{j != k} (lam - lam_j) = det M * total_phase / phase_k * exp(weights_log_k)
    with np.errstate(invalid="ignore", divide="ignore"):
        ph = np.where(zero, total_phase, total_phase / np.where(phase != 0, phase, 1.0))
    top = float(np.max(weights_log)) if np.any(np.isfinite(weights_log)) else 0.0
    w = np.where(np.isfinite(weights_log), np.exp(weights_log - top), 0.0) * ph * sign_m
    det_log = finite_sum + log_det_m if not zero.any() else -np.inf
    return w, top + log_det_m, det_log, total_phase


def modal_adjugate(sys, lam, modes=None) -> AdjugateMatrix:
    """The spectral representation of the adjugate (paper Corollary 10.2, theory: flexibility).

    .. math::
        \\operatorname{adj} L(\\lambda) = \\det M \\sum_{k} x_k y_k^T \\prod_{j\\ne k}(\\lambda - \\lambda_j)

    with Lancaster-normalized modes; valid for a simple dynamic stiffness, also
    at an eigenvalue ``lam_k`` (where it reduces to ``p'(lam_k) x_k y_k^T``).
    The products are accumulated in logarithms.

    Parameters
    ----------
    sys : LinearizedSystem
    lam : complex
        Point [1/s].
    modes : Modes, optional
        Result of :func:`pinlin.modal_analysis` (computed when omitted).

    Returns
    -------
    AdjugateMatrix
        With ``det = det M prod_k (lam - lam_k)`` and the residual of
        ``L adj L = p I``.

    Raises
    ------
    ParameterError
        Bad ``sys``, ``lam`` or ``modes``.
    NotSimpleError
        The dynamic stiffness is not simple (a defective eigenvalue has no
        Lancaster-normalized left vector).
    ComputationError
        The adjugate over- or underflows double precision.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam = complex_scalar(lam, "lam")
    modes = check_modes(sys, modes)
    normalized = np.asarray(modes.left_normalized)
    if not modes.is_simple or not np.all(normalized):
        bad = np.flatnonzero(~normalized)
        where = f" near {complex(modes.eigenvalues[bad[0]]):.6g}" if bad.size else ""
        raise NotSimpleError(
            "the spectral form of the adjugate needs a simple dynamic stiffness (every eigenvalue "
            f"semisimple, left eigenvectors normalized y^T L' x = 1); this system has a defective eigenvalue"
            f"{where}: use pinlin.adjugate (SVD form) instead",
            lam=complex(modes.eigenvalues[bad[0]]) if bad.size else None,
        )
    sign_m, log_m = np.linalg.slogdet(sys.M)
    w, log_scale, det_log, total_phase = _modal_weights(lam, np.asarray(modes.eigenvalues), log_m, sign_m)
    scaled = (np.asarray(modes.right) * w[None, :]) @ np.asarray(modes.left).T
    A = scaled * checked_exp(log_scale, f"adj L({lam:.6g})")
    with np.errstate(invalid="ignore"):
        p_scaled = sign_m * total_phase * np.exp(det_log - log_scale) if np.isfinite(det_log) else 0.0
    if not np.isfinite(det_log):
        det = 0.0j
    elif LOG_TINY < det_log < LOG_MAX:
        det = complex(sign_m * total_phase * np.exp(det_log))
    else:
        det = None
    L = sys.dynamic_stiffness(lam).astype(complex)
    sv = np.linalg.svd(L, compute_uv=False)
    return AdjugateMatrix(
        A,
        lam=lam,
        det=det,
        log_abs_det=float(det_log),
        log_scale=0.0,
        residual=adjugate_residual(L, scaled, complex(p_scaled)),
        singular_values=sv,
        rank_one_defect=float(sv[-1] / sv[-2]) if sys.n > 1 and sv[-2] > 0 else 0.0,
        method="modal (paper Corollary 10.2)",
        elapsed=time.perf_counter() - t0,
    )
