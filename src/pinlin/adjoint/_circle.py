"""Polynomial coefficients from samples on circles, by the FFT (theory: adjoint).

A polynomial ``P(z) = sum_k c_k (z - z0)^k`` of known degree d, scalar or
matrix-valued, is sampled at ``N > d + 1`` equally spaced points
``z_l = z0 + r exp(2 pi i l / N)`` of a circle.  The discrete Fourier transform
of the samples gives ``c_k r^k`` for ``k <= d`` exactly in exact arithmetic, and
zero for ``d < k < N``: those "tail" coefficients are pure rounding noise and
measure the absolute error ``eps_r`` of every coefficient on that circle.  The
error of ``c_k`` taken from radius r is then ``eps_r / r^k``.  Several radii are
tried and each coefficient is taken from the circle where its error bound is
smallest (small circles for the low-order coefficients, large ones for the
high-order ones), which keeps the relative accuracy of coefficients that differ
by many orders of magnitude.

Samples are carried as ``value * exp(log_scale)`` so that determinants and
adjugates of large systems never overflow before the final, checked conversion.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError
from ..numerics.checks import check_integer, check_radii
from ..numerics.floating import EPS, checked_exp
from ..numerics.scaling import eigenvalue_bounds
from ..numerics.stacks import CHUNK_BYTES, chunks

__all__ = [
    "CircleFit",
    "fit_on_circles",
    "ladder",
    "eigenvalue_radii",
    "default_points",
    "check_points",
    "chunks",
    "CHUNK_BYTES",
    "RADIUS_RATIO",
    "RADIUS_MARGIN",
    "SINGULAR_SPAN",
    "MIN_POINTS",
    "POINTS_PER_COEFFICIENT",
    "NOISE_SAFETY",
    "MAX_RADII",
]

#: Default ratio between successive radii of the sampling circles: each
#: coefficient's error bound eps_r / r^k varies by 4^k between neighbours, so
#: the best circle for every coefficient is within a factor 4^k of optimal.
RADIUS_RATIO = 4.0
#: The circles reach this factor beyond the bounds on the eigenvalue moduli
#: (out to 2 hi, in to lo / 2): no eigenvalue lies close to the extreme circles.
RADIUS_MARGIN = 2.0
#: Without a positive lower bound on |lam| (K singular: zero roots) the smallest
#: circle is this fraction of the largest: about sqrt(eps), where the low-order
#: coefficients are resolved without the rounding of the large circles.
SINGULAR_SPAN = 1e-8
#: Fewest samples per circle (the FFT needs some tail to measure the noise).
MIN_POINTS = 8
#: Default samples per coefficient: half of them measure the rounding noise.
POINTS_PER_COEFFICIENT = 2
#: Factor on the largest tail coefficient for the unobserved noise of the kept ones.
NOISE_SAFETY = 3.0
#: Most circles of a ladder (4^40 ~ 1e24 of span is more than double precision resolves).
MAX_RADII = 40


@dataclass(frozen=True)
class CircleFit:
    """Coefficients ``c_k = mantissa[k] * exp(log_scale[k])`` of ``sum_k c_k (z - center)^k``.

    Attributes
    ----------
    mantissa : (d + 1, ...) complex ndarray
    log_scale : (d + 1,) ndarray
    error_mantissa : (d + 1,) ndarray
        Absolute error bound of coefficient k is ``error_mantissa[k] * exp(log_scale[k])``
        (Frobenius norm for matrix coefficients).
    radius : (d + 1,) ndarray
        The radius each coefficient was taken from.
    radii : ndarray
        All radii tried.
    n_points : int
        Samples per circle.
    """

    mantissa: np.ndarray
    log_scale: np.ndarray
    error_mantissa: np.ndarray
    radius: np.ndarray
    radii: np.ndarray
    n_points: int

    @property
    def evaluations(self) -> int:
        return self.n_points * len(self.radii)

    def values(self, what: str) -> tuple[np.ndarray, np.ndarray]:
        """The coefficients and their error bounds as plain numbers, checked for range.

        Raises ComputationError when a coefficient that is not rounding noise
        over- or underflows double precision (it would become inf or a silent 0).
        """
        norms = np.linalg.norm(self.mantissa.reshape(len(self.mantissa), -1), axis=1)
        with np.errstate(divide="ignore"):
            log_size = self.log_scale + np.log(norms)
        significant = norms > self.error_mantissa
        with np.errstate(divide="ignore"):
            log_err = self.log_scale + np.log(self.error_mantissa)
        # overflow of anything (a value or its error bound) is an error; underflow only of a
        # coefficient that is not rounding noise (noise may flush to zero, its bound says so)
        checked_exp(np.maximum(log_size, log_err), f"a coefficient of {what}")
        checked_exp(np.where(significant, log_size, np.nan), f"a coefficient of {what}", each=True)
        # exp(log_scale) may exceed the double range where mantissa * exp(log_scale) does not
        half = np.exp(0.5 * self.log_scale)
        shape = (-1,) + (1,) * (self.mantissa.ndim - 1)
        values = self.mantissa * half.reshape(shape) * half.reshape(shape)
        return values, self.error_mantissa * half * half


def default_points(degree: int) -> int:
    """Samples per circle for a polynomial of this degree: max(MIN_POINTS, 2 (degree + 1))."""
    return max(MIN_POINTS, POINTS_PER_COEFFICIENT * (degree + 1))


def check_points(n_points, degree: int) -> int:
    """``n_points`` (default :func:`default_points`) checked to exceed degree + 1.

    Raises
    ------
    ParameterError
        Not an integer > degree + 1.
    """
    if n_points is None:
        return default_points(degree)
    return check_integer(n_points, "n_points", low=degree + 2)


def eigenvalue_radii(sys, radii=None, ratio: float = RADIUS_RATIO) -> np.ndarray:
    """Circle radii [1/s]: the given ones checked, or a ladder spanning the eigenvalue moduli.

    The automatic ladder runs from RADIUS_MARGIN hi down to lo / RADIUS_MARGIN
    (:func:`pinlin.numerics.eigenvalue_bounds`), or down to SINGULAR_SPAN times
    the largest radius when there is no positive lower bound.

    Raises
    ------
    ParameterError
        Given radii that are not finite positive numbers.
    """
    if radii is not None:
        return check_radii(radii)
    lo, hi = eigenvalue_bounds(sys)
    r_hi = RADIUS_MARGIN * hi if hi > 0 else 1.0
    r_lo = lo / RADIUS_MARGIN if lo > 0 else r_hi * SINGULAR_SPAN
    return ladder(r_lo, r_hi, ratio)


def fit_on_circles(
    evaluate: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    degree: int,
    center: complex,
    radii,
    n_points: int | None = None,
) -> CircleFit:
    """Fit ``sum_{k<=degree} c_k (z - center)^k`` to samples on circles of the given radii.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(z) -> (values, log_scale)`` with ``values`` of shape
        ``(len(z), ...)`` and the true samples ``values * exp(log_scale[:, None...])``.
    degree : int
        Degree d of the polynomial (an upper bound is fine; more points are used).
    center : complex
    radii : sequence of float
        Positive radii.
    n_points : int, optional
        Samples per circle; default :func:`default_points` so that ``N - d - 1``
        tail coefficients estimate the rounding noise.

    Raises
    ------
    ParameterError
        Fewer than degree + 2 points per circle.
    ComputationError
        Every sample on every circle was zero.
    """
    d = int(degree)
    N = check_points(n_points, d)
    radii = np.asarray(sorted(float(r) for r in radii), dtype=float)
    roots_of_unity = np.exp(2j * np.pi * np.arange(N) / N)
    best_mant = best_log = best_err = best_r = None
    k = np.arange(d + 1)
    for r in radii:
        z = center + r * roots_of_unity
        values, logs = evaluate(z)
        values = np.asarray(values, dtype=complex)
        logs = np.asarray(logs, dtype=float)
        shape = values.shape[1:]
        mags = np.linalg.norm(values.reshape(N, -1), axis=1)
        with np.errstate(divide="ignore"):
            logmag = logs + np.log(mags)
        finite = np.isfinite(logmag)
        if not np.any(finite):
            continue
        F = float(np.max(logmag[finite]))
        with np.errstate(invalid="ignore"):
            factor = np.where(np.isfinite(logs), np.exp(logs - F), 0.0)
        factor = factor.reshape((N,) + (1,) * len(shape))
        v = values * factor
        a = np.fft.fft(v, axis=0) / N
        tail = np.linalg.norm(a[d + 1 :].reshape(N - d - 1, -1), axis=1)
        # the largest of the tail's noise samples, with a safety factor for the kept
        # coefficients' own (unobserved) noise, plus the FFT's rounding
        noise = NOISE_SAFETY * float(tail.max()) + EPS * np.log2(N) * float(np.max(np.linalg.norm(v.reshape(N, -1), axis=1)))
        log_r = np.log(r)
        log_scale = F - k * log_r
        # error bound of c_k from this circle, in logs: log(noise) + F - k log r
        log_err = np.log(noise) + log_scale if noise > 0 else np.full(d + 1, -np.inf)
        mant = a[: d + 1]
        if best_mant is None:
            best_mant, best_log, best_err, best_r = mant.copy(), log_scale, log_err, np.full(d + 1, r)
            best_noise = np.full(d + 1, noise)
            continue
        better = log_err < best_err
        best_mant[better] = mant[better]
        best_log = np.where(better, log_scale, best_log)
        best_err = np.where(better, log_err, best_err)
        best_r = np.where(better, r, best_r)
        best_noise = np.where(better, noise, best_noise)
    if best_mant is None:
        raise ComputationError("every sample on every circle was zero: nothing to interpolate")
    return CircleFit(
        mantissa=best_mant,
        log_scale=best_log,
        error_mantissa=best_noise,
        radius=best_r,
        radii=radii,
        n_points=N,
    )


def ladder(lo: float, hi: float, ratio: float = RADIUS_RATIO, max_radii: int = MAX_RADII) -> np.ndarray:
    """Radii ``hi, hi/ratio, ...`` down to ``lo`` (at most ``max_radii``; at least one)."""
    hi = float(hi)
    out = [hi]
    while out[-1] / ratio >= lo and len(out) < max_radii:
        out.append(out[-1] / ratio)
    return np.asarray(out)
