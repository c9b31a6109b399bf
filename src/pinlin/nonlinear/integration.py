"""One integration of a scene's nonlinear equations with ``solve_ivp``, across local charts.

The state is y = (dq, v_f): the chart coordinates of the configuration
(:class:`~pinlin.nonlinear.charts.Chart`) and the free velocities.  A terminal
event stops the solver when dq leaves the chart; the chart is re-centred at
the event point and the solver restarts from there, until the last output time.
Every step of the run, across charts, counts against one
:class:`~pinlin.nonlinear.budget.Budget`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import IntegrationError
from ..model.scene import Scene
from .budget import Budget, budgeted_solver
from .charts import Chart, chart_groups
from .dynamics import FreeDynamics

__all__ = ["Settings", "Trajectory", "integrate"]


@dataclass(frozen=True)
class Settings:
    """The integrator and its options (checked by :func:`pinlin.simulate`).

    Examples
    --------
    >>> from pinlin.nonlinear.integration import Settings
    >>> Settings("DOP853", rtol=1e-10, atol=1e-12, max_step=np.inf, chart_radius=1.0, max_steps=None,
    ...          max_time=None).method
    'DOP853'
    """

    method: str
    rtol: float
    atol: float
    max_step: float
    chart_radius: float
    max_steps: int | None
    max_time: float | None


@dataclass
class Trajectory:
    """What one integration produced: configurations, velocities and the solver's statistics.

    Examples
    --------
    >>> from pinlin.nonlinear.integration import Trajectory
    >>> Trajectory(q=np.zeros((1, 2)), v=np.zeros((1, 2))).message
    'a single time point: nothing to integrate'
    """

    q: np.ndarray
    v: np.ndarray
    nfev: int = 0
    njev: int = 0
    nlu: int = 0
    steps: int = 0
    charts: int = 1
    message: str = "a single time point: nothing to integrate"


class _NonFinite(Exception):
    """Raised inside the right-hand side when the state or the dynamics stop being finite."""

    def __init__(self, t: float):
        super().__init__(t)
        self.t = t


class _Problem:
    """The ODE in the current chart: right-hand side and chart-leaving event."""

    def __init__(self, scene: Scene, v_init: np.ndarray, chart: Chart, radius: float):
        self.dyn = FreeDynamics(scene)
        self.free = scene.free_dofs
        self.nv = scene.model.nv
        self.v_full = v_init.copy()  # prescribed entries stay at their velocity
        self.chart = chart
        self.radius = radius

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        dq = y[: self.nv]
        self.v_full[self.free] = y[self.nv :]
        q = self.chart.configuration(dq)
        a_p = self.dyn.apply_motions(t, q, self.v_full)
        out = np.concatenate(
            [self.chart.coordinate_rate(dq, self.v_full), self.dyn.acceleration(q, self.v_full, a_p)]
        )
        if not np.all(np.isfinite(out)):
            raise _NonFinite(t)
        return out

    def events(self):
        if not self.chart.groups:
            return None

        def leave_chart(t, y):
            return self.radius - self.chart.size(y[: self.nv])

        leave_chart.terminal = True
        leave_chart.direction = -1
        return leave_chart


def _solve(problem: _Problem, t0: float, y: np.ndarray, times: np.ndarray, settings: Settings, solver: type):
    """One ``solve_ivp`` call from (t0, y) towards ``times[-1]``, its failures as IntegrationError."""
    try:
        sol = solve_ivp(
            problem.rhs,
            (t0, times[-1]),
            y,
            method=solver,
            t_eval=times,
            rtol=settings.rtol,
            atol=settings.atol,
            max_step=settings.max_step,
            events=problem.events(),
        )
    except _NonFinite as exc:
        raise IntegrationError(
            f"simulate: the state or the accelerations became non-finite at t = {exc.t:.6g} s "
            f"(the motion diverged, or the mass matrix became singular)",
            t_reached=exc.t,
        ) from None
    if sol.status == -1:
        reached = float(sol.t[-1]) if sol.t.size else float(t0)
        raise IntegrationError(
            f"simulate: solve_ivp ({settings.method}) failed at t = {reached:.6g} s: {sol.message}; "
            f"try method='Radau' for a stiff scene or looser tolerances",
            t_reached=reached,
        )
    return sol


def integrate(
    scene: Scene,
    q_init: np.ndarray,
    v_init: np.ndarray,
    times: np.ndarray,
    settings: Settings,
    what: str = "simulate",
) -> Trajectory:
    """Integrate from (q_init, v_init) at ``times[0]``; outputs at every entry of ``times``.

    ``what`` names the run in the messages of its errors.

    Raises
    ------
    IntegrationBudgetError
        The run used up ``settings.max_steps`` or ``settings.max_time``, or would
        clearly exceed them (see :class:`~pinlin.nonlinear.budget.Budget`).
    IntegrationError
        The solver failed or the state became non-finite (``t_reached`` says where).

    Examples
    --------
    >>> from pinlin.nonlinear.integration import Settings, integrate
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> settings = Settings("DOP853", 1e-10, 1e-12, np.inf, 1.0, max_steps=10_000, max_time=None)
    >>> run = integrate(scene, np.array([0.1, 0.0]), np.zeros(2), np.linspace(0.0, 1.0, 5), settings)
    >>> np.round(run.q[:, 0], 6), run.charts
    (array([ 0.1     ,  0.052513, -0.016845, -0.069088, -0.094171]), 1)
    """
    budget = Budget(times[0], times[-1], settings.max_steps, settings.max_time, what)
    solver = budgeted_solver(settings.method, budget)
    model, free, nv = scene.model, scene.free_dofs, scene.model.nv
    out = Trajectory(np.empty((len(times), model.nq)), np.empty((len(times), nv)))
    out.q[0], out.v[0] = q_init, v_init
    problem = _Problem(scene, v_init, Chart(model, q_init, chart_groups(model)), settings.chart_radius)
    y = np.concatenate([np.zeros(nv), v_init[free]])
    t_now, done = times[0], 1  # done: output rows filled

    def store(row: int, dq: np.ndarray, v_free: np.ndarray) -> None:
        out.q[row] = problem.chart.configuration(dq)
        out.v[row] = v_init
        out.v[row, free] = v_free
        problem.dyn.apply_motions(times[row], out.q[row], out.v[row])  # the prescribed motions exactly

    while done < len(times):
        sol = _solve(problem, t_now, y, times[done:], settings, solver)
        out.nfev, out.njev, out.nlu = out.nfev + sol.nfev, out.njev + sol.njev, out.nlu + sol.nlu
        out.message = sol.message
        for i in range(sol.t.size):
            store(done + i, sol.y[:nv, i], sol.y[nv:, i])
        done += sol.t.size
        if done == len(times):
            break
        if sol.status != 1:  # pragma: no cover (solve_ivp contract: it stops early only at an event)
            raise IntegrationError(
                f"simulate: solve_ivp stopped early: {sol.message}", t_reached=float(sol.t[-1])
            )
        # Left the chart: re-centre at the event point and continue.
        y_event = sol.y_events[0][0]
        t_now = float(sol.t_events[0][0])
        problem.chart = problem.chart.recentred(y_event[:nv])
        y = np.concatenate([np.zeros(nv), y_event[nv:]])
        out.charts += 1
        if t_now >= times[done]:  # pragma: no cover (event exactly on an output time)
            store(done, y[:nv], y[nv:])
            done += 1
    out.steps = budget.steps
    return out
