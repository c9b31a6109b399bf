"""The adjugate as a matrix polynomial and its Taylor coefficients at a point (theory: adjoint, paper Sec. 7-9).

.. math::
    \\operatorname{adj} L(\\lambda) = \\sum_{k=0}^{2n-2} A_k \\lambda^k
    = \\sum_{j} T_j (\\lambda - \\lambda_0)^j,\\qquad
    T_j = \\frac{1}{j!}\\frac{d^j}{d\\lambda^j}\\operatorname{adj} L(\\lambda_0)

Both come from SVD-form adjugates (:mod:`pinlin.adjoint.svd`) sampled on
circles and interpolated by the FFT (:mod:`pinlin.adjoint._circle`), each
coefficient from the circle where its a-posteriori error bound is smallest.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..linearization.system import check_system
from ..numerics.checks import check_integer, check_radii, complex_scalar
from ..numerics.scaling import eigenvalue_bounds, natural_scale
from ..results import Result
from ._circle import RADIUS_RATIO, check_points, chunks, eigenvalue_radii, fit_on_circles, ladder
from .svd import svd_adjugate

__all__ = [
    "AdjugatePolynomial",
    "adjugate_polynomial",
    "AdjugateTaylor",
    "adjugate_taylor",
    "adjugate_samples",
    "TAYLOR_SPAN",
]

#: Span (smallest / largest radius) of the circles around a Taylor centre: down
#: to about sqrt(eps) of the largest, where the low-order coefficients are
#: resolved without the rounding of the large circles.
TAYLOR_SPAN = 1e-8


def adjugate_samples(sys):
    """``evaluate(z) -> (scaled adjugates, log scales)`` for :func:`fit_on_circles` (chunked)."""
    M, C, K = (np.asarray(a, dtype=complex) for a in (sys.M, sys.C, sys.K))

    def evaluate(z):
        vals = np.empty((len(z), sys.n, sys.n), dtype=complex)
        logs = np.empty(len(z))
        for sl in chunks(len(z), sys.n):
            zz = z[sl, None, None]
            f = svd_adjugate(zz * zz * M + zz * C + K)
            vals[sl], logs[sl] = f.scaled, f.log_scale
        return vals, logs

    return evaluate


def _horner(coef: np.ndarray, x: complex) -> np.ndarray:
    out = np.zeros(coef.shape[1:], dtype=complex)
    for c in coef[::-1]:
        out = out * x + c
    return out


def _relative(coef: np.ndarray, coef_error: np.ndarray) -> float:
    total = np.linalg.norm(coef)
    return float(np.linalg.norm(coef_error) / total) if total > 0 else float("inf")


@dataclass(frozen=True, repr=False, kw_only=True)
class AdjugatePolynomial(Result):
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
        Seconds [s].
    error : float
        Normwise relative error of the coefficients, ``||coef_error|| / ||coef||``.
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
        return _relative(self.coef, self.coef_error)

    def __call__(self, lam) -> np.ndarray:
        """``adj L(lam)`` by Horner's rule in ``lam - center``.

        Raises
        ------
        ParameterError
            ``lam`` is not a finite scalar.
        """
        lam = complex_scalar(lam, "lam")
        return _horner(self.coef, lam - self.center)

    def deriv(self, m: int = 1) -> AdjugatePolynomial:
        """The m-th derivative ``d^m/dlam^m adj L`` as a matrix polynomial (errors scaled alike).

        Raises
        ------
        ParameterError
            ``m`` is not a non-negative integer.
        """
        m = check_integer(m, "m", low=0)
        d = self.degree
        method = self.method + f"; derivative {m}"
        if m > d:
            zero = np.zeros((1,) + self.coef.shape[1:], dtype=self.coef.dtype)
            return AdjugatePolynomial(
                coef=zero, coef_error=np.zeros(1), center=self.center, radius=self.radius[:1],
                evaluations=self.evaluations, method=method, elapsed=self.elapsed,
            )
        factor = np.array([math.perm(int(j), m) for j in range(m, d + 1)], dtype=float)
        return AdjugatePolynomial(
            coef=self.coef[m:] * factor[:, None, None], coef_error=self.coef_error[m:] * factor,
            center=self.center, radius=self.radius[m:], evaluations=self.evaluations, method=method,
            elapsed=self.elapsed,
        )

    def __repr__(self) -> str:
        n = self.coef.shape[1]
        return f"AdjugatePolynomial(n={n}, degree={self.degree}, center={self.center:.6g}, error={self.error:.2e})"


def _fit_adjugate(sys, center, radii, n_points):
    degree = 2 * sys.n - 2
    N = check_points(n_points, degree)
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
    radii = eigenvalue_radii(sys, radii)
    fit, coef, err, N = _fit_adjugate(sys, 0.0, radii, n_points)
    err = np.maximum(err, np.linalg.norm(coef.imag.reshape(len(coef), -1), axis=1))
    return AdjugatePolynomial(
        coef=coef.real.copy(), coef_error=err, center=0.0j, radius=fit.radius, evaluations=fit.evaluations,
        method=f"SVD-form adjugates on {len(fit.radii)} circle(s) of {N} points, FFT interpolation",
        elapsed=time.perf_counter() - t0,
    )


@dataclass(frozen=True, repr=False, kw_only=True)
class AdjugateTaylor(Result):
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
        Seconds [s].
    method : str
    error : float
        Normwise relative error of the coefficients, ``||coef_error|| / ||coef||``
        (per coefficient: ``relative_error``).
    """

    lam0: complex
    coef: np.ndarray
    coef_error: np.ndarray
    radius: np.ndarray
    evaluations: int
    elapsed: float
    method: str = "Cauchy integrals of SVD-form adjugates on circles around lam0, FFT"

    @property
    def error(self) -> float:
        return _relative(self.coef, self.coef_error)

    def derivative(self, j: int) -> np.ndarray:
        """``d^j/dlam^j adj L`` at ``lam0``: ``j! T_j``.

        Raises
        ------
        ParameterError
            ``j`` is not an integer in [0, order].
        """
        j = check_integer(j, "j", low=0, high=len(self.coef) - 1)
        return math.factorial(j) * self.coef[j]

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
        Radii [1/s] instead of the automatic ladder from ``|lam0| + max(hi, natural
        scale)`` down by :data:`TAYLOR_SPAN`.
    n_points : int, optional
        Points per circle (default ``2 (2n - 1)``, at least 8).

    Raises
    ------
    ParameterError
        Bad arguments.
    ComputationError
        A coefficient over- or underflows double precision.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam0 = complex_scalar(lam0, "lam0")
    order = check_integer(order, "order", low=0)
    if radii is None:
        _, hi = eigenvalue_bounds(sys)
        r_hi = abs(lam0) + max(hi, natural_scale(sys))
        radii = ladder(r_hi * TAYLOR_SPAN, r_hi, RADIUS_RATIO)
    else:
        radii = check_radii(radii)
    fit, coef, err, N = _fit_adjugate(sys, lam0, radii, n_points)
    m = order + 1
    rad = fit.radius
    if m > len(coef):  # beyond degree 2n - 2 the coefficients are exactly zero
        extra = m - len(coef)
        coef = np.concatenate([coef, np.zeros((extra,) + coef.shape[1:], dtype=complex)])
        err = np.concatenate([err, np.zeros(extra)])
        rad = np.concatenate([rad, np.zeros(extra)])
    return AdjugateTaylor(
        lam0=lam0, coef=coef[:m], coef_error=err[:m], radius=rad[:m], evaluations=fit.evaluations,
        elapsed=time.perf_counter() - t0,
    )
