"""Transition matrices of y' = A(t) y on a step grid refined in rounds, for coefficients that are cheap to
evaluate at many times at once (an interpolant of sampled coefficients, :mod:`.sampling`) (theory: Floquet).

The same Gauss-Legendre step and Richardson estimate as :mod:`.collocation`, by its kernel
:func:`~.gauss_step.try_steps` (each step taken whole and as two halves,
E = (P_1/2 P_1/2' - P_h) / (2^(2s) - 1), accepted when ||E||_2 <= rtol ||P||_2 and
h ||D^-1 A D||_2 <= :data:`~.collocation.MAX_STEP_NORM` at its middle node), but every pending step of a
round is taken at once: one evaluation of A at all their nodes and one stacked solve.  The first grid is uniform,
with the step the cap allows at the largest rate seen on a probe of A over the period (and no longer than
the order-based first step of :mod:`.collocation`); a rejected step is split in two for the next round.
Where evaluating A costs a Pinocchio pass, the sequential controller of :mod:`.collocation` wastes fewer
evaluations; here the evaluations are a small matrix product and the rounds save the per-step Python.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from ..errors import IntegrationBudgetError, IntegrationError
from .options import GROWTH, MAX_STEPS, MAX_TIME, RTOL, STAGES
from .collocation import MAX_STEP_NORM, Transitions, balancing, group_segments
from .gauss_step import try_steps, two_norms

__all__ = ["integrate_on_grid", "PROBES"]

#: Times per period at which A is probed for the largest rate (the first grid's step).
PROBES = 64


def _first_grid(probe, period, scaling, stages, rtol, max_step_norm) -> tuple[np.ndarray, np.ndarray]:
    """Uniform steps (starts, lengths): h ||D^-1 A D|| <= max_step_norm at the largest rate of the ``probe``
    values of A, and C_s (h ||A||)^(2s+1) <= rtol with C_s = (s!)^4 / ((2s)!^3 (2s+1)), the Gauss method's
    error constant."""
    probe = probe * scaling
    rate = max(float(two_norms(probe).max()), 1e-300)
    order = 2 * stages
    constant = math.factorial(stages) ** 4 / (math.factorial(order) ** 3 * (order + 1))
    h_error = (rtol / constant) ** (1.0 / (order + 1)) / rate
    count = max(1, math.ceil(period / min(max_step_norm / rate, h_error)))
    return np.arange(count) * (period / count), np.full(count, period / count)


def _reached(steps: list) -> float:
    """The end of the accepted steps that join up from t = 0 [s]."""
    t = 0.0
    for step in sorted(steps, key=lambda step: step.t0):
        if step.t0 > t * (1 + 1e-14) + 1e-300:
            break
        t = step.t0 + step.h
    return t


def integrate_on_grid(
    A: Callable[[np.ndarray], np.ndarray],
    period: float,
    m: int,
    *,
    rtol: float = RTOL,
    stages: int = STAGES,
    growth: float = GROWTH,
    max_steps: int = MAX_STEPS,
    max_time: float = MAX_TIME,
    max_step_norm: float = MAX_STEP_NORM,
    second_order: bool = False,
    coefficient_error: np.ndarray | None = None,
    probe: np.ndarray | None = None,
    A0: np.ndarray | None = None,
) -> Transitions:
    """Step transitions over [0, period] to a relative tolerance, grouped into well-conditioned segments.

    Parameters
    ----------
    A : callable
        times [s] (1-d array) -> (len(times), m, m) array: the first-order coefficients [1/s] at all of them.
    period : float
        T [s].
    rtol, stages, growth, max_steps, max_time, max_step_norm
        As :func:`~pinlin.periodic.collocation.integrate_transitions`.
    second_order : bool
        A has the first-order form [[0, I], [X, Y]] of a second-order system at every time.
    coefficient_error : (g, g) array or None
        Block bound on the error of A as an approximation of the true coefficients (each step carries it).
    probe : (k, m, m) array or None
        A at times spread over the period (the samples it was made from), for the first grid's step; None:
        A at :data:`PROBES` equispaced times.
    A0 : (m, m) array or None
        A(0) when the caller has it (its balancing scales the rates).

    Raises
    ------
    IntegrationBudgetError
        The next round would take the steps past ``max_steps`` (rounds are not split), or ``max_time`` spent.
    IntegrationError
        Coefficients not finite at t = 0 or at a probe, a step below 1e-12 T, or a non-finite transition.

    Examples
    --------
    >>> from pinlin.periodic.collocation_grid import integrate_on_grid
    >>> def A(times):         # Mathieu's equation at many times at once
    ...     out = np.zeros((np.size(times), 2, 2))
    ...     out[:, 0, 1], out[:, 1, 0] = 1.0, -(1.3 + 0.4 * np.cos(times))
    ...     return out
    >>> tr = integrate_on_grid(A, 2 * np.pi, 2, second_order=True)
    >>> print(len(tr.steps), tr.rejected, tr.steps[0].t0, f"{tr.steps[-1].t0 + tr.steps[-1].h:.6f}")
    7 0 0.0 6.283185
    """
    start = time.perf_counter()
    evaluations = (A0 is None) + (probe is None) * PROBES
    A0 = A(np.array([0.0]))[0] if A0 is None else A0
    if probe is None:
        probe = A(np.arange(PROBES) * period / PROBES)
    if not (np.all(np.isfinite(A0)) and np.all(np.isfinite(probe))):
        raise IntegrationError("the coefficients are not finite at t = 0 or at a probed time", 0.0)
    d, scaling = balancing(A0)
    t0, h = _first_grid(probe, period, scaling, stages, rtol, max_step_norm)
    steps, rejected = [], 0
    while t0.size:
        taken = len(steps) + rejected
        if taken + t0.size > max_steps or time.perf_counter() - start > max_time:
            budget = "max_steps" if taken + t0.size > max_steps else "max_time"
            raise IntegrationBudgetError(
                f"monodromy integration on a grid stopped after {len(steps)} accepted and {rejected} rejected "
                f"steps, with {t0.size} more needed ({budget} reached; rtol = {rtol:g})",
                _reached(steps), period, taken, time.perf_counter() - start, budget)
        if h.min() < 1e-12 * period:
            raise IntegrationError(
                f"step size {h.min():.3g} s fell below 1e-12 T at t = {t0[np.argmin(h)]:.6g} s: the coefficients "
                f"are not smooth enough (or not finite) for rtol = {rtol:g}", float(t0[np.argmin(h)]))
        trial = try_steps(A, t0, h, stages=stages, rtol=rtol, scaling=scaling, max_step_norm=max_step_norm,
                          second_order=second_order, coefficient_error=coefficient_error)
        evaluations += trial.evaluations
        steps.extend(trial.steps)
        retry = ~trial.accepted
        rejected += int(np.count_nonzero(retry))
        t0 = np.concatenate([t0[retry], t0[retry] + h[retry] / 2])
        h = np.concatenate([h[retry] / 2, h[retry] / 2])
    steps.sort(key=lambda step: step.t0)
    segments, factors = group_segments(steps, growth, d)
    return Transitions(steps, segments, factors, evaluations, rejected)
