"""The dynamic flexibility H(s) = L(s)^-1 and its spectral forms (SPEC section 4, paper Sec. 10).

.. math::
    H(s) = L(s)^{-1} = \\frac{\\operatorname{adj} L(s)}{p(s)}
         = \\sum_{k=1}^{2n} \\frac{x_k y_k^T}{s - \\lambda_k}
    \\quad (L \\text{ simple},\\ y_k^T L'(\\lambda_k) x_k = 1)

and, multiplying by ``p(s) = det M prod_k (s - lam_k)`` (paper Corollary 10.2),

.. math::
    \\operatorname{adj} L(s) = \\det M \\sum_k x_k y_k^T \\prod_{j \\ne k} (s - \\lambda_j).

The error figure of every evaluation is the residual of the defining equation,
``||L(s) H(s) - I|| / (||L(s)|| ||H(s)||)`` (Frobenius norms, SPEC section 8),
computed without forming ``L(s)`` for all s at once.
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import NotSimpleError, ParameterError
from ..adjoint._circle import chunks
from ..adjoint._util import LOG_MAX, LOG_TINY, ResultArray, check_system, checked_exp, complex_points, complex_scalar
from ..adjoint.adjugate import AdjugateMatrix, _residual_scaled

__all__ = [
    "FlexibilityArray",
    "flexibility",
    "flexibility_columns",
    "modal_adjugate",
    "check_modes",
]

METHODS = ("direct", "modal")


class FlexibilityArray(ResultArray):
    """``H(s)``: (n, n) or (len(s), n, n) complex ndarray carrying its error figures.

    The attributes are set on the returned array only; slices and arithmetic
    results are plain data and carry None.

    Attributes
    ----------
    s : (len(s),) complex ndarray
        Evaluation points [1/s].
    residual : (len(s),) ndarray
        ``||L(s) H(s) - I|| / (||L(s)|| ||H(s)||)`` per point.
    error : float
        ``max(residual)``.
    method : str
        "direct" (LU factorization per point) or "modal" (spectral sum).
    elapsed : float
        Seconds.
    """

    _meta = ("s", "residual", "error", "method", "elapsed")


def check_modes(sys, modes):
    """``modes`` (or a fresh :func:`pinlin.modal_analysis`) validated for the modal form."""
    if modes is None:
        from ..spectral import modal_analysis

        modes = modal_analysis(sys)
    for attr in ("eigenvalues", "right", "left"):
        if not hasattr(modes, attr):
            raise ParameterError("modes", f"expected the result of pinlin.modal_analysis, got {type(modes).__name__}")
    n = sys.n
    if modes.right.shape != (n, 2 * n) or modes.left.shape != (n, 2 * n) or modes.eigenvalues.shape != (2 * n,):
        raise ParameterError(
            "modes",
            f"expected eigenvectors of shape {(n, 2 * n)} and {2 * n} eigenvalues for this system, got "
            f"{modes.right.shape}, {modes.left.shape}, {modes.eigenvalues.shape}",
        )
    simple = getattr(modes, "is_simple", True)
    normalized = np.all(getattr(modes, "left_normalized", True))
    if not simple or not normalized:
        bad = np.flatnonzero(~np.asarray(getattr(modes, "left_normalized", np.ones(2 * n, bool))))
        lam = complex(modes.eigenvalues[bad[0]]) if bad.size else None
        raise NotSimpleError(
            "the modal form of H needs a simple dynamic stiffness (every eigenvalue semisimple, left "
            "eigenvectors normalized y^T L' x = 1); this system has a defective eigenvalue"
            + (f" near {lam:.6g}" if lam is not None else "")
            + ": use method='direct', or pinlin.residues for the principal parts",
            lam=lam,
        )
    system = getattr(modes, "system", None)
    if system is not None and system is not sys:
        same = all(np.array_equal(getattr(system, a), getattr(sys, a)) for a in ("M", "C", "K"))
        if not same:
            raise ParameterError("modes", "these modes belong to a different system")
    return modes


def _equation_residual(sys, s: np.ndarray, H: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """``||L(s) H_c - I_c|| / (||L(s)|| ||H_c||)`` per point, for the columns ``cols`` of H.

    H has shape (len(s), n, len(cols)).  L(s) H is formed as ``s^2 (M H) + s (C H) + K H``
    with one matrix product over all points, so no (len(s), n, n) stack of L is built.
    """
    n = sys.n
    F, _, m = H.shape
    flat = np.moveaxis(H, 0, 1).reshape(n, F * m)
    MH, CH, KH = (np.asarray(A) @ flat for A in (sys.M, sys.C, sys.K))
    ss = np.repeat(s, m)
    LH = (ss * ss) * MH + ss * CH + KH
    LH = np.moveaxis(LH.reshape(n, F, m), 1, 0)
    LH[:, cols, np.arange(m)] -= 1.0
    res = np.linalg.norm(LH.reshape(F, -1), axis=1)
    a = np.abs(s)
    # ||L(s)||_F without forming it: ||s^2 M + s C + K||_F^2 expanded
    MM, CC, KK = (float(np.sum(np.asarray(A) ** 2)) for A in (sys.M, sys.C, sys.K))
    MC, MK, CK = (float(np.sum(np.asarray(A) * np.asarray(B))) for A, B in ((sys.M, sys.C), (sys.M, sys.K), (sys.C, sys.K)))
    sq = (
        a**4 * MM
        + a**2 * CC
        + KK
        + 2 * np.real(s * s * np.conj(s)) * MC
        + 2 * np.real(s * s) * MK
        + 2 * np.real(s) * CK
    )
    nL = np.sqrt(np.maximum(sq, 0.0))
    nH = np.linalg.norm(H.reshape(F, -1), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(nL * nH > 0, res / (nL * nH), np.where(res > 0, np.inf, 0.0))


def _direct_columns(sys, s: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """Columns ``cols`` of ``L(s)^-1`` by LU per point (batched LAPACK gesv): (len(s), n, len(cols))."""
    n = sys.n
    M, C, K = (np.asarray(a, dtype=complex) for a in (sys.M, sys.C, sys.K))
    rhs = np.zeros((n, len(cols)), dtype=complex)
    rhs[cols, np.arange(len(cols))] = 1.0
    out = np.empty((len(s), n, len(cols)), dtype=complex)
    for sl in chunks(len(s), n):
        z = s[sl, None, None]
        L = z * z * M + z * C + K
        try:
            out[sl] = np.linalg.solve(L, np.broadcast_to(rhs, (L.shape[0], n, len(cols))))
        except np.linalg.LinAlgError:
            bad = [i for i in range(L.shape[0]) if np.linalg.matrix_rank(L[i]) < n]
            k = sl.start + (bad[0] if bad else 0)
            raise ParameterError(
                "s",
                f"L(s) is exactly singular at s[{k}] = {s[k]:.10g}: s is an eigenvalue, where H has a pole "
                f"(use pinlin.residues there)",
            ) from None
    return out


def _modal_columns(modes, s: np.ndarray, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """``sum_k x_k[rows] y_k[cols]^T / (s - lam_k)``: (len(s), len(rows), len(cols))."""
    lam = np.asarray(modes.eigenvalues)
    X = np.asarray(modes.right)[rows]  # (r, 2n)
    Y = np.asarray(modes.left)[cols]  # (c, 2n)
    W = 1.0 / (s[:, None] - lam[None, :])  # (F, 2n)
    if len(cols) == 1:
        return ((W * Y[0][None, :]) @ X.T)[:, :, None]
    # (F, 2n) x (2n, r*c) via the Khatri-Rao product of the modal vectors
    XY = (X[:, None, :] * Y[None, :, :]).reshape(-1, lam.size)  # (r*c, 2n)
    return (W @ XY.T).reshape(len(s), len(rows), len(cols))


def flexibility_columns(sys, s, *, rows=None, cols=None, method: str = "direct", modes=None, check: bool = True):
    """``H(s)[rows][:, cols]`` for many points, with the residual per point.

    The workhorse behind :func:`flexibility` and
    :func:`pinlin.frequency_response`.  Returns ``(H, residual)`` with H of
    shape (len(s), len(rows), len(cols)); the residual needs all rows of the
    requested columns and is computed on them (``check=False`` skips it and
    returns None).
    """
    sys = check_system(sys)
    pts, _ = complex_points(s, "s")
    n = sys.n
    rows = np.arange(n) if rows is None else np.asarray(rows, dtype=int)
    cols = np.arange(n) if cols is None else np.asarray(cols, dtype=int)
    if method not in METHODS:
        raise ParameterError("method", f"expected one of {METHODS}, got {method!r}")
    if method == "direct":
        full = _direct_columns(sys, pts, cols)
    else:
        modes = check_modes(sys, modes)
        lam = np.asarray(modes.eigenvalues)
        hit = np.isin(pts, lam)
        if np.any(hit):
            k = int(np.flatnonzero(hit)[0])
            raise ParameterError("s", f"s[{k}] = {pts[k]:.10g} is an eigenvalue, where H has a pole")
        if check or len(rows) == n:
            full = _modal_columns(modes, pts, np.arange(n), cols)
        else:
            return _modal_columns(modes, pts, rows, cols), None
    residual = _equation_residual(sys, pts, full, cols) if check else None
    return full[:, rows, :], residual


def flexibility(sys, s, *, method: str = "direct", modes=None) -> FlexibilityArray:
    """The dynamic flexibility ``H(s) = L(s)^-1`` [rad/N m, m/N], vectorized over s.

    .. math::  H(s) = (s^2 M + s C + K)^{-1} = \\sum_k \\frac{x_k y_k^T}{s - \\lambda_k}

    Parameters
    ----------
    sys : LinearizedSystem
    s : complex or 1-D array of complex
        Points [1/s] (``s = i omega`` for a harmonic response); finite and not
        eigenvalues.
    method : {"direct", "modal"}
        "direct": LU factorization of L(s) at every point (batched LAPACK).
        "modal": the spectral sum with Lancaster-normalized eigenvectors
        ``y_k^T L'(lam_k) x_k = 1`` (SPEC section 4) from ``modes``; needs a
        simple dynamic stiffness.
    modes : Modes, optional
        Result of :func:`pinlin.modal_analysis` for ``method="modal"``
        (computed when omitted).

    Returns
    -------
    FlexibilityArray
        (n, n) for a scalar s, (len(s), n, n) otherwise, complex, with
        ``residual`` (per point), ``error``, ``method``, ``elapsed``.

    Raises
    ------
    ParameterError
        Bad ``sys``, ``s`` (shape, non-finite, an exact eigenvalue) or ``method``.
    NotSimpleError
        ``method="modal"`` for a system with a defective eigenvalue.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    pts, scalar = complex_points(s, "s")
    H, residual = flexibility_columns(sys, pts, method=method, modes=modes)
    out = H[0] if scalar else H
    return FlexibilityArray(
        out,
        s=pts,
        residual=residual,
        error=float(np.max(residual)),
        method=method,
        elapsed=time.perf_counter() - t0,
    )


def modal_adjugate(sys, lam, modes=None) -> AdjugateMatrix:
    """The spectral representation of the adjugate (paper Corollary 10.2).

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
    ParameterError, NotSimpleError, ComputationError
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam = complex_scalar(lam, "lam")
    modes = check_modes(sys, modes)
    ev = np.asarray(modes.eigenvalues)
    diff = lam - ev
    with np.errstate(divide="ignore"):
        logd = np.log(np.abs(diff))
    phase = np.where(diff != 0, diff / np.where(diff != 0, np.abs(diff), 1.0), 0.0)
    sign_m, log_m = np.linalg.slogdet(sys.M)
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
    X = np.asarray(modes.right)
    Y = np.asarray(modes.left)
    scaled = (X * w[None, :]) @ Y.T
    log_scale = top + log_m
    det_log = finite_sum + log_m if not zero.any() else -np.inf
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
        residual=_residual_scaled(L, scaled, complex(p_scaled)),
        singular_values=sv,
        rank_one_defect=float(sv[-1] / sv[-2]) if sys.n > 1 and sv[-2] > 0 else 0.0,
        method="modal (paper Corollary 10.2)",
        elapsed=time.perf_counter() - t0,
    )
