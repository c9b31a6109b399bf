"""Transition matrices of y' = A(t) y by Gauss-Legendre collocation with step doubling, step by step, grouped
into well-conditioned segments (theory: Floquet).

Each step is the Gauss step of :mod:`.gauss_step` (a stack of one): taken whole and as two halves, accepted
when the Richardson estimate E <= rtol ||P||_2 and h ||D^-1 A D||_2 <= :data:`MAX_STEP_NORM` (D balancing
A(0)), where the estimate is trusted; the next step's length follows the estimate (order 2 s + 1).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from ..errors import IntegrationBudgetError, IntegrationError
from .gauss_step import try_steps
from .jumps import JUMP_ULPS, EdgeWatch
from .options import GROWTH, MAX_STEPS, MAX_TIME, RTOL, STAGES

__all__ = ["Transitions", "integrate_transitions", "group_segments", "balancing", "MAX_STEP_NORM"]

#: Largest h ||D^-1 A D||_2 of a step (D balancing A(0)) (measured on Mathieu and damped cases against
#: mpmath: up to 2 the bounds of :mod:`.bounds` stay above the true error; at 2.5, with the projected
#: estimate doubled, they fell below it by up to 20 %).
MAX_STEP_NORM = 2.0


@dataclass(frozen=True)
class Transitions:
    """The period cut into steps, grouped into segments.

    Attributes
    ----------
    steps : list of Step
    segments : list of (start, stop)
        Step index ranges; segment j is steps[start:stop].
    factors : list of ndarray
        Segment transitions Phi_j = P_stop-1 ... P_start (formed within a segment only: their condition stays
        below the growth threshold).
    evaluations : int
        Calls of A(t) (rejected steps included).
    rejected : int
        Steps rejected by the error test.

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> print(len(tr.segments), tr.rejected, f"{np.linalg.det(tr.factors[0]):.10f}")     # Liouville: det = 1
    1 0 1.0000000000
    """

    steps: list = field(default_factory=list)
    segments: list = field(default_factory=list)
    factors: list = field(default_factory=list)
    evaluations: int = 0
    rejected: int = 0


def balancing(A0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(d, S) with S = d_j / d_i: the diagonal similarity D = diag(d) (powers of 2, from A(0)) that balances A,
    applied as ``A * S`` = D^-1 A D, so that the step cap sees rates (frequencies, decay rates) rather than
    the units of the coordinates.

    Examples
    --------
    >>> from pinlin.periodic.collocation import balancing
    >>> d, S = balancing(np.array([[0.0, 1.0], [-1e6, 0.0]]))      # x in m beside v in m/s at 1000 rad/s
    >>> print(d, np.linalg.norm(np.array([[0.0, 1.0], [-1e6, 0.0]]) * S, 2))
    [9.765625e-04 1.000000e+00] 1024.0
    """
    d = scipy.linalg.matrix_balance(A0, permute=False, separate=True)[1][0]
    return d, d[None, :] / d[:, None]


def _initial_step(A0: np.ndarray, period: float, stages: int, rtol: float) -> float:
    """A first step from ||A(0)||: the local error (h ||A||)^(2s+1) / (2s+1)! about rtol."""
    norm = max(float(np.linalg.norm(A0, 2)), 1e-300)
    order = 2 * stages
    h = (rtol * np.prod(np.arange(1.0, order + 2))) ** (1.0 / (order + 1)) / norm
    return float(min(period, max(h, period * 1e-6)))


