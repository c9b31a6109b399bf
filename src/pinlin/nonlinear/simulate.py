"""``simulate``: the nonlinear reference, Pinocchio forward dynamics of a scene integrated on its manifold.

The linearized equations (theory: equations) describe small deviations from an
equilibrium or steady motion; :func:`simulate` integrates the full nonlinear
equations of the same scene so that the linearization can be validated against
them.  The right-hand side is
:mod:`pinlin.nonlinear.dynamics`, the charts :mod:`pinlin.nonlinear.charts`, the
solver loop :mod:`pinlin.nonlinear.integration`.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np
import pinocchio as pin

from ..errors import ConstraintError, IntegrationBudgetError, IntegrationError, ParameterError
from ..model.scene import Scene
from ..numerics.arrays import check_times
from ..numerics.checks import check_integer, check_tolerance
from .charts import MAX_CHART_RADIUS
from .coordinates import linear_coordinates
from .dynamics import FreeDynamics, initial_velocity
from .integration import Settings, Trajectory, integrate
from .result import Simulation

__all__ = [
    "Simulation",
    "simulate",
    "linear_coordinates",
    "EXPLICIT_METHODS",
    "IMPLICIT_METHODS",
    "ERROR_TOL_FACTOR",
    "MIN_RTOL",
    "DEFAULT_MAX_STEPS",
    "DEFAULT_RTOL",
    "DEFAULT_ATOL",
]

#: ``solve_ivp`` methods for non-stiff scenes (explicit Runge-Kutta).
EXPLICIT_METHODS = ("DOP853", "RK45", "RK23")
#: ``solve_ivp`` methods for stiff scenes (implicit; Jacobian by finite differences).
IMPLICIT_METHODS = ("Radau", "BDF", "LSODA")

#: The comparison run behind ``Simulation.error`` uses tolerances this many times tighter: for a
#: solver whose global error is proportional to its tolerance, the difference of the two runs then
#: estimates the returned run's error to within about 1/ERROR_TOL_FACTOR of itself, and DOP853
#: (8th order) pays only 10^(1/8) = 1.33 times the steps for it.
ERROR_TOL_FACTOR = 10.0
#: Smallest rtol ``solve_ivp`` honours (it raises smaller ones to this, with a warning).
MIN_RTOL = 100 * np.finfo(float).eps
#: Default relative and absolute accuracy of the integration (``solve_ivp``'s ``rtol`` and ``atol``; atol
#: in [rad, m] and [rad/s, m/s]): a reference for linearizations that agree to ~1e-8.
DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-12
#: Default ``max_steps`` of each integration run: at the default tolerances DOP853 takes about 40
#: steps per period of the paper's double pendulum (theory: double pendulum), so this covers hours of its motion
#: in about a minute of wall time, while ``simulate(scene, q0, v0, [0, 1e9])`` stops in a second.
DEFAULT_MAX_STEPS = 100_000


def _budget(max_steps, max_time) -> tuple[int | None, float | None]:
    """The checked budget of each run: (max_steps, max_time), None for no limit."""
    if max_steps is not None:
        max_steps = check_integer(max_steps, "max_steps", low=1)
    if max_time is not None:
        max_time = check_tolerance(max_time, "max_time")
    return max_steps, max_time


def _settings(method, rtol, atol, max_step, chart_radius, estimate_error: bool, budget) -> Settings:
    """The checked integrator options."""
    if method not in EXPLICIT_METHODS + IMPLICIT_METHODS:
        raise ParameterError(
            "method",
            f"unknown method {method!r}; explicit: {EXPLICIT_METHODS}, implicit (stiff): {IMPLICIT_METHODS}",
        )
    rtol = check_tolerance(rtol, "rtol")
    atol = check_tolerance(atol, "atol")
    if rtol < MIN_RTOL:
        raise ParameterError("rtol", f"solve_ivp cannot honour rtol below {MIN_RTOL:.3g}, got {rtol:g}")
    if estimate_error and rtol / ERROR_TOL_FACTOR < MIN_RTOL:
        raise ParameterError(
            "rtol",
            f"{rtol:g} leaves no room for the error estimate's comparison run at rtol / {ERROR_TOL_FACTOR:g} "
            f"(solve_ivp's floor is {MIN_RTOL:.3g}); use rtol >= {ERROR_TOL_FACTOR * MIN_RTOL:.3g} or estimate_error=False",
        )
    try:
        max_step = float(max_step)
    except (TypeError, ValueError):
        raise ParameterError("max_step", f"expected a positive number of seconds, got {max_step!r}") from None
    if not max_step > 0:
        raise ParameterError("max_step", f"must be positive, got {max_step!r}")
    chart_radius = check_tolerance(chart_radius, "chart_radius")
    if chart_radius > MAX_CHART_RADIUS:
        raise ParameterError(
            "chart_radius",
            f"must be at most {MAX_CHART_RADIUS:g} rad (charts are singular at pi), got {chart_radius!r}",
        )
    return Settings(method, rtol, atol, max_step, chart_radius, *_budget(*budget))


def _relative(num: float, scale: float) -> float:
    return num / scale if num else 0.0


def _error_estimate(scene: Scene, run: Trajectory, reference: Trajectory, atol: float) -> tuple[float, float]:
    """(error_q, error_v): the returned run against the tighter comparison run, relative to the motion."""
    model, f = scene.model, scene.free_dofs
    gap = [pin.difference(model, qr, q)[f] for q, qr in zip(run.q, reference.q)]
    moved = [pin.difference(model, run.q[0], q)[f] for q in run.q]
    error_q = _relative(
        max(float(np.linalg.norm(d)) for d in gap), max(max(float(np.linalg.norm(d)) for d in moved), atol)
    )
    error_v = _relative(
        float(np.max(np.linalg.norm(run.v[:, f] - reference.v[:, f], axis=1))),
        max(float(np.max(np.linalg.norm(run.v[:, f], axis=1))), atol),
    )
    return error_q, error_v


def _describe(scene: Scene, s: Settings, estimate_error: bool) -> str:
    path = "aba" if not (scene.prescribed or scene.motions) else "rnea and M_ff (prescribed joints at constant velocity)"
    if scene.motions:
        path = "rnea and M_ff (prescribed joints at constant velocity or following q_p(t), v_p(t), a_p(t))"
    error = (
        f"error against a run at tolerances / {ERROR_TOL_FACTOR:g}"
        if estimate_error
        else "error not estimated (estimate_error=False)"
    )
    return (
        f"solve_ivp {s.method} (rtol={s.rtol:g}, atol={s.atol:g}, max_step={s.max_step:g} s) of {path}, "
        f"on charts of radius {s.chart_radius:g} rad; {error}"
    )


def simulate(
    scene: Scene,
    q0,
    v0=None,
    t=None,
    *,
    method: str = "DOP853",
    rtol: float = DEFAULT_RTOL,
    atol: float = DEFAULT_ATOL,
    max_step: float = np.inf,
    chart_radius: float = 1.0,
    estimate_error: bool = True,
    max_steps: int | None = DEFAULT_MAX_STEPS,
    max_time: float | None = None,
) -> Simulation:
    """Integrate the nonlinear equations of motion of a scene (theory: equations, elements).

    The free coordinates obey

    .. math::
        M_{ff}(q)\\, a_f = Q_{e,f}(q, v) - h_f(q, v), \\qquad
        h = \\mathrm{rnea}(q, v, 0, f_{ext})

    with every scene element and gravity (:mod:`pinlin.nonlinear.dynamics`).  Prescribed joints
    keep their constant velocity or follow their periodic motion exactly (their entries of q0 and v0
    are replaced by q_p(t[0]), v_p(t[0])).  The state (dq, v_f) lives in a local chart
    q = ``pin.integrate(q_b, dq)`` of the configuration manifold, re-centred when a joint's rotation
    exceeds ``chart_radius`` (:mod:`pinlin.nonlinear.charts`).  The tolerances bound local errors per
    step; ``.error`` estimates the trajectory's error by a second run at tolerances
    :data:`ERROR_TOL_FACTOR` times tighter (see :class:`Simulation`).  The run uses the calling
    thread's Pinocchio workspace, so one scene can be simulated from many threads at once.

    Parameters
    ----------
    scene : Scene
    q0 : (nq,) array
        Initial configuration (full, prescribed joints included).
    v0 : (nv,) or (n,) array, optional
        Initial velocity: the full velocity (its prescribed entries must equal
        the scene's), or only the n free velocities.  Default: the steady
        velocity (zero on the free joints).
    t : (len(t),) array
        Strictly increasing output times [s]; integration starts at t[0].
    method : str
        A ``solve_ivp`` method: one of :data:`EXPLICIT_METHODS` (default
        ``DOP853``, 8th order) or, for stiff scenes (stiffness ratios of many
        decades), one of :data:`IMPLICIT_METHODS` (``Radau``).
    rtol, atol : float
        ``solve_ivp`` tolerances; atol applies to dq [rad, m] and v [rad/s, m/s].
    max_step : float
        Largest step [s].
    chart_radius : float
        Largest rotation [rad] of a chart before re-centring, in (0, 3].
    estimate_error : bool
        Run the comparison integration behind ``.error`` (about 1.3 to 2 times
        the cost of the run itself); without it ``.error`` is NaN.
    max_steps : int or None
        Most solver steps of each run (the comparison run has its own budget),
        default :data:`DEFAULT_MAX_STEPS`; None: no limit.
    max_time : float or None
        Most wall time [s] of each run; default None (no limit, so that whether
        a run succeeds does not depend on the machine's speed).  Both limits are
        also projected: after :data:`~pinlin.nonlinear.budget.PROJECTION_MIN_STEPS`
        steps a run whose rate so far would need more than
        :data:`~pinlin.nonlinear.budget.PROJECTION_FACTOR` times its budget to
        reach ``t[-1]`` stops at once.

    Returns
    -------
    Simulation
        The (len(t), nq) array of configurations (also ``.q``), with ``.v``
        (len(t), nv), ``.t``, ``.error``, solver statistics and elapsed time as attributes.

    Raises
    ------
    ConfigurationError
        q0 or v0 of the wrong size or not finite; v0 contradicting a prescribed velocity.
    ParameterError
        Not a scene; bad time grid (not 1-D, non-finite, not strictly increasing);
        unknown method; non-positive tolerances, rtol too small for solve_ivp (or
        for the comparison run); chart_radius outside (0, 3]; max_steps not a
        positive integer, max_time not a positive number (or None).
    ConstraintError
        The scene has constraints (closed loops, contacts): not integrated yet.
    IntegrationBudgetError
        A run used up ``max_steps`` or ``max_time`` or would clearly exceed them;
        ``t_reached``, ``steps`` and ``elapsed`` say how far it got.
    IntegrationError
        The solver failed or the state became non-finite, in the run or in the
        comparison run (``t_reached`` says where).

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> sim = pinlin.simulate(pinlin.Scene(robot), [0.1, 0.0], t=np.linspace(0.0, 1.0, 5))
    >>> sim.shape, sim.integrator
    ((5, 2), 'DOP853')
    >>> np.round(sim[:, 0], 6)
    array([ 0.1     ,  0.052513, -0.016845, -0.069088, -0.094171])
    >>> bool(sim.error < 1e-8)
    True
    """
    t_start = time.perf_counter()
    if not isinstance(scene, Scene):
        raise ParameterError("scene", f"expected a pinlin.Scene, got {type(scene).__name__}")
    if scene.constraints:
        raise ConstraintError(
            f"simulate integrates open trees only: the scene has {len(scene.constraints)} constraint(s) "
            f"({', '.join(repr(c.label) for c in scene.constraints)}), "
            f"whose forces forward dynamics without them would silently drop",
            tuple(scene.constraints),
        )
    if t is None:
        raise ParameterError("t", "the output times are required")
    times = check_times(t)
    q_init = scene.check_configuration(q0, "q0")
    v_init = initial_velocity(scene, v0)
    if scene.motions:  # the periodically moving joints start where their motion is at t[0]
        FreeDynamics(scene).apply_motions(times[0], q_init, v_init)
    settings = _settings(method, rtol, atol, max_step, chart_radius, bool(estimate_error), (max_steps, max_time))
    run = integrate(scene, q_init, v_init, times, settings)
    error_q = error_v = float("nan")
    reference_nfev = 0
    if estimate_error:
        tight = replace(settings, rtol=settings.rtol / ERROR_TOL_FACTOR, atol=settings.atol / ERROR_TOL_FACTOR)
        what = (
            f"simulate, in the comparison run for the error estimate at rtol = {tight.rtol:g} "
            f"(estimate_error=False skips it)"
        )
        try:
            reference = integrate(scene, q_init, v_init, times, tight, what)
        except IntegrationBudgetError:
            raise
        except IntegrationError as exc:
            raise IntegrationError(
                f"{exc} (in the comparison run for the error estimate, at rtol = {tight.rtol:g}; "
                f"estimate_error=False skips it)",
                t_reached=exc.t_reached,
            ) from None
        error_q, error_v = _error_estimate(scene, run, reference, settings.atol)
        reference_nfev = reference.nfev
    return Simulation(
        run.q,
        scene=scene,
        t=times,
        v=run.v,
        method=_describe(scene, settings, bool(estimate_error)),
        error=max(error_q, error_v) if estimate_error else float("nan"),
        error_q=error_q,
        error_v=error_v,
        integrator=settings.method,
        rtol=settings.rtol,
        atol=settings.atol,
        max_step=settings.max_step,
        chart_radius=settings.chart_radius,
        nfev=run.nfev,
        njev=run.njev,
        nlu=run.nlu,
        steps=run.steps,
        max_steps=settings.max_steps,
        max_time=settings.max_time,
        reference_nfev=reference_nfev,
        charts=run.charts,
        elapsed=time.perf_counter() - t_start,
        message=run.message,
    )
