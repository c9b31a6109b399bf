"""Derivatives dM/dp, dC/dp, dK/dp of a parameter family of systems (theory: boundaries).

``func(p)`` is a black box to pinlin, and Pinocchio computes in real arithmetic
(no complex step), so the derivatives come from one of

- the user: ``derivative(p) -> (dM, dC, dK)``, exact (for a parameter that
  enters polynomially: an element's stiffness or damping, a wrench magnitude,
  a prescribed speed, gravity -- with the equilibrium's own shift included, see
  below);
- central differences with Richardson extrapolation (Ridders' tableau): steps
  h, h/2, h/4, ... give D(h) = (X(p+h) - X(p-h)) / (2h) = X' + c2 h^2 + c4 h^4 + ...;
  extrapolation removes the powers of h one by one, and the difference between
  neighbouring entries of the tableau estimates the error.  Rounding,
  eps ||X|| / h, is added to the estimate.  A matrix that is a polynomial of
  degree <= 2 in p is differentiated exactly (up to rounding) by the first step;
- secants between two evaluated systems (inside the boundary searches, where
  they cost no call of ``func``; exact when the matrices are affine in p).

**The equilibrium's shift.** When p moves the equilibrium q(p) (a load, a
stiffness under gravity), the matrices depend on p directly and through q:
dX/dp = partial X / partial p + (partial X / partial q) dq/dp with
K dq/dp = -partial r / partial p (from r(q(p), p) = 0).  A ``func`` that finds
the equilibrium again for each p (``find_equilibrium`` then ``linearize``)
includes this term in its differences automatically; a user ``derivative`` must
include it itself.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError, SystemFunctionError
from .evaluation import Evaluator

__all__ = [
    "MatrixDerivatives",
    "exact_derivatives",
    "richardson_derivatives",
    "secant_derivatives",
    "STEP_FRACTION",
    "RICHARDSON_LEVELS",
    "ROUNDING_FACTOR",
    "EPS",
]

EPS = float(np.finfo(float).eps)

#: Default first step of the differences, relative to |p|: (1e-2)^6 = 1e-12 is the truncation error left
#: after two Richardson extrapolations, and 1 % keeps the samples close to p for families that change fast.
STEP_FRACTION = 1e-2
#: Default number of steps (h, h/2, h/4): two extrapolations, and a third entry to estimate their error.
RICHARDSON_LEVELS = 3
#: Rounding in a difference quotient is about eps ||X|| / h; this factor covers the extrapolation weights
#: (at most 4/3 + 1/3 per level) and the rounding of X itself by a few ulps.
ROUNDING_FACTOR = 8.0

_NAMES = ("M", "C", "K")


@dataclass(frozen=True, kw_only=True)
class MatrixDerivatives:
    """dM/dp, dC/dp, dK/dp at one parameter value, with absolute error estimates.

    Attributes
    ----------
    stack : (3, n, n) ndarray
        dM/dp, dC/dp, dK/dp.
    error : (3,) ndarray
        Estimated absolute error of each, Frobenius norm.
    method : str
        "exact (user derivative)", "central differences, Richardson", or "secant".
    calls : int
        Calls of ``func`` spent on them.
    step : float or None
        First step of the differences.
    """

    stack: np.ndarray
    error: np.ndarray
    method: str
    calls: int = 0
    step: float | None = None

    def dynamic(self, lam: complex) -> np.ndarray:
        """L_p(lam) = lam^2 dM/dp + lam dC/dp + dK/dp."""
        dM, dC, dK = self.stack
        return lam * lam * dM + lam * dC + dK

    def dynamic_error(self, lam: complex) -> float:
        """Bound on ||error of L_p(lam)||_F from the three matrix errors."""
        a = abs(lam)
        return float(a * a * self.error[0] + a * self.error[1] + self.error[2])


def exact_derivatives(derivative: Callable, p: float, n: int) -> MatrixDerivatives:
    """The user's ``derivative(p) -> (dM, dC, dK)``, checked.

    Raises
    ------
    SystemFunctionError
        ``derivative`` raised, or returned something other than three real finite (n, n) matrices.
    """
    try:
        parts = derivative(p)
    except Exception as exc:  # noqa: BLE001 - any failure of the user's function is reported with p
        raise SystemFunctionError(f"derivative({p!r}) raised {type(exc).__name__}: {exc}", p) from exc
    try:
        stack = np.array([np.asarray(a, dtype=float) for a in parts])
    except (TypeError, ValueError):
        raise SystemFunctionError(
            f"derivative({p!r}) must return three real (n, n) matrices (dM, dC, dK)", p) from None
    if stack.shape != (3, n, n):
        raise SystemFunctionError(
            f"derivative({p!r}) returned shape {stack.shape}; expected (3, {n}, {n}) for (dM, dC, dK)", p)
    if not np.all(np.isfinite(stack)):
        raise SystemFunctionError(f"derivative({p!r}) returned non-finite entries", p)
    norms = np.linalg.norm(stack, axis=(1, 2))
    return MatrixDerivatives(stack=stack, error=EPS * norms, method="exact (user derivative)")


def richardson_derivatives(evaluator: Evaluator, p: float, step: float, levels: int = RICHARDSON_LEVELS
                           ) -> MatrixDerivatives:
    """Central differences of M, C, K at p with Richardson extrapolation and its error estimate.

    Parameters
    ----------
    evaluator : Evaluator
    p : float
    step : float
        First step h > 0; then h/2, h/4, ...
    levels : int
        Number of steps, at least 2 (2 levels calls of ``func``).

    Returns
    -------
    MatrixDerivatives
        Each matrix from the tableau entry of smallest estimated error (Ridders):
        max(|T_ij - T_i,j-1|, |T_ij - T_i-1,j-1|), plus rounding
        ``ROUNDING_FACTOR`` eps max ||X|| / h_i.

    Raises
    ------
    ParameterError
        ``step`` not positive or ``levels`` < 2.
    SystemFunctionError
        From ``func``.
    """
    if not (np.isfinite(step) and step > 0):
        raise ParameterError("step", f"expected a positive finite step, got {step!r}")
    if int(levels) != levels or levels < 2:
        raise ParameterError("levels", f"expected an integer >= 2 (an error estimate needs two steps), got {levels!r}")
    levels = int(levels)
    calls0 = evaluator.calls
    h = [step / 2**i for i in range(levels)]
    table: list[list[np.ndarray]] = []
    rounding = []
    for hi in h:
        plus, minus = evaluator.matrices(p + hi), evaluator.matrices(p - hi)
        table.append([(plus - minus) / (2 * hi)])
        size = np.maximum(np.linalg.norm(plus, axis=(1, 2)), np.linalg.norm(minus, axis=(1, 2)))
        rounding.append(ROUNDING_FACTOR * EPS * size / hi)
    best = np.array(table[0][0])
    best_err = np.full(3, np.inf)
    for i in range(1, levels):
        for j in range(1, i + 1):
            factor = 4.0**j - 1.0
            table[i].append(table[i][j - 1] + (table[i][j - 1] - table[i - 1][j - 1]) / factor)
            gap = np.maximum(np.linalg.norm(table[i][j] - table[i][j - 1], axis=(1, 2)),
                             np.linalg.norm(table[i][j] - table[i - 1][j - 1], axis=(1, 2)))
            err = gap + rounding[i]
            for k in range(3):
                if err[k] < best_err[k]:
                    best_err[k] = err[k]
                    best[k] = table[i][j][k]
    return MatrixDerivatives(
        stack=best, error=best_err,
        method=f"central differences, Richardson ({levels} steps from h = {step:.3g})",
        calls=evaluator.calls - calls0, step=step,
    )


def secant_derivatives(X_a: np.ndarray, p_a: float, X_b: np.ndarray, p_b: float) -> MatrixDerivatives:
    """(X_b - X_a) / (p_b - p_a) for stacks X = (M, C, K): exact when they are affine in p.

    The error is not known (it is O(|p_b - p_a|) times the second derivative); it
    is reported as NaN and must not enter an error bound.  The searches use
    secants only to choose their steps, never to bound a result.
    """
    stack = (np.asarray(X_b) - np.asarray(X_a)) / (p_b - p_a)
    return MatrixDerivatives(stack=stack, error=np.full(3, np.nan), method="secant")