def integrate_transitions(
    A: Callable[[float], np.ndarray],
    period: float,
    m: int,
    *,
    rtol: float = RTOL,
    stages: int = STAGES,
    growth: float = GROWTH,
    max_steps: int = MAX_STEPS,
    max_time: float = MAX_TIME,
    max_step_norm: float = MAX_STEP_NORM,
    breaks=(),
) -> Transitions:
    """Step transitions over [0, period] to a relative tolerance, grouped into well-conditioned segments.

    Parameters
    ----------
    A : callable
        t [s] -> (m, m) array, the first-order coefficient matrix [1/s] (validated by the caller).
    period : float
        T [s].
    rtol : float
        Accepted local error per step, relative to the step transition's 2-norm.
    stages : int
        Gauss-Legendre stages s (order 2 s).
    growth : float
        A segment closes when the condition number of its transition exceeds this (K then grows with the
        decades the multipliers span, not with the step count).
    max_steps, max_time : int, float
        Budget of accepted plus rejected steps and of wall time [s].
    max_step_norm : float
        Largest h ||D^-1 A(t_mid) D||_2 of a step (D the balancing of A(0), t_mid its middle node): the
        Richardson estimate assumes the asymptotic range.
    breaks : sequence of float
        Times in (0, period) [s] that are step boundaries: the jumps of A (:mod:`.jumps`), which no step
        may cross (its nodes would all lie on one side).  Jumps in the gap between two steps' outer nodes
        are found as the steps go (:class:`.jumps.EdgeWatch`) and become step boundaries too.

    Raises
    ------
    IntegrationBudgetError
        The budget ran out before T.
    IntegrationError
        The step size fell below 1e-12 T (non-smooth or singular coefficients).

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> print(len(tr.steps), tr.evaluations == 1 + 18 * (len(tr.steps) + tr.rejected))
    7 True
    """
    start = time.perf_counter()
    counted, seen = [0], {}

    def values(times):
        counted[0] += len(times)
        seen["times"], seen["values"] = times, np.stack([A(float(t)) for t in times])
        return seen["values"]

    A0 = values(np.array([0.0]))[0]
    d, scaling = balancing(A0)
    t, h = 0.0, _initial_step(A0 * scaling, period, stages, rtol)
    cap = max_step_norm / max(float(np.linalg.norm(A0 * scaling, 2)), 1e-300)
    steps, rejected = [], 0
    stops = sorted(float(b) for b in breaks if 0.0 < b < period) + [float(period)]
    watch = EdgeWatch(lambda t: values(np.array([t]))[0], rtol)
    while t < period * (1 - 1e-14):
        stop = next(b for b in stops if b > t)
        h = min(h, cap, stop - t)
        if len(steps) + rejected >= max_steps or time.perf_counter() - start > max_time:
            budget = "max_steps" if len(steps) + rejected >= max_steps else "max_time"
            raise IntegrationBudgetError(
                f"monodromy integration stopped at t = {t:.6g} s of T = {period:.6g} s after {len(steps)} "
                f"accepted and {rejected} rejected steps ({budget} reached; rtol = {rtol:g})",
                t, period, len(steps) + rejected, time.perf_counter() - start, budget)
        if h < 1e-12 * period:
            raise IntegrationError(
                f"step size {h:.3g} s fell below 1e-12 T at t = {t:.6g} s: the coefficients are not smooth "
                f"enough (or not finite) for rtol = {rtol:g}", t)
        trial = try_steps(values, np.array([t]), np.array([h]), stages=stages, rtol=rtol, scaling=scaling,
                          max_step_norm=max_step_norm)
        # one node: the cap is a heuristic, an SVD per node is not
        cap = max_step_norm / max(float(trial.rate[0]), 1e-300)
        if trial.accepted[0]:
            jump = watch.check(seen["times"], seen["values"])
            if jump is not None and abs(jump - t) > JUMP_ULPS * np.spacing(t):
                # a jump in the gap before this step's first node: restart at the step that holds it
                if jump < t:
                    t = steps.pop().t0
                stops = sorted(stops + [jump])
                watch.forget()
                continue
            steps.extend(trial.steps)
            t = stop if h == stop - t else t + h
        else:
            rejected += 1
            jump = watch.inside(seen["times"], seen["values"])
            if jump is not None and t < jump < stop:
                stops = sorted(stops + [jump])
                continue
            if h > 1.2 * cap:
                continue    # outside the asymptotic range the Richardson estimate is not trusted: h = cap
        h *= min(2.0, max(0.2, 0.9 * max(float(trial.ratio[0]), 1e-30) ** (-1.0 / (2 * stages + 1))))
    segments, factors = group_segments(steps, growth, d)
    return Transitions(steps, segments, factors, counted[0], rejected)


def group_segments(steps: list, growth: float, d: np.ndarray, lookahead: int = 16) -> tuple[list, list]:
    """Consecutive steps grouped so that each segment's transition has condition number <= growth
    (a single step above it makes a segment of its own), measured in the coordinates that balance A(0)
    (``d``: D^-1 P D): the condition of a transition in raw units counts the coordinates' units (a stiff
    support in m beside a velocity in m/s), not how far the multipliers' scales drift apart.  The running
    products are formed ``lookahead`` steps at a time and their conditions taken on the stack.

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> from pinlin.periodic.collocation import group_segments
    >>> segments, factors = group_segments(tr.steps, 10.0, np.ones(2))
    >>> print(segments[0][0], segments[-1][1] == len(tr.steps), all(np.linalg.cond(f) <= 10 for f in factors))
    0 True True
    """
    segments, factors = [], []
    scaling = d[None, :] / d[:, None]          # as balancing(A0) gives it
    begin = 0
    while begin < len(steps):
        products, end = [steps[begin].P], None
        k = begin + 1
        while end is None and k < len(steps):
            chunk = []
            for step in steps[k:k + lookahead]:
                chunk.append(step.P @ (chunk[-1] if chunk else products[-1]))
            over = np.flatnonzero(np.linalg.cond(np.stack(chunk) * scaling) > growth)
            if over.size:
                end = k + int(over[0])
                products.extend(chunk[:over[0]])
            else:
                products.extend(chunk)
                k += len(chunk)
        end = len(steps) if end is None else end
        segments.append((begin, end))
        factors.append(products[end - begin - 1])
        begin = end
    return segments, factors
