"""The adjugate (classical adjoint) of the dynamic stiffness (SPEC section 4, paper Sec. 7-9).

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
final, checked conversion.  The error figure is the residual of the defining
identity, ``max(||L A - p I||, ||A L - p I||) / (||L|| ||A||)`` (Frobenius norms,
SPEC section 8).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ._circle import chunks, fit_on_circles, ladder
from ._util import (
    LOG_MAX,
    LOG_TINY,
    ResultArray,
    check_radii,
    check_system,
    checked_exp,
    complex_scalar,
    eigenvalue_bounds,
    natural_scale,
)

__all__ = [
    "AdjugateMatrix",
    "adjugate",
    "adjugate_residual",
    "AdjugatePolynomial",
    "adjugate_polynomial",
    "AdjugateTaylor",
    "adjugate_taylor",
]

#: Ratio between successive radii of the sampling circles.
RADIUS_RATIO = 4.0
#: Span (smallest / largest radius) of the circles around a Taylor centre.
TAYLOR_SPAN = 1e-8


# ---------------------------------------------------------------------------- the SVD form


@dataclass(frozen=True)
class _SvdAdjugate:
    """Batched SVD-form adjugates: ``adj = scaled * exp(log_scale)``, ``det = phase * exp(log_det)``."""

    scaled: np.ndarray  # (N, n, n), largest singular value 1
    log_scale: np.ndarray  # (N,)
    phase: np.ndarray  # (N,) complex, |phase| = 1
    log_det: np.ndarray  # (N,), -inf for an exactly singular L
    singular_values: np.ndarray  # (N, n) of L, descending
    log_norm: np.ndarray  # (N,) log ||L||_F


def _svd_adjugate(L: np.ndarray) -> _SvdAdjugate:
    """Adjugates of a stack of matrices (N, n, n) by the SVD form, in logarithms."""
    L = np.asarray(L, dtype=complex)
    N, n, _ = L.shape
    norm = np.linalg.norm(L.reshape(N, -1), axis=1)
    zero = norm == 0
    safe = np.where(zero, 1.0, norm)
    U, s, Vh = np.linalg.svd(L / safe[:, None, None])
    with np.errstate(divide="ignore"):
        log_s = np.log(s)
    nz = np.isfinite(log_s)
    n_zero = np.sum(~nz, axis=1)
    total = np.sum(np.where(nz, log_s, 0.0), axis=1)
    # log prod_{j != i} s_j: one exact zero kills every term but its own, two kill all
    log_d = np.where(nz, total[:, None] - np.where(nz, log_s, 0.0), total[:, None])
    log_d = np.where((n_zero[:, None] == 1) & nz, -np.inf, log_d)
    log_d = np.where(n_zero[:, None] >= 2, -np.inf, log_d)
    log_norm = np.log(safe)
    log_d = log_d + (n - 1) * log_norm[:, None]
    log_det = np.where(n_zero > 0, -np.inf, total + n * log_norm)
    log_scale = np.max(log_d, axis=1)
    finite = np.isfinite(log_scale)
    log_scale_safe = np.where(finite, log_scale, 0.0)
    with np.errstate(invalid="ignore"):
        w = np.where(np.isfinite(log_d), np.exp(log_d - log_scale_safe[:, None]), 0.0)
    phase = np.linalg.det(U) * np.linalg.det(Vh)
    phase = phase / np.abs(phase)
    V = np.conj(np.swapaxes(Vh, 1, 2))
    Uh = np.conj(np.swapaxes(U, 1, 2))
    scaled = phase[:, None, None] * np.matmul(V * w[:, None, :], Uh)
    if n == 1:  # adj of a 1 x 1 matrix is [[1]], also for L = 0
        scaled = np.ones((N, 1, 1), dtype=complex)
        log_scale = np.zeros(N)
    elif np.any(zero):
        scaled[zero] = 0.0
        log_scale = np.where(zero, -np.inf, log_scale)
    return _SvdAdjugate(scaled, log_scale, phase, log_det, s * safe[:, None], log_norm)


def _residual_scaled(L: np.ndarray, A: np.ndarray, p_over_scale: complex) -> float:
    """``max(||L A - p I||, ||A L - p I||) / (||L|| ||A||)`` with A and p divided by a common scale."""
    nl = np.linalg.norm(L)
    na = np.linalg.norm(A)
    if nl == 0 or na == 0:
        return 0.0 if p_over_scale == 0 else float("inf")
    Ls = L / nl
    ps = p_over_scale / nl
    eye = ps * np.eye(L.shape[0])
    r1 = np.linalg.norm(Ls @ A - eye)
    r2 = np.linalg.norm(A @ Ls - eye)
    return float(max(r1, r2) / na)


def adjugate_residual(L, A, p) -> float:
    """Relative residual of ``L A = A L = p I``: ``max(||LA - pI||, ||AL - pI||) / (||L|| ||A||)``.

    Parameters
    ----------
    L, A : (n, n) array_like
        A matrix and a candidate adjugate.
    p : complex
        A candidate ``det L``.
    """
    L = np.asarray(L, dtype=complex)
    A = np.asarray(A, dtype=complex)
    if L.ndim != 2 or L.shape[0] != L.shape[1] or A.shape != L.shape:
        raise ParameterError("L, A", f"expected two square matrices of the same shape, got {L.shape} and {A.shape}")
    na = np.linalg.norm(A)
    scale = na if na > 0 else 1.0
    return _residual_scaled(L, A / scale, complex(p) / scale)


class AdjugateMatrix(ResultArray):
    """``adj L(lam)``: an (n, n) complex ndarray that also carries its error figures.

    The attributes are set on the returned array only; slices and arithmetic
    results are plain data and carry None.

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
        ``max(||L A - p I||, ||A L - p I||) / (||L|| ||A||)`` (SPEC section 8).
    singular_values : (n,) ndarray
        Singular values of ``L(lam)``, descending.
    rank_one_defect : float
        ``s_n / s_{n-1}`` of L: the ratio of the second to the largest singular
        value of the adjugate.  Small at a root where the adjugate has rank one
        (paper Sec. 8); 0 for n = 1.
    method : str
    elapsed : float
        Seconds.
    """

    _meta = (
        "lam",
        "det",
        "log_abs_det",
        "log_scale",
        "residual",
        "singular_values",
        "rank_one_defect",
        "method",
        "elapsed",
    )


def adjugate(sys, lam, *, scaled: bool = False) -> AdjugateMatrix:
    """The adjugate ``adj L(lam)`` of the dynamic stiffness, also where L(lam) is singular.

    .. math::
        \\operatorname{adj} L = \\det U\\,\\det V^H\\, V \\operatorname{diag}\\Bigl(\\prod_{j\\ne i} s_j\\Bigr) U^H,
        \\qquad L(\\lambda) = U \\operatorname{diag}(s) V^H

    (SPEC section 4).  ``L adj L = adj L L = p(lam) I``; at a simple root its
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
        ``log_scale`` (0 unless scaled), ``residual``, ``singular_values``,
        ``rank_one_defect``, ``elapsed``.

    Raises
    ------
    ParameterError
        ``sys`` is not a LinearizedSystem, ``lam`` not a finite scalar.
    ComputationError
        The adjugate over- or underflows double precision (and ``scaled`` is False).
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam = complex_scalar(lam, "lam")
    L = sys.dynamic_stiffness(lam).astype(complex)
    f = _svd_adjugate(L[None])
    scale = float(f.log_scale[0])
    log_det = float(f.log_det[0])
    if not np.isfinite(scale):  # adj is exactly zero (L = 0 with n >= 2, or rank <= n - 2 exactly)
        A = np.zeros_like(L)
        det = 0.0 + 0.0j
        residual = _residual_scaled(L, A, 0.0)
        log_scale = 0.0
    else:
        with np.errstate(invalid="ignore"):
            p_scaled = f.phase[0] * np.exp(log_det - scale) if np.isfinite(log_det) else 0.0
        residual = _residual_scaled(L, f.scaled[0], complex(p_scaled))
        if scaled:
            A, det, log_scale = f.scaled[0], complex(p_scaled), scale
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


