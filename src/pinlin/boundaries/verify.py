"""Checking a boundary by the verdicts beside it, and bisection on the verdict (theory: boundaries).

A value p* with error bound e found from the eigenvalues is *verified* when the
stability verdicts at p* - e and p* + e (clipped to the bracket, whose ends'
verdicts are known) are those of the bracket's two ends: then the verdict
changes within [p* - e, p* + e].  A point whose verdict is "undecided" (within
rounding of the boundary) widens the check by a decade, up to
``VERIFY_DECADES`` times; a verdict undecided beyond that is a boundary that is
not isolated.  A wrong side (Newton converged to a root that is not where the
verdict changes, such as an eigenvalue resting on the axis) is reported
(``ok`` False) with the bracket shrunk by the verdicts computed, for the search
to be planned again.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import BoundaryNotIsolatedError, ConvergenceError
from .bracket import Bracket
from .derivatives import EPS
from .evaluation import Evaluator

__all__ = ["Check", "verify", "bisect", "VERIFY_DECADES", "BISECTION_ULPS", "NOT_ISOLATED_RTOL"]

#: Widenings by a factor of ten of the verified interval while a verdict beside p* is "undecided": a
#: verdict that stays undecided over 10^4 error bounds is not rounding at an isolated boundary.
VERIFY_DECADES = 4
#: Bisection stops at a bracket of this many ulps of p: below it the midpoint does not change.
BISECTION_ULPS = 4.0
#: Relative width (to the size of the bracket's ends) beyond which an "undecided" verdict is not rounding
#: at an isolated boundary: at a crossing or a coalescence the undecided band is a few hundred ulps of p
#: wide, far below sqrt(eps).
NOT_ISOLATED_RTOL = 1e-8


@dataclass
class Check:
    """The outcome of :func:`verify`: ``ok`` when the verdicts beside ``value`` (within ``bound``) differ."""

    value: float
    bound: float
    ok: bool = True
    steps: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)


def _rightmost(ev: Evaluator, p: float) -> complex:
    lam = ev.modes(p).eigenvalues
    return complex(lam[int(np.argmax(lam.real))])


def bisect(ev: Evaluator, br: Bracket, tol: float, max_evaluations: int):
    """Halve the bracket on the verdict until it is narrower than 2 max(tol, a few ulps).

    Returns (value, bound, eigenvalue, steps): the midpoint, half the final
    width, the rightmost eigenvalue at the end nearest the boundary's unstable side.

    Raises
    ------
    ConvergenceError
        More than ``max_evaluations`` modal analyses.
    BoundaryNotIsolatedError
        A midpoint's verdict is "undecided" and stays so on both halves: the
        verdict is undecided over an interval wider than the tolerance.
    """
    steps = []
    while br.width > 2 * max(tol, BISECTION_ULPS * EPS * max(abs(br.lo), abs(br.hi))):
        if ev.analyses >= max_evaluations:
            raise ConvergenceError(f"bisection: more than {max_evaluations} modal analyses, bracket "
                                   f"[{br.lo!r}, {br.hi!r}]", [br.width])
        mid = 0.5 * (br.lo + br.hi)
        cls = br.judge(ev, mid, "bisection", replan=False)
        steps.append("bisection")
        if cls == "undecided" and _undecided_interval(ev, br, mid, tol, max_evaluations, steps):
            break
    unstable_end = br.hi if br.class_lo == "stable" else br.lo
    return 0.5 * (br.lo + br.hi), 0.5 * br.width, _rightmost(ev, unstable_end), steps


def _undecided_interval(ev, br, mid, tol, max_evaluations, steps) -> bool:
    """An undecided midpoint: probe a quarter of the bracket to each side.

    Returns True when both probes are undecided too and the undecided span is
    within the resolution (stop: the bracket is the answer); raises when it is
    wider (the boundary is not isolated); False when a probe decided.
    """
    quarter = 0.25 * br.width
    for p in (mid - quarter, mid + quarter):
        if ev.analyses >= max_evaluations:
            raise ConvergenceError(f"bisection: more than {max_evaluations} modal analyses", [br.width])
        steps.append("bisection (probe beside an undecided verdict)")
        if br.judge(ev, p, "bisection probe", replan=False) != "undecided":
            return False
    if 2 * quarter > max(tol, NOT_ISOLATED_RTOL * max(abs(br.lo), abs(br.hi))):
        raise BoundaryNotIsolatedError(
            f"the stability verdict is 'undecided' over [{mid - quarter!r}, {mid + quarter!r}]: the boundary between "
            f"{br.kind_lo} at {br.lo!r} and {br.kind_hi} at {br.hi!r} is not isolated", (mid - quarter, mid + quarter))
    return True


def verify(ev: Evaluator, br: Bracket, value: float, bound: float, tol: float, band: float = 0.0) -> Check:
    """The verdicts at value -+ max(bound, band) (see the module docstring): the checked value and bound, or
    ``ok`` False.

    ``band`` is the expected half-width of the "undecided" verdicts around the
    boundary (where the verdict's own error bounds straddle zero): checking
    inside it would only widen.

    Raises
    ------
    BoundaryNotIsolatedError
        A verdict beside the value stays "undecided" over ``VERIFY_DECADES`` widenings.
    """
    w = max(bound, band, BISECTION_ULPS * EPS * abs(value))
    scale = max(abs(value), abs(br.lo), abs(br.hi))
    widest = max(w * 10.0**VERIFY_DECADES, NOT_ISOLATED_RTOL * scale, tol)
    check = Check(value, bound)
    while br.lo <= value <= br.hi:
        a, b = max(value - w, br.lo), min(value + w, br.hi)
        judged = [p for p, end in ((a, br.lo), (b, br.hi)) if p != end]
        ca = br.class_lo if a == br.lo else br.judge(ev, a, "verification", replan=False)
        cb = br.class_hi if b == br.hi else br.judge(ev, b, "verification", replan=False)
        check.steps += ["verification"] * len(judged)
        if ca == br.class_lo and cb == br.class_hi and br.lo == a and br.hi == b:
            check.bound = max(value - a, b - value)
            return check
        if "undecided" not in (ca, cb):
            break
        if w >= widest:
            raise BoundaryNotIsolatedError(
                f"the stability verdict stays 'undecided' within {w:.3g} of p = {value!r} (the error bound was "
                f"{bound:.3g}): the boundary between {br.kind_lo} and {br.kind_hi} is not isolated",
                (value - w, value + w))
        w *= 10.0
    check.ok = False
    check.notes.append(f"the verdicts beside p = {value!r} (+-{w:.3g}) do not separate the bracket's verdicts "
                       f"(the root found is not where the verdict changes); bracket now [{br.lo!r}, {br.hi!r}]")
    return check
