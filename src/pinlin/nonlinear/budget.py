"""The budget of one integration: solver steps and wall time, checked at every step, so that a
run that would take hours stops early with what it reached.

``solve_ivp`` runs until it reaches the last output time, however long that
takes: ``simulate(scene, q0, v0, [0, 1e9])`` on a double pendulum would need
about 4e10 steps.  Every integration pinlin runs therefore carries a
:class:`Budget`.  The solver class is wrapped (:func:`budgeted_solver`) so that
each accepted step is counted and the budget checked before the next one:

- the step count against ``max_steps`` and the wall time against ``max_time``;
- after :data:`PROJECTION_MIN_STEPS` steps, the projection of both to the end
  of the interval at the rate so far: a run that would need more than
  :data:`PROJECTION_FACTOR` times its budget stops at once instead of spending
  the whole budget first.

Either way :class:`~pinlin.errors.IntegrationBudgetError` says how far the run
got (time reached, steps, seconds) and what the limit was.
"""

from __future__ import annotations

import time

from scipy.integrate import BDF, DOP853, LSODA, RK23, RK45, Radau

from ..errors import IntegrationBudgetError

__all__ = ["Budget", "budgeted_solver", "SOLVERS", "PROJECTION_MIN_STEPS", "PROJECTION_FACTOR"]

#: The ``solve_ivp`` methods by name (the classes scipy itself maps the names to).
SOLVERS = {"DOP853": DOP853, "RK45": RK45, "RK23": RK23, "Radau": Radau, "BDF": BDF, "LSODA": LSODA}

#: Steps after which the projection to the end of the interval is trusted: the solvers' step-size
#: control settles within a few tens of steps from its initial guess, and by then the rate also
#: averages over several periods of the fastest motion that sets the step.
PROJECTION_MIN_STEPS = 1000
#: A run stops early only when its projected steps or seconds exceed the budget by this factor:
#: step sizes vary along a trajectory (a transient first, a slow drift later), and within a factor
#: of 10 the run is allowed to try, so a projection never refuses a run that would have fitted.
PROJECTION_FACTOR = 10.0


class Budget:
    """Steps and wall time of one integration from ``t_start`` to ``t_end``, checked at each step.

    Parameters
    ----------
    t_start, t_end : float
        The interval [s] to integrate.
    max_steps : int or None
        Most solver steps (accepted steps, summed over re-centred charts); None: no limit.
    max_time : float or None
        Most wall time [s]; None: no limit.
    what : str
        Which run this is, for the message (``"simulate"``, ``"the comparison run"``).

    Examples
    --------
    >>> from pinlin.nonlinear.budget import Budget
    >>> budget = Budget(0.0, 1.0, max_steps=2, max_time=None, what="demo")
    >>> budget.step(0.0); budget.step(0.1)
    >>> try:
    ...     budget.step(0.2)
    ... except pinlin.IntegrationBudgetError as exc:
    ...     print(exc.budget, exc.steps, exc.t_reached)
    max_steps 2 0.2
    """

    def __init__(self, t_start: float, t_end: float, max_steps: int | None, max_time: float | None, what: str):
        self.t_start, self.t_end = float(t_start), float(t_end)
        self.max_steps, self.max_time = max_steps, max_time
        self.what = what
        self.steps = 0
        self.started = time.perf_counter()

    def step(self, t: float) -> None:
        """Check the budget before a step that starts at ``t`` [s], then count that step.

        Raises
        ------
        IntegrationBudgetError
            ``max_steps`` or ``max_time`` reached, or projected to be exceeded by
            more than :data:`PROJECTION_FACTOR`.
        """
        elapsed = time.perf_counter() - self.started
        if self.max_steps is not None and self.steps >= self.max_steps:
            self._fail(t, elapsed, "max_steps", f"{self.max_steps} steps used up")
        if self.max_time is not None and elapsed > self.max_time:
            self._fail(t, elapsed, "max_time", f"max_time = {self.max_time:g} s used up")
        self._project(t, elapsed)
        self.steps += 1

    def _project(self, t: float, elapsed: float) -> None:
        """Stop now when the rate so far needs far more than the budget to reach ``t_end``."""
        done = t - self.t_start
        if self.steps < PROJECTION_MIN_STEPS or done <= 0:
            return
        share = (self.t_end - self.t_start) / done  # the whole interval over the part done
        if self.max_steps is not None and self.steps * share > PROJECTION_FACTOR * self.max_steps:
            self._fail(
                t, elapsed, "max_steps",
                f"at the rate so far reaching t = {self.t_end:g} s needs about {self.steps * share:.2g} steps, "
                f"more than {PROJECTION_FACTOR:g} x max_steps = {self.max_steps}",
            )
        if self.max_time is not None and elapsed * share > PROJECTION_FACTOR * self.max_time:
            self._fail(
                t, elapsed, "max_time",
                f"at the rate so far reaching t = {self.t_end:g} s needs about {elapsed * share:.2g} s, "
                f"more than {PROJECTION_FACTOR:g} x max_time = {self.max_time:g} s",
            )

    def _fail(self, t: float, elapsed: float, budget: str, why: str) -> None:
        span = self.t_end - self.t_start
        share = 100.0 * (t - self.t_start) / span if span > 0 else 100.0
        raise IntegrationBudgetError(
            f"{self.what}: stopped at its budget: {why}; it reached t = {t:.6g} s of [{self.t_start:g}, "
            f"{self.t_end:g}] s ({share:.3g} %) in {self.steps} steps and {elapsed:.3g} s; shorten t, loosen "
            f"rtol, or raise {budget} (None: no limit)",
            t_reached=t, t_end=self.t_end, steps=self.steps, elapsed=elapsed, budget=budget,
        )


def budgeted_solver(name: str, budget: Budget) -> type:
    """The ``solve_ivp`` solver class ``name``, counting each step against ``budget`` before taking it.

    ``solve_ivp`` accepts an ``OdeSolver`` subclass as its ``method``; this one
    only adds the check in front of the solver's own step.

    Examples
    --------
    >>> from pinlin.nonlinear.budget import Budget, budgeted_solver
    >>> budgeted_solver("RK45", Budget(0.0, 1.0, 100, None, "demo")).__name__
    'BudgetedRK45'
    """
    base = SOLVERS[name]

    class Budgeted(base):
        def _step_impl(self):
            budget.step(self.t)
            return super()._step_impl()

    Budgeted.__name__ = Budgeted.__qualname__ = f"Budgeted{name}"
    return Budgeted