def adjugate_samples(sys):
    """``evaluate(z) -> (scaled adjugates, log scales)`` for :func:`fit_on_circles` (chunked)."""
    M, C, K = (np.asarray(a, dtype=complex) for a in (sys.M, sys.C, sys.K))

    def evaluate(z):
        vals = np.empty((len(z), sys.n, sys.n), dtype=complex)
        logs = np.empty(len(z))
        for sl in chunks(len(z), sys.n):
            zz = z[sl, None, None]
            f = _svd_adjugate(zz * zz * M + zz * C + K)
            vals[sl], logs[sl] = f.scaled, f.log_scale
        return vals, logs

    return evaluate


# ---------------------------------------------------------------------------- matrix polynomial


def _horner(coef: np.ndarray, x: complex) -> np.ndarray:
    out = np.zeros(coef.shape[1:], dtype=complex)
    for c in coef[::-1]:
        out = out * x + c
    return out


@dataclass(frozen=True, repr=False)
class AdjugatePolynomial:
    """``adj L(lam) = sum_k A_k (lam - center)^k`` as a matrix polynomial of degree 2n - 2.

    Attributes
    ----------
    coef : (2n - 1, n, n) ndarray
        ``A_k``; real when ``center`` is real.
    coef_error : (2n - 1,) ndarray
        A-posteriori absolute error bound of each ``A_k`` (Frobenius norm).
    center : complex
    radius : (2n - 1,) ndarray
        Circle radius [1/s] each coefficient was taken from.
    evaluations : int
        Adjugates evaluated.
    method : str
    elapsed : float
        Seconds.
    """

    coef: np.ndarray
    coef_error: np.ndarray
    center: complex
    radius: np.ndarray
    evaluations: int
    method: str
    elapsed: float

    @property
    def degree(self) -> int:
        return len(self.coef) - 1

    @property
    def error(self) -> float:
        """Normwise relative error ``||coef_error|| / ||coef||``."""
        total = np.linalg.norm(self.coef)
        return float(np.linalg.norm(self.coef_error) / total) if total > 0 else float("inf")

    def __call__(self, lam) -> np.ndarray:
        """``adj L(lam)`` by Horner's rule in ``lam - center``."""
        lam = complex_scalar(lam, "lam")
        return _horner(self.coef, lam - self.center)

    def deriv(self, m: int = 1) -> AdjugatePolynomial:
        """The m-th derivative ``d^m/dlam^m adj L`` as a matrix polynomial (errors scaled alike)."""
        if not isinstance(m, (int, np.integer)) or m < 0:
            raise ParameterError("m", f"expected a non-negative integer, got {m!r}")
        d = self.degree
        if m > d:
            return AdjugatePolynomial(
                np.zeros((1,) + self.coef.shape[1:], dtype=self.coef.dtype),
                np.zeros(1),
                self.center,
                self.radius[:1],
                self.evaluations,
                self.method + f"; derivative {m}",
                self.elapsed,
            )
        k = np.arange(m, d + 1)
        factor = np.array([math.perm(int(j), int(m)) for j in k], dtype=float)
        return AdjugatePolynomial(
            self.coef[m:] * factor[:, None, None],
            self.coef_error[m:] * factor,
            self.center,
            self.radius[m:],
            self.evaluations,
            self.method + f"; derivative {m}",
            self.elapsed,
        )

    def __repr__(self) -> str:
        n = self.coef.shape[1]
        return f"AdjugatePolynomial(n={n}, degree={self.degree}, center={self.center:.6g}, error={self.error:.2e})"


