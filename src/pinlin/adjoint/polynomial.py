"""The characteristic polynomial p(lam) = det L(lam) (theory: adjoint, paper Sec. 6).

.. math::  p(\\lambda) = \\det(\\lambda^2 M + \\lambda C + K)
           = \\det M\\,\\lambda^{2n} + \\dots + \\det K
           = \\det M \\prod_{k=1}^{2n} (\\lambda - \\lambda_k)

The coefficients are computed from determinants on circles (LU, log-scaled)
interpolated by the FFT, each coefficient taken from the circle where its
a-posteriori error bound is smallest (see :mod:`pinlin.adjoint._circle`).  The
coefficients of a polynomial of high degree are ill-conditioned functions of the
roots and vice versa: the reported ``coef_error`` says how many digits each
coefficient keeps; the roots of p are no substitute for a structured eigensolver
(:func:`pinlin.modal_analysis`) beyond small n.
"""

from __future__ import annotations

import time

import numpy as np
from numpy.polynomial import Polynomial

from ..errors import ComputationError, ParameterError
from ..linearization.system import check_system
from ..numerics.checks import check_tolerance, complex_points
from ..numerics.floating import EPS
from ..numerics.stacks import chunks
from ..results import Result
from ._circle import RADIUS_RATIO, check_points, eigenvalue_radii, fit_on_circles

__all__ = ["CharacteristicPolynomial", "characteristic_polynomial", "det_samples", "HORNER_ROUNDING"]

#: Rounding of Horner's rule for p(lam): each of the k steps of coefficient k
#: costs at most a multiplication and an addition of a complex number, bounded
#: by this many unit roundoffs (eps) per step.
HORNER_ROUNDING = 4
#: Rounding of the conversion mantissa * exp(log_scale) and to real, in eps per coefficient.
CONVERSION_ROUNDING = 4


class CharacteristicPolynomial(Polynomial, Result):
    """``p(lam) = det L(lam)`` as a :class:`numpy.polynomial.Polynomial`, with its error figures.

    It is a Polynomial in every respect (call it, ``.coef``, ``.roots()``,
    ``.deriv()``, arithmetic); the extra attributes below are set only on the
    object :func:`characteristic_polynomial` returns (derived polynomials carry
    ``None``).  ``to_dict()`` gives the coefficients and the figures; the repr
    is one line (``str(p)`` prints the polynomial).

    Attributes
    ----------
    coef_error : (2n + 1,) ndarray
        A-posteriori absolute error bound of each coefficient (same units as it).
    error : float
        Normwise relative error of the coefficients, ``||coef_error|| / ||coef||``.
    radius : (2n + 1,) ndarray
        Radius [1/s] of the circle each coefficient was taken from.
    evaluations : int
        Determinants evaluated.
    method : str
        How the coefficients were computed.
    elapsed : float
        Seconds.

    Examples
    --------
    det L(lam) as a numpy Polynomial (coefficients in ascending powers); p(0) = det K:

    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> p = pinlin.characteristic_polynomial(sys)
    >>> round(float(np.real(p(0.0))), 6)
    3.0
    """

    _meta = ("coef_error", "error", "radius", "evaluations", "method", "elapsed")
    _dict_fields = ("coef", "coef_error", "radius", "evaluations")

    def __init__(self, coef, domain=None, window=None, symbol="x"):
        super().__init__(coef, domain, window, symbol)
        for key in self._meta:
            setattr(self, key, None)

    @classmethod
    def _from_values(cls, values: dict) -> CharacteristicPolynomial:
        out = cls(values["coef"])
        for key in cls._meta:
            setattr(out, key, values.get(key))
        return out

    def __repr__(self) -> str:
        if self.error is None:
            return f"CharacteristicPolynomial(degree={self.degree()}, derived: no error figures)"
        return (
            f"CharacteristicPolynomial(degree={self.degree()}, error={self.error:.2e}, "
            f"evaluations={self.evaluations}, elapsed={self.elapsed * 1e3:.3g} ms)"
        )

    @property
    def relative_coef_error(self) -> np.ndarray:
        """``coef_error / |coef|`` per coefficient (``inf`` where a coefficient is zero).

        Raises
        ------
        AttributeError
            This polynomial was derived from a computed one and has no error figures.
        """
        if self.coef_error is None:
            raise AttributeError("this polynomial was derived from a computed one and carries no error figures")
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.coef != 0, self.coef_error / np.abs(self.coef), np.inf)

    def error_at(self, lam) -> np.ndarray | float:
        """Error bound of ``p(lam)`` evaluated from these coefficients.

        .. math::  \\sum_k (\\epsilon_k + 4 k\\,u\\,|c_k|)\\,|\\lambda|^k

        with the coefficient errors ``epsilon_k`` and the rounding of Horner's
        rule (``u`` the unit roundoff; the 4 is :data:`HORNER_ROUNDING`).

        Raises
        ------
        AttributeError
            This polynomial was derived from a computed one and has no error figures.
        ParameterError
            ``lam`` is not finite complex points.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> p = pinlin.characteristic_polynomial(sys)
        >>> bool(p.error_at(1.0) < 1e-12), p.error_at([1.0, 2j]).shape
        (True, (2,))
        """
        if self.coef_error is None:
            raise AttributeError("this polynomial was derived from a computed one and carries no error figures")
        z, scalar = complex_points(lam, "lam")
        k = np.arange(len(self.coef))
        weights = self.coef_error + HORNER_ROUNDING * k * EPS * np.abs(self.coef)
        out = np.abs(z)[:, None] ** k @ weights
        return float(out[0]) if scalar else out


