"""Transition matrices of y' = A(t) y on a step grid refined in rounds, for coefficients that are cheap to
evaluate at many times at once (an interpolant of sampled coefficients, :mod:`.sampling`) (theory: Floquet).

The same Gauss-Legendre step and Richardson estimate as :mod:`.collocation` (each step taken whole and as
two halves, E = (P_1/2 P_1/2' - P_h) / (2^(2s) - 1), accepted when ||E||_2 <= rtol ||P||_2 and
h ||D^-1 A D||_2 <= :data:`~.collocation.MAX_STEP_NORM` at its middle node), but every pending step of a round
is taken at once: one evaluation of A at all their nodes and one stacked solve.  The first grid is uniform,
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
from .collocation import (MAX_STEP_NORM, ROUNDING_FACTOR, Step, Transitions, balancing, gauss_legendre,
                          group_segments, stage_solve)

__all__ = ["integrate_on_grid", "PROBES"]

#: Times per period at which A is probed for the largest rate (the first grid's step).
PROBES = 64

_EPS = float(np.finfo(float).eps)


def _two_norms(X: np.ndarray) -> np.ndarray:
    return np.linalg.norm(X, 2, axis=(-2, -1))


def _first_grid(probe, period, scaling, stages, rtol, max_step_norm) -> tuple[np.ndarray, np.ndarray]:
    """Uniform steps (starts, lengths): h ||D^-1 A D|| <= max_step_norm at the largest rate of the ``probe``
    values of A, and C_s (h ||A||)^(2s+1) <= rtol with C_s = (s!)^4 / ((2s)!^3 (2s+1)), the Gauss method's
    error constant."""
    probe = probe * scaling
    rate = max(float(_two_norms(probe).max()), 1e-300)
    order = 2 * stages
    constant = math.factorial(stages) ** 4 / (math.factorial(order) ** 3 * (order + 1))
    h_error = (rtol / constant) ** (1.0 / (order + 1)) / rate
    count = max(1, math.ceil(period / min(max_step_norm / rate, h_error)))
    return np.arange(count) * (period / count), np.full(count, period / count)


def _round(A, t0, h, c, a, b, stages, second_order, scaling):
    """Whole and half steps of every pending step at once: (whole P, halves (P1, Z1), (P2, Z2), rate at the
    middle node)."""
    B = t0.size
    nodes = np.concatenate([t0[:, None] + c[None] * h[:, None],
                            t0[:, None] + c[None] * (h / 2)[:, None],
                            (t0 + h / 2)[:, None] + c[None] * (h / 2)[:, None]], axis=1)   # (B, 3 s)
    values = A(nodes.ravel())
    m = values.shape[-1]
    An = values.reshape(B * 3, stages, m, m)
    P, Z = stage_solve(An, np.stack([h, h / 2, h / 2], axis=1).ravel(), a, b, second_order)
    P, Z = P.reshape(B, 3, m, m), Z.reshape(B, 3, stages, m, m)
    middle = values.reshape(B, 3, stages, m, m)[:, 0, stages // 2] * scaling
    return P, Z, _two_norms(middle), nodes


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
    rtol: float = 1e-13,
    stages: int = 6,
    growth: float = 1e3,
    max_steps: int = 20000,
    max_time: float = 600.0,
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
    """
    start = time.perf_counter()
    c, a, b = gauss_legendre(stages)
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
        P3, Z3, rate, nodes = _round(A, t0, h, c, a, b, stages, second_order, scaling)
        evaluations += nodes.size
        whole, P1, P2 = P3[:, 0], P3[:, 1], P3[:, 2]
        P = P2 @ P1
        difference = (P - whole) / (4.0 ** stages - 1)
        estimate, norm = _two_norms(difference), _two_norms(P)
        if not np.all(np.isfinite(estimate)):
            bad = int(np.argmin(np.isfinite(estimate)))
            raise IntegrationError(f"the step transition at t = {t0[bad]:.6g} s is not finite", float(t0[bad]))
        ok = (estimate <= rtol * norm) & (h * rate <= 1.2 * max_step_norm)
        # the rounding floor with Frobenius norms of the halves (an upper bound of their 2-norms; no SVD)
        rounding = ROUNDING_FACTOR * _EPS * np.sqrt(stages * m) * (
            np.linalg.norm(P1, axis=(1, 2)) * np.linalg.norm(P2, axis=(1, 2)) + norm)
        stages_at = np.concatenate([Z3[:, 1], Z3[:, 2] @ P1[:, None]], axis=1)     # t0 -> each half's nodes
        weights = np.concatenate([b, b])[None, :] * (h / 2)[:, None]
        for k in np.flatnonzero(ok):
            steps.append(Step(float(t0[k]), float(h[k]), P[k], difference[k], float(rounding[k]),
                              float(estimate[k] + rounding[k]), nodes[k, stages:], stages_at[k], weights[k],
                              coefficient_error, float(norm[k]), float(estimate[k])))
        rejected += int(np.count_nonzero(~ok))
        t0 = np.concatenate([t0[~ok], t0[~ok] + h[~ok] / 2])
        h = np.concatenate([h[~ok] / 2, h[~ok] / 2])
    steps.sort(key=lambda step: step.t0)
    segments, factors = group_segments(steps, growth, d)
    return Transitions(steps, segments, factors, evaluations, rejected)
