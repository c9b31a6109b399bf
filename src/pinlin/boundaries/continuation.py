"""A stability boundary curve p2*(p1) in a plane of two parameters, by continuation (theory: boundaries).

From point to point the boundary moves little: the next p2* is predicted by
extrapolating the points found (linearly from two, quadratically from three)
and bracketed tightly around the prediction, so each corrector
(:func:`~pinlin.boundaries.critical_parameter`) starts from a narrow bracket
whose secant already knows how the matrices change.  A bracket whose verdicts
do not differ is widened by ``WIDEN_FACTOR`` until they do, and at last the
caller's bracket is used.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..errors import BracketError, ParameterError, PinlinError
from ..errors.deprecated import renamed_keywords
from ..numerics.arrays import readonly
from ..results import Result
from .critical import MAX_EVALUATIONS, CriticalParameter, critical_parameter
from .derivatives import EPS

__all__ = ["StabilityBoundary", "BoundaryFailure", "stability_boundary", "PREDICTOR_SPREAD", "WIDEN_FACTOR",
           "WIDENINGS", "ON_ERROR"]

#: Half-width of the bracket around a prediction, in units of the prediction's own error estimate (the
#: change from the lower-order extrapolation): generous, since a missed bracket costs two more analyses.
PREDICTOR_SPREAD = 4.0
#: Each failed bracket around a prediction is widened by this factor ...
WIDEN_FACTOR = 8.0
#: ... this many times, before the caller's bracket is used.
WIDENINGS = 3
#: Relative floor of a predicted bracket's half-width: the correctors' own precision, with margin.
MIN_RELATIVE_SPREAD = 1e3 * EPS
ON_ERROR = ("raise", "record")


@dataclass(frozen=True, kw_only=True)
class BoundaryFailure:
    """A point of the curve that could not be found (``on_error="record"``): its index, p1 and what was raised.

    Examples
    --------
    A point whose system cannot be built is recorded with ``on_error="record"``:

    >>> def family(c, p):
    ...     if c == 2.0:
    ...         raise pinlin.ParameterError("c", "no model here")
    ...     return pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.1]], [[c - p]])
    >>> curve = pinlin.stability_boundary(family, [1.0, 2.0], (0.0, 3.0), on_error="record")
    >>> failure = curve.failures[0]
    >>> failure.index, failure.p1
    (1, 2.0)
    """

    index: int
    p1: float
    message: str


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class StabilityBoundary(Result):
    """The boundary curve p2*(p1) (theory: boundaries).

    Attributes
    ----------
    p1 : (m,) float
        The first parameter's values, as given.
    p2 : (m,) float
        The boundary p2*(p1); NaN exactly where ``found`` is False (see ``failures``).
    error_bound : (m,) float
        Absolute bound of each point [unit of p2] (inf where not found).
    kind : tuple of str
        "divergence" / "flutter" per point ("" where not found).
    mechanism : tuple of str
    eigenvalue : (m,) complex
        The critical eigenvalue at each point.
    found : (m,) bool
    points : tuple of CriticalParameter or None
        Each point's full result.
    failures : tuple of BoundaryFailure
    evaluations : int
        Modal analyses over the whole curve.
    function_calls : int
    method : str
    error : float
        Largest ``error_bound`` of the points found (absolute, unit of p2; inf if none).
    elapsed : float
        Seconds [s].

    Examples
    --------
    >>> def family(c, p):
    ...     return pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.1]], [[c - p]])
    >>> curve = pinlin.stability_boundary(family, [1.0, 2.0], (0.0, 3.0))
    >>> curve.kind, curve.found.tolist()
    (('divergence', 'divergence'), [True, True])
    """

    p1: np.ndarray
    p2: np.ndarray
    error_bound: np.ndarray
    kind: tuple[str, ...]
    mechanism: tuple[str, ...]
    eigenvalue: np.ndarray
    found: np.ndarray
    points: tuple[CriticalParameter | None, ...]
    failures: tuple[BoundaryFailure, ...]
    evaluations: int
    function_calls: int
    method: str
    elapsed: float

    @property
    def error(self) -> float:
        return float(np.max(self.error_bound[self.found])) if np.any(self.found) else float("inf")

    def __repr__(self) -> str:
        return (f"StabilityBoundary(points={len(self.p1)}, found={int(np.sum(self.found))}, "
                f"kinds={sorted(set(k for k in self.kind if k))}, error={self.error:.1e}, "
                f"evaluations={self.evaluations}, elapsed={self.elapsed:.3g}s)")


def _predict(p1: float, done: list[tuple[float, float]]) -> tuple[float, float] | None:
    """Extrapolated p2 at p1 and an estimate of its error, from the last points found (None if none)."""
    if not done:
        return None
    if len(done) == 1:
        return done[-1][1], np.inf
    xs, ys = np.array([d[0] for d in done[-3:]]), np.array([d[1] for d in done[-3:]])
    linear = ys[-1] + (ys[-1] - ys[-2]) * (p1 - xs[-1]) / (xs[-1] - xs[-2])
    if len(xs) < 3:
        return linear, abs(linear - ys[-1])
    quadratic = float(np.polyval(np.polyfit(xs, ys, 2), p1))
    return quadratic, abs(quadratic - linear)


def _brackets(p1, done, bracket):
    """Brackets to try at p1: around the prediction, widening, then the caller's."""
    lo, hi = min(bracket), max(bracket)
    guess = _predict(p1, done)
    if guess is not None and np.isfinite(guess[1]):
        center, spread = guess
        w = max(PREDICTOR_SPREAD * spread, MIN_RELATIVE_SPREAD * abs(center), done[-1][2])
        for _ in range(WIDENINGS + 1):
            a, b = max(center - w, lo), min(center + w, hi)
            if a < b and (a, b) != (lo, hi):
                yield (a, b), "predicted"
            w *= WIDEN_FACTOR
    yield (lo, hi), "given"