def det_samples(sys):
    """``evaluate(z) -> (sign, log|det L(z)|)`` for :func:`fit_on_circles` (LU, chunked)."""
    M, C, K = (np.asarray(a, dtype=complex) for a in (sys.M, sys.C, sys.K))

    def evaluate(z):
        sign = np.empty(len(z), dtype=complex)
        logdet = np.empty(len(z))
        for sl in chunks(len(z), sys.n):
            zz = z[sl, None, None]
            sign[sl], logdet[sl] = np.linalg.slogdet(zz * zz * M + zz * C + K)
        return sign, logdet

    return evaluate


def characteristic_polynomial(
    sys,
    *,
    radii=None,
    n_points: int | None = None,
    radius_ratio: float = RADIUS_RATIO,
) -> CharacteristicPolynomial:
    """The characteristic polynomial ``p(lam) = det(lam^2 M + lam C + K)``, degree 2n.

    Determinants are evaluated (LU with partial pivoting, log-scaled) at ``N``
    points of circles ``|lam| = r`` and interpolated by the FFT; ``N - 2n - 1``
    extra points per circle measure the rounding noise ``eps_r``, and coefficient
    k is taken from the circle minimizing its error bound ``eps_r / r^k``.  The
    radii span the bounds ``lo/2 ... 2 hi`` on the eigenvalue moduli, with
    ``|lam|^2 <= ||M^-1 C|| |lam| + ||M^-1 K||`` and the same for ``1/lam`` with
    ``K^-1`` (theory: adjoint).  Leading coefficient ``det M``, constant term
    ``det K``.

    Parameters
    ----------
    sys : LinearizedSystem
    radii : sequence of float, optional
        Circle radii [1/s] to use instead of the automatic ladder.
    n_points : int, optional
        Points per circle; default ``2 (2n + 1)``.
    radius_ratio : float
        Ratio (> 1) of successive radii of the automatic ladder (default 4).

    Returns
    -------
    CharacteristicPolynomial
        A :class:`numpy.polynomial.Polynomial` in lam [1/s] with ``coef_error``,
        ``error``, ``elapsed`` and the other fields of the class.

    Raises
    ------
    ParameterError
        ``sys`` is not a LinearizedSystem; bad radii or point count.
    ComputationError
        A coefficient over- or underflows double precision (large n in
        unsuitable units: ``det M`` of a 100-link chain is about 1e-620).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> p = pinlin.characteristic_polynomial(sys)
    >>> p.degree(), np.round(p.coef, 6)
    (4, array([3.  , 0.4 , 4.01, 0.2 , 1.  ]))
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    n = sys.n
    ratio = check_tolerance(radius_ratio, "radius_ratio")
    if ratio <= 1:
        raise ParameterError("radius_ratio", f"must be > 1, got {radius_ratio}")
    radii = eigenvalue_radii(sys, radii, ratio)
    N = check_points(n_points, 2 * n)
    fit = fit_on_circles(det_samples(sys), 2 * n, 0.0, radii, N)
    coef_c, err = fit.values("the characteristic polynomial")
    # p has real coefficients: an imaginary part is rounding noise of the same size as err
    err = np.maximum(err, np.abs(coef_c.imag))
    coef = coef_c.real
    err = err + CONVERSION_ROUNDING * EPS * np.abs(coef)  # the conversions mantissa * exp(log) and to real
    p = CharacteristicPolynomial(coef)
    p.coef_error = err
    p.error = float(np.linalg.norm(err) / np.linalg.norm(coef)) if np.any(coef) else float("inf")
    p.radius = fit.radius
    p.evaluations = fit.evaluations
    p.method = (
        f"det L by LU on {len(fit.radii)} circle(s) of {N} points, FFT interpolation, "
        f"each coefficient from its most accurate circle"
    )
    p.elapsed = time.perf_counter() - t0
    if not np.all(np.isfinite(coef)):
        raise ComputationError("the characteristic polynomial has non-finite coefficients")
    return p