def _fit_adjugate(sys, center, radii, n_points):
    n = sys.n
    degree = 2 * n - 2
    N = max(8, 2 * (degree + 1)) if n_points is None else int(n_points)
    if N < degree + 2:
        raise ParameterError("n_points", f"expected an integer > degree + 1 = {degree + 1}, got {n_points!r}")
    fit = fit_on_circles(adjugate_samples(sys), degree, center, radii, N)
    coef, err = fit.values("the adjugate")
    return fit, coef, err, N


def adjugate_polynomial(sys, *, radii=None, n_points: int | None = None) -> AdjugatePolynomial:
    """The coefficient matrices ``A_0, ..., A_{2n-2}`` of ``adj L(lam) = sum_k A_k lam^k``.

    ``A_{2n-2} = adj M`` and ``A_0 = adj K``.  Computed like the characteristic
    polynomial (:func:`characteristic_polynomial`): SVD-form adjugates on circles
    ``|lam| = r`` spanning the eigenvalue-modulus bounds, FFT interpolation, each
    coefficient from the circle where its a-posteriori error is smallest.

    Parameters
    ----------
    sys : LinearizedSystem
    radii : sequence of float, optional
        Circle radii [1/s] instead of the automatic ladder.
    n_points : int, optional
        Points per circle; default ``2 (2n - 1)`` (at least 8).

    Raises
    ------
    ParameterError
        Bad arguments.
    ComputationError
        A coefficient over- or underflows double precision.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    if radii is None:
        lo, hi = eigenvalue_bounds(sys)
        r_hi = 2.0 * hi if hi > 0 else 1.0
        r_lo = 0.5 * lo if lo > 0 else r_hi * TAYLOR_SPAN
        radii = ladder(r_lo, r_hi, RADIUS_RATIO)
    else:
        radii = check_radii(radii)
    fit, coef, err, N = _fit_adjugate(sys, 0.0, radii, n_points)
    err = np.maximum(err, np.linalg.norm(coef.imag.reshape(len(coef), -1), axis=1))
    return AdjugatePolynomial(
        coef.real.copy(),
        err,
        0.0j,
        fit.radius,
        fit.evaluations,
        f"SVD-form adjugates on {len(fit.radii)} circle(s) of {N} points, FFT interpolation",
        time.perf_counter() - t0,
    )


# ---------------------------------------------------------------------------- derivatives at a point


@dataclass(frozen=True, repr=False)
class AdjugateTaylor:
    """Taylor coefficients ``adj L(lam) = sum_j T_j (lam - lam0)^j`` at ``lam0``.

    ``T_j = adj L^{(j)}(lam0) / j!``.

    Attributes
    ----------
    lam0 : complex
    coef : (order + 1, n, n) complex ndarray
        ``T_0, ..., T_order``.
    coef_error : (order + 1,) ndarray
        A-posteriori absolute error bounds (Frobenius norm).
    radius : (order + 1,) ndarray
        Radius [1/s] of the circle around lam0 each coefficient came from (0 for
        the coefficients beyond degree 2n - 2, exactly zero).
    evaluations : int
    elapsed : float
    """

    lam0: complex
    coef: np.ndarray
    coef_error: np.ndarray
    radius: np.ndarray
    evaluations: int
    elapsed: float

    def derivative(self, j: int) -> np.ndarray:
        """``d^j/dlam^j adj L`` at ``lam0``: ``j! T_j``."""
        if not isinstance(j, (int, np.integer)) or not 0 <= j < len(self.coef):
            raise ParameterError("j", f"expected an integer in [0, {len(self.coef) - 1}], got {j!r}")
        return math.factorial(int(j)) * self.coef[j]

    @property
    def relative_error(self) -> np.ndarray:
        """``coef_error / ||T_j||`` per coefficient."""
        with np.errstate(divide="ignore", invalid="ignore"):
            norms = np.linalg.norm(self.coef.reshape(len(self.coef), -1), axis=1)
            return np.where(norms > 0, self.coef_error / norms, np.inf)

    def __repr__(self) -> str:
        return (
            f"AdjugateTaylor(lam0={self.lam0:.6g}, order={len(self.coef) - 1}, "
            f"relative_error={np.array2string(self.relative_error, precision=1)})"
        )


def adjugate_taylor(sys, lam0, order: int = 1, *, radii=None, n_points: int | None = None) -> AdjugateTaylor:
    """The adjugate and its lambda-derivatives at ``lam0``: ``T_j = adj L^{(j)}(lam0) / j!``.

    Cauchy's integral formula on circles ``|lam - lam0| = r`` evaluated by the
    FFT (exact for the polynomial adj L of degree 2n - 2 up to rounding); each
    ``T_j`` is taken from the radius where its a-posteriori error is smallest.
    Valid also at an eigenvalue (the adjugate is entire).  Used for Jordan chains
    (paper Sec. 9, Prop. 9.1: ``sum_{j<=i} L^{(j)}/j! adj L^{(i-j)}/(i-j)! =
    p^{(i)}/i! I``).

    Parameters
    ----------
    sys : LinearizedSystem
    lam0 : complex
        Centre [1/s].
    order : int
        Highest derivative wanted (0 ... 2n - 2; higher ones vanish).
    radii : sequence of float, optional
        Radii [1/s] instead of the automatic ladder ``(|lam0| + hi) * 4^-j``.
    n_points : int, optional
        Points per circle (default ``2 (2n - 1)``, at least 8).

    Raises
    ------
    ParameterError
        Bad arguments.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam0 = complex_scalar(lam0, "lam0")
    if not isinstance(order, (int, np.integer)) or order < 0:
        raise ParameterError("order", f"expected a non-negative integer, got {order!r}")
    if radii is None:
        _, hi = eigenvalue_bounds(sys)
        r_hi = abs(lam0) + max(hi, natural_scale(sys))
        radii = ladder(r_hi * TAYLOR_SPAN, r_hi, RADIUS_RATIO)
    else:
        radii = check_radii(radii)
    fit, coef, err, N = _fit_adjugate(sys, lam0, radii, n_points)
    m = int(order) + 1
    shape = coef.shape[1:]
    if m > len(coef):
        coef = np.concatenate([coef, np.zeros((m - len(coef),) + shape, dtype=complex)])
        # beyond degree 2n - 2 the coefficients are exactly zero
        err = np.concatenate([err, np.zeros(m - len(err))])
        rad = np.concatenate([fit.radius, np.zeros(m - len(fit.radius))])
    else:
        rad = fit.radius
    return AdjugateTaylor(lam0, coef[:m], err[:m], rad[:m], fit.evaluations, time.perf_counter() - t0)
