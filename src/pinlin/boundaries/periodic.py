"""Stability boundaries of periodic families ``func(p) -> FloquetAnalysis`` (theory: Floquet).

A periodic motion loses stability where a Floquet multiplier leaves the unit circle.  The boundary is
the root of one continuous function of p whose sign is the verdict's class, and which crosses zero
transversally at the boundary:

- damped (not conservative) systems: ``sigma(p) = max_k log |mu_k|`` over the non-trivial multipliers
  (a multiplier crosses the circle with nonzero speed);
- conservative systems (``FloquetAnalysis.conservative``: the monodromy is symplectic, the multipliers come
  in pairs mu, 1 / mu): on the stable side every multiplier lies on the circle, so ``log |mu|`` is
  identically 0 there and useless for a root.  The pair leaves the circle through +1 or -1 (a tongue of
  Mathieu's equation) where ``c = (mu + 1 / mu) / 2`` reaches +1 or -1: c is real on both sides (cos theta on
  the circle, cosh of the growth rate off it), and ``sigma(p) = max_k |Re c_k| - 1`` changes sign
  transversally.  A collision of two pairs away from +-1 (a Krein collision) leaves c complex on the
  unstable side: there sigma takes ``max log |mu|`` (positive), still the right sign.

The root is bracketed and found by Brent's method (scipy's ``brentq``: superlinear, never leaves the
bracket).  Its error bound adds Brent's final bracket to the multipliers' own error bounds carried into p
through the slope of sigma: ``|sigma error| / |sigma'(p*)|``, with ``sigma'`` from the last two iterates.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
import scipy.optimize

from ..errors import BracketError, ParameterError, SystemFunctionError
from ..periodic import FloquetAnalysis
from .critical_result import CriticalParameter
from .evaluation import VERDICT_CLASS, call_family, check_parameter

__all__ = ["periodic_critical_parameter", "stability_function", "is_periodic_family", "MAX_EVALUATIONS"]

#: Most Floquet analyses a boundary search makes.
MAX_EVALUATIONS = 60


def is_periodic_family(value) -> bool:
    """True when ``value`` (a family's value at one p) is a Floquet analysis.

    Examples
    --------
    >>> from pinlin.boundaries.periodic import is_periodic_family
    >>> flo = pinlin.floquet_analysis_matrices([[1.0]], None, [[2.0]], 1.0)
    >>> is_periodic_family(flo), is_periodic_family(pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.0]], [[2.0]]))
    (True, False)
    """
    return isinstance(value, FloquetAnalysis)


def stability_function(flo: FloquetAnalysis) -> tuple[float, float, complex]:
    """(sigma, its error bound, the critical multiplier) of one Floquet analysis (see the module docstring).

    Negative: stable; positive: unstable; the error bound is the multipliers' bounds carried into sigma
    (first order: |d log|mu|| <= b / |mu|, |d c| <= b |1 - 1 / mu^2| / 2).

    Examples
    --------
    >>> from pinlin.boundaries.periodic import stability_function
    >>> def mathieu(delta):
    ...     return pinlin.floquet_analysis_matrices([[1.0]], None, lambda t: [[delta + 0.3 * np.cos(t)]], 2 * np.pi)
    >>> inside, outside = stability_function(mathieu(0.25))[0], stability_function(mathieu(0.5))[0]
    >>> print(inside > 0, outside < 0)       # unstable in the tongue, stable outside
    True True
    """
    keep = ~np.asarray(flo.trivial, dtype=bool)
    mu = np.asarray(flo.multipliers)[keep]
    bound = np.asarray(flo.error_bound)[keep]
    if mu.size == 0:
        raise ParameterError("func", "every multiplier of the Floquet analysis is trivial: no boundary to find")
    log_abs = np.log(np.abs(mu))
    worst = int(np.argmax(log_abs))
    if flo.conservative:
        c = (mu + 1.0 / mu) / 2.0
        real = np.abs(c.imag) <= np.abs(bound * np.abs(1.0 - 1.0 / mu**2))   # c real within its error
        if np.all(real):
            k = int(np.argmax(np.abs(c.real)))
            error = float(bound[k] * abs(1.0 - 1.0 / mu[k] ** 2) / 2.0)
            return float(abs(c[k].real) - 1.0), error, complex(mu[k])
    return float(log_abs[worst]), float(bound[worst] / abs(mu[worst])), complex(mu[worst])


def _verify(family: _Family, root: float, bound: float, bracket) -> tuple[float, bool]:
    """Verdicts at root -+ w, w = bound times 1, 10, 100, ... (inside the bracket): the first w at which both
    are decided and differ in class widens the bound to w (near a collision of multipliers on the circle
    the verdict is "undecided" over a width well above the root's own uncertainty)."""
    w = max(bound, 4 * np.finfo(float).eps * max(abs(root), 1.0))
    while w <= (bracket[1] - bracket[0]) / 2:
        if family.calls + 2 > family.max_evaluations:
            return bound, False
        below, above = (family(min(max(root + sign * w, bracket[0]), bracket[1])).stability.kind for sign in (-1, 1))
        classes = VERDICT_CLASS[below], VERDICT_CLASS[above]
        if "undecided" not in classes and (classes[0] == "stable") != (classes[1] == "stable"):
            return max(bound, w), True
        w *= 10.0
    return bound, False


class _Family:
    """``func`` with checks and a memory of its values for one search."""

    def __init__(self, func: Callable, first: tuple[float, FloquetAnalysis] | None, max_evaluations: int):
        self.func, self.max_evaluations = func, max_evaluations
        self.values: dict[float, FloquetAnalysis] = {}
        self.calls = 0
        if first is not None:
            self.values[float(first[0])] = first[1]
            self.calls = 1

    def __call__(self, p: float) -> FloquetAnalysis:
        p = float(p)
        if p in self.values:
            return self.values[p]
        if self.calls >= self.max_evaluations:
            raise SystemFunctionError(
                f"the search needed more than max_evaluations = {self.max_evaluations} Floquet analyses", p)
        self.calls += 1
        flo = call_family(self.func, p)
        if not is_periodic_family(flo):
            raise SystemFunctionError(
                f"func({p!r}) returned {type(flo).__name__}; the family returned a FloquetAnalysis elsewhere", p)
        self.values[p] = flo
        return flo


def periodic_critical_parameter(func: Callable, bracket, *, atol: float | None = None,
                                max_evaluations: int = MAX_EVALUATIONS,
                                first: tuple[float, FloquetAnalysis] | None = None) -> CriticalParameter:
    """The parameter in ``bracket`` where the Floquet verdict of ``func(p)`` changes class.

    Parameters
    ----------
    func : callable
        ``func(p) -> FloquetAnalysis`` (for example ``lambda p: pinlin.floquet_analysis(scene(p), orbit(p))``),
        continuous in p.
    bracket : (float, float)
        Two values whose verdicts differ in class (stable against divergence or flutter).
    atol : float, optional
        Absolute tolerance of Brent's iteration [unit of p]; default: 4 eps |p| (rounding).  Reached through
        :func:`pinlin.critical_parameter`, whose keyword it is.
    max_evaluations : int
        Most Floquet analyses allowed.
    first : (float, FloquetAnalysis), optional
        A value of the family already computed (reused, counted as one call).

    Returns
    -------
    CriticalParameter
        ``error_bound``: the final bracket plus the multipliers' bounds carried into p, widened to the
        distance at which the verdicts on the two sides were computed, decided and found to differ
        (``verified``); ``mechanism`` "multiplier crossing", ``eigenvalue`` the critical multiplier at p* (on the unit
        circle), ``kind`` the verdict on the unstable side.

    Raises
    ------
    BracketError
        The ends have the same verdict class or one is "undecided".
    SystemFunctionError
        ``func`` raised, returned something else, or the budget ran out.

    Examples
    --------
    The lower edge of Mathieu's first tongue of instability, b_1(q) / 4 at q = 0.6 (scipy.special.mathieu_b):

    >>> import scipy.special
    >>> from pinlin.boundaries.periodic import periodic_critical_parameter
    >>> def mathieu(delta):
    ...     return pinlin.floquet_analysis_matrices([[1.0]], None, lambda t: [[delta + 0.3 * np.cos(t)]], 2 * np.pi)
    >>> crit = periodic_critical_parameter(mathieu, (0.05, 0.25))
    >>> print(f"{crit.value:.6f}", f"{scipy.special.mathieu_b(1, 0.6) / 4:.6f}", crit.verified)
    0.089568 0.089568 True
    """
    t0 = time.perf_counter()
    lo, hi = (check_parameter(x, "bracket") for x in bracket)
    if not lo < hi:
        raise BracketError(f"bracket must be two increasing numbers, got {tuple(bracket)!r}", (lo, hi))
    family = _Family(func, first, int(max_evaluations))
    ends = [family(lo), family(hi)]
    classes = [VERDICT_CLASS[f.stability.kind] for f in ends]
    if "undecided" in classes or (classes[0] == "stable") == (classes[1] == "stable"):
        raise BracketError(
            f"the Floquet verdicts at the ends of the bracket, {classes}, must be stable at one end and unstable "
            f"at the other", (lo, hi), tuple(f.stability.kind for f in ends))
    steps: list[str] = []

    def sigma(p: float) -> float:
        value = stability_function(family(p))[0]
        steps.append(f"p = {p:.17g}: sigma = {value:+.3e}")
        return value

    xtol = 4 * np.finfo(float).eps * max(abs(lo), abs(hi)) if atol is None else float(atol)
    root, info = scipy.optimize.brentq(sigma, lo, hi, xtol=max(xtol, 1e-300), rtol=4 * np.finfo(float).eps,
                                       full_output=True, disp=False)
    # the tightest pair of evaluated values with opposite signs of sigma: the final bracket
    values = sorted(family.values)
    signs = {p: stability_function(family(p)) for p in values}
    pairs = [(a, b) for a, b in zip(values, values[1:]) if (signs[a][0] < 0) != (signs[b][0] < 0) and a <= root <= b]
    a, b = min(pairs, key=lambda ab: ab[1] - ab[0]) if pairs else (lo, hi)
    slope = (signs[b][0] - signs[a][0]) / (b - a)
    carried = max(signs[a][1], signs[b][1]) / abs(slope) if slope else math.inf
    bound = float((b - a) + carried)
    near = (a, b)
    s = [signs[a] if abs(a - root) <= abs(b - root) else signs[b]]
    bound, verified = _verify(family, float(root), bound, (lo, hi))
    unstable = ends[1] if classes[0] == "stable" else ends[0]
    verdicts = (ends[0].stability.kind, ends[1].stability.kind)
    return CriticalParameter(
        value=float(root), kind=unstable.stability.kind, mechanism="multiplier crossing",
        eigenvalue=s[0][2], error_bound=bound, bracket=(float(min(near)), float(max(near))), verdicts=verdicts,
        verified=bool(verified and info.converged), evaluations=family.calls, function_calls=family.calls,
        steps=tuple(steps),
        method="Brent's method on the Floquet stability function (multipliers' distance from the unit circle)",
        elapsed=time.perf_counter() - t0,
        notes=(("conservative: sigma = max |Re (mu + 1/mu) / 2| - 1",) if ends[0].conservative else ()),
    )
