"""The characteristic differential equation p(d/dt) x_i = 0 (theory: adjoint, paper Sec. 7).

Applying the adjoint operator ``adj L(d/dt)`` to ``L(d/dt) x = 0`` gives, since
``adj L(lam) L(lam) = p(lam) I``,

.. math::  p\\Bigl(\\frac{d}{dt}\\Bigr) x_i = \\sum_{k=0}^{2n} c_k\\, x_i^{(k)} = 0
           \\qquad (i = 1, \\dots, n)

for every component of every free solution: each ``x_i`` is an exponential
polynomial ``sum_k sum_{j < m_k} a_{kj} t^j exp(lam_k t)`` over the roots lam_k of
p with multiplicities m_k (paper Theorem 7.1).

Two checks are offered: :meth:`CharacteristicDifferentialEquation.defect` for
a trajectory whose derivatives up to order 2n are known, and
:func:`check_free_response` for a sampled trajectory, which measures the
distance of each component to the span of those exponential polynomials.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..errors.deprecated import renamed_keywords
from ..linearization.system import check_system
from ..numerics.checks import check_tolerance
from ..numerics.clustering import find_clusters
from ..results import Result
from .polynomial import CharacteristicPolynomial, characteristic_polynomial

__all__ = [
    "CharacteristicDifferentialEquation",
    "characteristic_differential_equation",
    "CDECheck",
    "check_free_response",
    "expol_basis",
]

#: Default: a sampled component satisfies the equation when its relative defect is below
#: this: a least-squares fit of exact samples leaves rounding of about kappa(basis) eps,
#: which stays far below 1e-8 for well-separated roots over a few periods.
CDE_TOL = 1e-8
#: Default: roots closer than this (relative to max(|lam_i|, |lam_j|)) are one multiple
#: root; the roots of p split a double root by about sqrt(eps) ~ 1e-8 times its
#: condition, and 1e-6 regroups them without merging distinct roots of a few digits.
ROOT_CLUSTER_TOL = 1e-6


@dataclass(frozen=True, repr=False)
class CharacteristicDifferentialEquation(Result):
    """The scalar operator ``p(d/dt) = sum_k c_k d^k/dt^k`` of order 2n.

    Attributes
    ----------
    polynomial : CharacteristicPolynomial
        ``p``, with its coefficient errors.
    error : float
        The normwise relative error of the coefficients (``polynomial.error``).
    method : str
        How the coefficients were computed (``polynomial.method``).
    elapsed : float
        Seconds to compute them [s] (``polynomial.elapsed``).
    """

    polynomial: CharacteristicPolynomial

    @property
    def error(self) -> float:
        return self.polynomial.error

    @property
    def method(self) -> str:
        return f"coefficients of p(lam) = det L(lam): {self.polynomial.method}"

    @property
    def elapsed(self) -> float:
        return self.polynomial.elapsed

    @property
    def order(self) -> int:
        return len(self.polynomial.coef) - 1

    @property
    def coefficients(self) -> np.ndarray:
        """``c_0 ... c_2n`` (``c_k`` multiplies the k-th derivative)."""
        return self.polynomial.coef.copy()

    def _check(self, derivatives) -> np.ndarray:
        d = np.asarray(derivatives)
        if d.dtype == object or not np.issubdtype(d.dtype, np.number):
            raise ParameterError("derivatives", f"expected numbers, got dtype {d.dtype}")
        if d.ndim == 0 or d.shape[0] != self.order + 1:
            raise ParameterError(
                "derivatives",
                f"expected the derivatives of orders 0 ... {self.order} along the first axis "
                f"(shape ({self.order + 1}, ...)), got shape {d.shape}",
            )
        if not np.all(np.isfinite(d)):
            raise ParameterError("derivatives", "must be finite")
        return d

    def apply(self, derivatives) -> np.ndarray:
        """``p(d/dt) x = sum_k c_k x^(k)`` from ``derivatives[k] = d^k x / dt^k`` (any trailing shape).

        Raises
        ------
        ParameterError
            ``derivatives`` not finite numbers of shape (2n + 1, ...).
        """
        d = self._check(derivatives)
        return np.tensordot(self.polynomial.coef, d, axes=(0, 0))

    def defect(self, derivatives) -> np.ndarray:
        """Relative defect ``|sum_k c_k x^(k)| / sum_k |c_k| |x^(k)|`` elementwise (0 where x is 0).

        Raises
        ------
        ParameterError
            ``derivatives`` not finite numbers of shape (2n + 1, ...).
        """
        d = self._check(derivatives)
        num = np.abs(np.tensordot(self.polynomial.coef, d, axes=(0, 0)))
        den = np.tensordot(np.abs(self.polynomial.coef), np.abs(d), axes=(0, 0))
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(den > 0, num / den, 0.0)

    def __repr__(self) -> str:
        return f"CharacteristicDifferentialEquation(order={self.order}, coefficient error={self.polynomial.error:.1e})"


def characteristic_differential_equation(sys, **kwargs) -> CharacteristicDifferentialEquation:
    """The characteristic differential equation ``p(d/dt) x_i = 0`` of ``sys`` (paper Sec. 7).

    Parameters
    ----------
    sys : LinearizedSystem
    **kwargs
        Passed to :func:`characteristic_polynomial`.

    Raises
    ------
    ParameterError, ComputationError
        As :func:`characteristic_polynomial`.
    """
    return CharacteristicDifferentialEquation(characteristic_polynomial(check_system(sys), **kwargs))


def _group_roots(roots: np.ndarray, tol: float) -> list[tuple[complex, int]]:
    """Roots that rounding cannot tell apart (:func:`pinlin.numerics.find_clusters`) as (mean, multiplicity)."""
    return [(complex(np.mean(roots[list(g)])), len(g)) for g in find_clusters(roots, tol, singletons=True)]


def expol_basis(t: np.ndarray, roots, *, cluster_tol: float = ROOT_CLUSTER_TOL) -> np.ndarray:
    """Columns ``(t - t0)^j exp(lam (t - t0))``, j < multiplicity, for the grouped roots (Theorem 7.1).

    Each column is scaled to unit 2-norm (its size says nothing about the fit).
    """
    t = np.asarray(t, dtype=float)
    tau = t - t[0]
    cols = []
    for lam, m in _group_roots(np.asarray(roots, dtype=complex), cluster_tol):
        e = np.exp(lam * tau)
        for j in range(m):
            c = tau**j * e
            nrm = np.linalg.norm(c)
            if nrm > 0 and np.isfinite(nrm):
                cols.append(c / nrm)
    return np.column_stack(cols) if cols else np.zeros((t.size, 0), dtype=complex)


@dataclass(frozen=True, repr=False, kw_only=True)
class CDECheck(Result):
    """How well a sampled trajectory satisfies ``p(d/dt) x_i = 0``.

    Attributes
    ----------
    defect : (n,) ndarray
        Per component, ``||x_i - P x_i|| / ||x_i||`` with P the least-squares
        projection onto the exponential polynomials of the roots of p (0 for a
        component that is identically zero).
    max_defect : float
    tol : float
    passed : bool
        ``max_defect <= tol``.
    roots : (2n,) complex ndarray
        The roots used.
    roots_source : str
    multiplicities : tuple of int
        Multiplicity of each distinct root used.
    elapsed : float
        Seconds [s].
    error : float
        The largest relative defect (``max_defect``).
    method : str
        The projection and where the roots came from.
    """

    defect: np.ndarray
    max_defect: float
    tol: float
    passed: bool
    roots: np.ndarray
    roots_source: str
    multiplicities: tuple[int, ...]
    elapsed: float

    @property
    def error(self) -> float:
        return self.max_defect

    @property
    def method(self) -> str:
        return f"least-squares distance to the exponential polynomials of the roots ({self.roots_source})"

    def __repr__(self) -> str:
        return f"CDECheck(passed={self.passed}, max_defect={self.max_defect:.2e}, tol={self.tol:g})"


@renamed_keywords(tol="defect_tol")
def check_free_response(
    sys,
    t,
    x,
    *,
    roots=None,
    defect_tol: float = CDE_TOL,
    cluster_tol: float = ROOT_CLUSTER_TOL,
) -> CDECheck:
    """Check that a sampled trajectory satisfies the characteristic differential equation.

    Every component of a free solution lies in the span of
    ``t^j exp(lam_k t)`` (j < m_k) over the roots lam_k of p (paper Theorem 7.1);
    each sampled component ``x[:, i]`` is projected on that span by least squares
    and its relative distance to it is the defect.  A forced response, or a
    free response of another system, leaves a large defect.

    Parameters
    ----------
    sys : LinearizedSystem
    t : (T,) array
        Sample times [s], strictly increasing, T > 2n (at least 2n + 1 samples
        so that the span does not fit everything).
    x : (T, n) array
        Sampled trajectory (real or complex).
    roots : (2n,) array, optional
        Roots of p to use, for example ``pinlin.modal_analysis(sys).eigenvalues``
        (accurate for any n).  Default: the roots of
        :func:`characteristic_polynomial` (``numpy.polynomial`` companion
        matrix), adequate for small n only; ``roots_source`` records which.
    defect_tol : float
        Largest relative defect accepted (default 1e-8; ``tol`` is its deprecated spelling).
    cluster_tol : float
        Roots within this relative distance are one multiple root (basis
        ``t^j exp(lam t)``).

    Returns
    -------
    CDECheck

    Raises
    ------
    ParameterError
        Wrong shapes, non-finite values, times not increasing, too few samples,
        wrong number of roots.

    Examples
    --------
    x(t) = cos t is a free motion of x'' + x = 0:

    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.0]], [[1.0]])
    >>> t = np.linspace(0.0, 10.0, 101)
    >>> check = pinlin.check_free_response(sys, t, np.cos(t)[:, None])
    >>> check.passed, bool(check.max_defect < 1e-12)
    (True, True)
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    check_tolerance(defect_tol, "defect_tol")
    check_tolerance(cluster_tol, "cluster_tol")
    n = sys.n
    try:
        tt = np.asarray(t, dtype=float)
        xx = np.asarray(x)
    except (TypeError, ValueError):
        raise ParameterError("t, x", "expected numeric arrays") from None
    if xx.dtype.kind not in "biufc":
        raise ParameterError("x", f"expected numbers, got an array of {xx.dtype}")
    if tt.ndim != 1:
        raise ParameterError("t", f"expected a 1-D array of times, got shape {tt.shape}")
    if xx.ndim != 2 or xx.shape != (tt.size, n):
        raise ParameterError("x", f"expected shape {(tt.size, n)} (samples, coordinates), got {xx.shape}")
    if not (np.all(np.isfinite(tt)) and np.all(np.isfinite(xx))):
        raise ParameterError("t, x", "must be finite")
    if tt.size <= 2 * n:
        raise ParameterError("t", f"need more than 2n = {2 * n} samples to test an equation of order 2n, got {tt.size}")
    if np.any(np.diff(tt) <= 0):
        raise ParameterError("t", "times must be strictly increasing")
    if roots is None:
        lam = np.asarray(characteristic_polynomial(sys).roots(), dtype=complex)
        source = "roots of the characteristic polynomial (companion matrix of p)"
    else:
        lam = np.asarray(roots, dtype=complex).ravel()
        if lam.size != 2 * n or not np.all(np.isfinite(lam)):
            raise ParameterError("roots", f"expected {2 * n} finite roots, got {lam.size}")
        source = "given"
    B = expol_basis(tt, lam, cluster_tol=cluster_tol)
    groups = _group_roots(lam, cluster_tol)
    coef, *_ = np.linalg.lstsq(B, xx.astype(complex), rcond=None)
    resid = xx - B @ coef
    nx = np.linalg.norm(xx, axis=0)
    nr = np.linalg.norm(resid, axis=0)
    defect = np.where(nx > 0, nr / np.where(nx > 0, nx, 1.0), 0.0)
    worst = float(np.max(defect))
    return CDECheck(
        defect=defect,
        max_defect=worst,
        tol=float(defect_tol),
        passed=bool(worst <= defect_tol),
        roots=lam,
        roots_source=source,
        multiplicities=tuple(m for _, m in groups),
        elapsed=time.perf_counter() - t0,
    )