@renamed_keywords(tol="atol")
def stability_boundary(
    func2: Callable[[float, float], Any],
    p1_values,
    bracket,
    *,
    atol: float | None = None,
    derivative: Callable[[float, float], Any] | None = None,
    on_error: str = "raise",
    verify_result: bool = True,
    max_evaluations: int = MAX_EVALUATIONS,
    modal_options: Mapping[str, Any] | None = None,
) -> StabilityBoundary:
    """The stability boundary p2*(p1) of ``func2(p1, p2)`` for each p1 in ``p1_values`` (theory: boundaries).

    Parameters
    ----------
    func2 : callable
        ``func2(p1, p2) -> LinearizedSystem``.
    p1_values : sequence of float
        Where to find the boundary, in the order to follow it (continuation).
    bracket : (float, float)
        A p2 bracket of the boundary valid at every p1 (used for the first point,
        and whenever a predicted bracket fails).
    atol, verify_result, max_evaluations, modal_options
        As :func:`~pinlin.boundaries.critical_parameter`, per point (``tol`` is the
        deprecated spelling of ``atol``).
    derivative : callable, optional
        ``derivative(p1, p2) -> (dM, dC, dK)``, exact derivatives in p2.
    on_error : {"raise", "record"}
        A point that fails raises, or is recorded in ``failures`` and the curve goes on.

    Returns
    -------
    StabilityBoundary

    Raises
    ------
    ParameterError
        Empty or non-finite ``p1_values``, bad ``on_error``.
    PinlinError
        Any error of :func:`~pinlin.boundaries.critical_parameter` at a point
        (with ``on_error="raise"``), the point named in the message.

    Examples
    --------
    The stiffness c - p vanishes at p = c:

    >>> def family(c, p):
    ...     return pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.1]], [[c - p]])
    >>> curve = pinlin.stability_boundary(family, [1.0, 2.0], (0.0, 3.0))
    >>> np.round(curve.p2, 12)
    array([1., 2.])
    """
    t0 = time.perf_counter()
    if on_error not in ON_ERROR:
        raise ParameterError("on_error", f"expected one of {ON_ERROR}, got {on_error!r}")
    try:
        p1s = np.array(p1_values, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ParameterError("p1_values", f"expected a sequence of numbers, got {p1_values!r}") from None
    if p1s.size == 0 or not np.all(np.isfinite(p1s)):
        raise ParameterError("p1_values", "expected a non-empty sequence of finite numbers")
    done: list[tuple[float, float, float]] = []
    points: list[CriticalParameter | None] = []
    failures: list[BoundaryFailure] = []
    for i, p1 in enumerate(float(x) for x in p1s):
        def func(p2, p1=p1):
            return func2(p1, p2)

        deriv = None if derivative is None else (lambda p2, p1=p1: derivative(p1, p2))
        try:
            point = _corrector(func, deriv, p1, done, bracket, atol, verify_result, max_evaluations, modal_options)
        except PinlinError as exc:
            if on_error == "raise":
                if hasattr(exc, "add_note"):  # Python >= 3.11
                    exc.add_note(f"stability_boundary: at point {i}, p1 = {p1!r}")
                raise
            failures.append(BoundaryFailure(index=i, p1=p1, message=f"{type(exc).__name__}: {exc}"))
            points.append(None)
            continue
        done.append((p1, point.value, point.error_bound))
        points.append(point)
    found = np.array([p is not None for p in points])
    return StabilityBoundary(
        p1=readonly(p1s),
        p2=readonly([p.value if p else np.nan for p in points]),
        error_bound=readonly([p.error_bound if p else np.inf for p in points]),
        kind=tuple(p.kind if p else "" for p in points),
        mechanism=tuple(p.mechanism if p else "" for p in points),
        eigenvalue=readonly(np.array([p.eigenvalue if p else np.nan for p in points], dtype=complex)),
        found=readonly(found),
        points=tuple(points),
        failures=tuple(failures),
        evaluations=sum(p.evaluations for p in points if p),
        function_calls=sum(p.function_calls for p in points if p),
        method="continuation: extrapolated predictor, bracket around it, critical_parameter as corrector",
        elapsed=time.perf_counter() - t0,
    )


def _corrector(func, deriv, p1, done, bracket, atol, verify_result, max_evaluations, modal_options):
    """critical_parameter at one p1, on the predicted brackets first; analyses of failed brackets counted."""
    spent, calls = 0, 0
    last = None
    for br, origin in _brackets(p1, done, bracket):
        try:
            point = critical_parameter(func, br, atol=atol, derivative=deriv, verify_result=verify_result,
                                       max_evaluations=max_evaluations, modal_options=modal_options)
        except BracketError as exc:
            spent += 2 if exc.verdicts else 0
            calls += 2 if exc.verdicts else 0
            last = exc
            if origin == "given":
                raise BracketError(f"at p1 = {p1!r}: {exc}", exc.bracket, exc.verdicts) from exc
            continue
        if spent:
            point = replace(point, evaluations=point.evaluations + spent, function_calls=point.function_calls + calls,
                            notes=point.notes + (f"{spent // 2} predicted bracket(s) missed the boundary",))
        return point
    raise last  # pragma: no cover - the caller's bracket is always tried last
