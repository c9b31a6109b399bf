"""The parameter value where the stability verdict changes (theory: boundaries).

:func:`critical_parameter` keeps a bracket from the verdicts
(:mod:`.bracket`) and converges with what the eigenvalues know:

- a transversal crossing by safeguarded Newton-type steps with the eigenvalue
  sensitivity (:mod:`.crossing`): on the spectral abscissa for flutter of a
  damped system, on the largest real eigenvalue of the pencil (-K, M) for
  divergence (a real root reaches zero where K turns singular);
- a coalescence (undamped circulatory or gyroscopic systems: two eigenvalues
  meet on an axis of symmetry of the spectrum and leave it, Re lam ~ sqrt(p - p*))
  by Newton on the defining system of the double eigenvalue (:mod:`.pairing`,
  :mod:`.coalescence`);

then checks the verdicts on both sides of the value found (:mod:`.verify`).
Which mechanism applies is read from the verdicts and the systems at the
bracket's ends (:func:`plan`); one that does not fit, a verdict of a third class
met inside, or a failed check makes the search plan again in the smaller
bracket.  Bisection on the verdict is available as ``method="bisection"`` (the
baseline) and is used, and said, when nothing else works.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from ..errors import ConvergenceError, ParameterError
from ..errors.deprecated import renamed_keywords
from ..spectral import STABILITY_SAFETY
from .bracket import Bracket, BracketChanged, PlanMismatch, open_bracket
from .critical_result import CriticalParameter
from .crossing import REAL_SAFETY, newton_crossing
from .evaluation import Evaluator, PeriodicFamily
from .pairing import coalescence_search
from .periodic import periodic_critical_parameter
from .vanishing import vanishing_damping_limit
from .verify import bisect, verify

__all__ = ["CriticalParameter", "critical_parameter", "plan", "BOUND_SAFETY", "MAX_EVALUATIONS", "METHODS",
           "VERDICT_MARGIN"]

#: Factor on the rounding-level (first-order) uncertainty of the root in the error bound: first-order
#: estimates of eigenvalue errors can be off by a small factor.
BOUND_SAFETY = 4.0
#: Default limit on modal analyses per boundary: bisection from a bracket of relative width 1 to rounding
#: needs about 52; the fast methods need about 10.
MAX_EVALUATIONS = 80
#: Times the search is planned again when a verdict of a third class (flutter between stable and
#: divergence) replaces the upper end: each time the bracket holds one boundary fewer.
MAX_REPLANS = 3
#: At a transversal crossing the verdict is "undecided" within its safety factor times the root's rounding
#: floor of p*; the check of the verdicts starts just outside, at this multiple of that band.
VERDICT_MARGIN = 2.0
METHODS = ("auto", "bisection")




def _zero(sys, name: str) -> bool:
    return not np.any(getattr(sys, name))


def _real_positive(modes) -> int:
    lam, r = modes.eigenvalues, REAL_SAFETY * modes.error_bound
    return int(np.sum((lam.real > r) & (np.abs(lam.imag) <= r)))


def plan(ev: Evaluator, br: Bracket) -> list[tuple[str, dict[str, Any]]]:
    """The mechanisms to try, most likely first, from the systems and verdicts at the bracket's ends.

    Each is ("crossing", {"mode": tracker}) or ("coalescence", {"squared", "axis", "on_class"}).  An
    undamped symmetric spectrum leaves a marginally stable side only by a coalescence (or, for
    D = G = 0, by mu = lam^2 through zero); a damped one by a crossing.  Between flutter and divergence,
    an odd change of the number of real positive eigenvalues suggests a real root through zero, an even
    one a complex pair landing on the real axis; the other is tried when the first does not fit.
    """
    systems = [ev.system(br.lo), ev.system(br.hi)]
    squared = all(_zero(s, "D") and _zero(s, "G") for s in systems)
    symmetric = all(_zero(s, "D") and (_zero(s, "G") or _zero(s, "N")) for s in systems)
    classes = {br.class_lo, br.class_hi}
    real_axis = ("coalescence", {"squared": squared, "axis": "real", "on_class": "divergence"})
    if "stable" in classes:
        stable_kind = br.kind_lo if br.class_lo == "stable" else br.kind_hi
        unstable = (classes - {"stable"}).pop()
        if stable_kind == "marginally_stable" and symmetric:
            axis = ("coalescence", {"squared": squared, "axis": "real" if squared else "imaginary",
                                    "on_class": "stable"})
            if squared and unstable == "divergence":
                return [("crossing", {"mode": "stiffness"}), axis]
            return [axis, ("crossing", {"mode": "abscissa"})]
        if unstable == "divergence":  # a real root through zero: K turns singular
            return [("crossing", {"mode": "stiffness"}), ("crossing", {"mode": "abscissa"})]
        return [("crossing", {"mode": "abscissa"})]
    root = ("crossing", {"mode": "stiffness"})
    change = abs(_real_positive(ev.modes(br.lo)) - _real_positive(ev.modes(br.hi)))
    return [root, real_axis] if change % 2 == 1 else [real_axis, root]


def _boundary_kind(br: Bracket) -> str:
    if br.class_lo == "stable":
        return br.class_hi
    if br.class_hi == "stable":
        return br.class_lo
    return "divergence"


def _lam_of(s: complex, squared: bool) -> complex:
    return complex(np.sqrt(complex(s))) if squared else complex(s)


@renamed_keywords(tol="atol")
def critical_parameter(
    func: Callable[[float], Any],
    bracket,
    *,
    atol: float | None = None,
    derivative: Callable[[float], Any] | None = None,
    method: str = "auto",
    verify_result: bool = True,
    max_evaluations: int = MAX_EVALUATIONS,
    modal_options: Mapping[str, Any] | None = None,
    damping=None,
) -> CriticalParameter:
    """The parameter value in ``bracket`` where the stability verdict of ``func(p)`` changes (theory: boundaries).

    Parameters
    ----------
    func : callable
        ``func(p) -> LinearizedSystem``, continuous in p; or ``func(p) -> FloquetAnalysis`` for a periodic
        family (the boundary where a multiplier leaves the unit circle: :mod:`pinlin.boundaries.periodic`;
        ``derivative``, ``method``, ``modal_options`` and ``damping`` do not apply there).
    bracket : (float, float)
        Two parameter values whose verdicts (``modes.stability.kind``) differ in
        class: stable (asymptotically or marginally), divergence, flutter.
    atol : float, optional
        Absolute accuracy aimed at on p* [unit of p]; default: as accurately as rounding
        allows (the Newton correction below the root's rounding-level uncertainty).
        ``tol`` is its deprecated spelling.
    derivative : callable, optional
        ``derivative(p) -> (dM, dC, dK)``, exact; otherwise secants between the
        evaluated systems choose the Newton steps (exact for matrices affine in
        p; only the speed depends on them, never the value or its bound).
    method : {"auto", "bisection"}
        "bisection" halves the bracket on the verdict alone (the baseline).
    verify_result : bool
        Compute the verdicts at value -+ error_bound (two more modal analyses,
        widened by decades while one is "undecided") and require them to differ.
    max_evaluations : int
        Most modal analyses allowed.
    modal_options : mapping, optional
        Passed to :func:`pinlin.modal_analysis`.
    damping : (n, n) array or callable, optional
        A damping shape D1 in the system's coordinates (or ``p -> D1``): the
        result is then the limit, as eps -> 0, of the flutter boundary of
        ``func(p)`` with D = eps D1 added, found from the limit problem (the
        root of the first-order rate of the axis eigenvalues' real parts,
        :mod:`pinlin.boundaries.vanishing`; theory: stability), mechanism
        "vanishing damping".  ``func(bracket[0])`` must be marginally stable
        and small damping of the shape must stabilize it there.

    Returns
    -------
    CriticalParameter

    Raises
    ------
    BracketError
        The ends have the same verdict class, or one is "undecided", or they are
        not two distinct finite numbers.
    BoundaryNotIsolatedError
        The verdict changes, but not at an isolated crossing (it stays
        "undecided" over an interval, or the critical eigenvalue stays on the
        axis on both sides of the value found).
    SystemFunctionError
        ``func`` (or ``derivative``) raised, returned a wrong value or systems of
        different sizes.
    ConvergenceError
        More than ``max_evaluations`` modal analyses.
    ParameterError
        Bad ``atol``, ``method`` or ``max_evaluations``.

    Examples
    --------
    The stiffness 1 - p vanishes at p = 1: divergence:

    >>> def family(p):
    ...     return pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.1]], [[1.0 - p]])
    >>> crit = pinlin.critical_parameter(family, (0.0, 2.0))
    >>> round(crit.value, 12), crit.kind
    (1.0, 'divergence')
    """
    t0 = time.perf_counter()
    if method not in METHODS:
        raise ParameterError("method", f"expected one of {METHODS}, got {method!r}")
    if atol is not None and not (np.isfinite(atol) and atol > 0):
        raise ParameterError("atol", f"expected a positive absolute tolerance or None, got {atol!r}")
    if (isinstance(max_evaluations, (bool, np.bool_)) or not isinstance(max_evaluations, (int, float, np.integer, np.floating))
            or not np.isfinite(max_evaluations) or int(max_evaluations) != max_evaluations or max_evaluations < 3):
        raise ParameterError("max_evaluations", f"expected an integer >= 3, got {max_evaluations!r}")
    if damping is not None:
        return _vanishing(func, bracket, damping, atol, max_evaluations, modal_options, t0)
    ev = Evaluator(func, modal_options)
    try:
        br = open_bracket(ev, bracket)
    except PeriodicFamily as found:  # func(p) -> FloquetAnalysis: the multipliers' boundary
        return periodic_critical_parameter(func, bracket, atol=atol, max_evaluations=max_evaluations,
                                           first=(found.p, found.value))
    tol_abs = 0.0 if atol is None else float(atol)
    notes: list[str] = []
    if method == "bisection":
        value, bound, lam, steps = bisect(ev, br, tol_abs, max_evaluations)
        mechanism, how, verified = "bisection", "bisection on the stability verdict", True
    else:
        mechanism, value, bound, lam, steps, how, verified = _search(
            ev, br, tol_abs, derivative, max_evaluations, verify_result, modal_options, notes)
    return CriticalParameter(
        value=float(value), kind=_boundary_kind(br), mechanism=mechanism, eigenvalue=complex(lam),
        error_bound=float(bound), bracket=(br.lo, br.hi), verdicts=(br.kind_lo, br.kind_hi), verified=verified,
        evaluations=ev.analyses, function_calls=ev.calls, steps=tuple(steps), method=how,
        elapsed=time.perf_counter() - t0, notes=tuple(notes),
    )


def _vanishing(func, bracket, damping, atol, max_evaluations, modal_options, t0) -> CriticalParameter:
    """``critical_parameter(..., damping=D1)``: the vanishing-damping limit, or the coalescence it reaches."""
    lim = vanishing_damping_limit(func, bracket, damping, atol=atol, max_evaluations=max_evaluations,
                                  modal_options=modal_options)
    if lim.value is None:
        res = critical_parameter(func, bracket, atol=atol, max_evaluations=max_evaluations, modal_options=modal_options)
        return dataclasses.replace(res, elapsed=time.perf_counter() - t0, notes=res.notes + (
            "vanishing damping of the given shape stabilizes up to the undamped flutter point: the limit is it",))
    return CriticalParameter(
        value=lim.value, kind="flutter", mechanism="vanishing damping", eigenvalue=lim.eigenvalue,
        error_bound=lim.error_bound, bracket=lim.bracket, verdicts=("asymptotically_stable", "flutter"),
        verified=False, evaluations=lim.evaluations, function_calls=lim.function_calls, steps=lim.steps,
        method="the root of the first-order rate g(p) = max d Re lam / d eps of the axis eigenvalues for "
               "D = eps D1 (the limit problem of vanishing damping; Brent's method)",
        elapsed=time.perf_counter() - t0,
        notes=("verdicts: of func(p) with D = eps D1 for small eps > 0, to first order in eps (not computed at "
               "a finite eps)",),
    )


def _search(ev, br, tol, derivative, max_evaluations, verify_result, modal_options, notes):
    """The fast search, checked by the verdicts beside its value; planned again (in the bracket the check
    shrank) when the check fails, and bisection when nothing else works: (mechanism, value, bound,
    eigenvalue, steps, method, verified)."""
    steps: list[str] = []
    for _ in range(MAX_REPLANS + 1):
        try:
            mechanism, value, bound, lam, taken, how, floor = _planned(ev, br, tol, derivative, max_evaluations,
                                                                       notes)
        except ConvergenceError as exc:
            notes.append(f"the fast iteration failed ({exc}); bisection on the verdict took over")
            break
        steps += taken
        if not verify_result:
            return mechanism, value, bound, lam, steps, how, False
        band = 0.0
        if mechanism == "crossing":
            band = VERDICT_MARGIN * dict(modal_options or {}).get("safety", STABILITY_SAFETY) * floor
        check = verify(ev, br, value, bound, tol, band)
        steps += check.steps
        notes += check.notes
        if check.ok:
            return mechanism, check.value, check.bound, lam, steps, how, True
    value, bound, lam, taken = bisect(ev, br, tol, max_evaluations + ev.analyses)
    return "bisection", value, bound, lam, steps + taken, "bisection on the stability verdict (fallback)", True


def _planned(ev, br, tol, derivative, max_evaluations, notes):
    """Plan the mechanisms from the bracket's verdicts and run the first that fits: (mechanism, value, bound,
    eigenvalue, steps, method, floor).  When none fits (the bracket holds more than the boundary it
    shows), a bisection step on the verdict shrinks it and the plan is made again; so also when a verdict
    of a third class replaces an end."""
    replans = 0
    while ev.analyses < max_evaluations:
        try:
            for mechanism, settings in plan(ev, br):
                try:
                    return _fast(ev, br, mechanism, settings, tol, derivative, max_evaluations)
                except PlanMismatch as why:
                    notes.append(f"{mechanism} ({', '.join(f'{v}' for v in settings.values())}) does not fit: {why}")
            br.judge(ev, 0.5 * (br.lo + br.hi), "bisection (no mechanism fits)")
        except BracketChanged as signal:
            replans += 1
            notes.append(f"{signal}: planned again for {br.kind_lo} / {br.kind_hi}")
            if replans > MAX_REPLANS:
                break
    raise ConvergenceError(f"no mechanism fits the verdicts at the bracket's ends [{br.lo!r}, {br.hi!r}]", [])


def _fast(ev, br, mechanism, settings, tol, derivative, max_evaluations):
    """The Newton iteration of ``mechanism``: (mechanism, value, bound, eigenvalue, steps, method, rounding floor)."""
    if mechanism == "crossing":
        res = newton_crossing(ev, br, settings["mode"], tol=tol, derivative=derivative, safety=BOUND_SAFETY,
                              max_evaluations=max_evaluations)
        what = {"abscissa": "Re lam = 0 (spectral abscissa)",
                "stiffness": "det K = 0 (the largest real eigenvalue mu of (-K, M))"}[settings["mode"]]
        if not res.converged:
            return ("bisection", res.value, res.bound, res.eigenvalue, res.steps,
                    f"safeguarded Newton on {what}: {res.reason}", res.floor)
        return ("crossing", res.value, res.bound, res.eigenvalue, res.steps,
                f"safeguarded Newton on {what}: steps from phi' (the eigenvalue sensitivity) and the cubic Hermite "
                "interpolant of phi, phi' at the bracket's ends", res.floor)
    sol, steps = coalescence_search(ev, br, squared=settings["squared"], axis=settings["axis"],
                                    on_class=settings["on_class"], tol=tol, derivative=derivative,
                                    max_evaluations=max_evaluations)
    form = "mu = lam^2, A = K + mu M (real)" if settings["squared"] else "lam, A = K + lam C + lam^2 M"
    bound = sol.last_step + BOUND_SAFETY * sol.floor
    return ("coalescence", sol.p, bound, _lam_of(sol.s, settings["squared"]), steps,
            f"Newton on the defining system of a double eigenvalue in (p, s, x, y), {form}", sol.floor)
