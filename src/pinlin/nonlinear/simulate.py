"""The nonlinear reference: Pinocchio forward dynamics of a scene, integrated on its manifold.

The linearized equations (SPEC section 1) describe small deviations from an
equilibrium or steady motion; :func:`simulate` integrates the full nonlinear
equations of the same scene so that the linearization can be validated against
them (issue 5, parts 4 and 5).
"""

from __future__ import annotations

import time

import numpy as np
import pinocchio as pin
import scipy.linalg
from scipy.integrate import solve_ivp

from ..linearization.assembly import external_forces
from ..linearization.workspace import Evaluation, workspace
from ..errors import ConfigurationError, IntegrationError, ParameterError
from ..model.scene import Scene
from ..response._array import ResponseArray
from ..response._inputs import check_times, check_tolerance

__all__ = ["Simulation", "simulate", "linear_coordinates", "EXPLICIT_METHODS", "IMPLICIT_METHODS"]

#: ``solve_ivp`` methods for non-stiff scenes (explicit Runge-Kutta).
EXPLICIT_METHODS = ("DOP853", "RK45", "RK23")
#: ``solve_ivp`` methods for stiff scenes (implicit; Jacobian by finite differences).
IMPLICIT_METHODS = ("Radau", "BDF", "LSODA")

#: Lie groups whose ``integrate`` is a plain sum in the tangent coordinates
#: (d integrate / d v = I): a single chart covers all of them.
_FLAT_GROUPS = ("R^", "SO(2)")


class _NonFinite(Exception):
    """Raised inside the right-hand side when the state or the dynamics stop being finite."""

    def __init__(self, t: float):
        super().__init__(t)
        self.t = t


class Simulation(ResponseArray):
    """A nonlinear trajectory of a scene: the (len(t), nq) array of configurations, with its figures.

    The array itself holds the configurations (SPEC section 9: ``simulate``
    returns (len(t), nq)); the rest are attributes.

    Attributes
    ----------
    q : (len(t), nq) ndarray
        The configurations as a plain array (full Pinocchio configurations,
        prescribed joints included, normalized).
    v : (len(t), nv) ndarray
        Velocities in Pinocchio's tangent space (prescribed joints at their velocity).
    t : (len(t),) ndarray
        Times [s].
    scene : Scene
    method : str
        The ``solve_ivp`` method.
    rtol, atol : float
        Its tolerances (atol in the units of the tangent coordinates and velocities).
    nfev, njev, nlu : int
        Right-hand side evaluations, Jacobian evaluations, LU decompositions
        (summed over all charts).
    charts : int
        Number of local charts used (1 + re-centrings, see :func:`simulate`).
    elapsed : float
        Seconds.
    message : str
        The solver's last status message.
    """

    _fields = ("v", "t", "scene", "method", "rtol", "atol", "nfev", "njev", "nlu", "charts", "elapsed", "message")

    @property
    def q(self) -> np.ndarray:
        return np.asarray(self).view(np.ndarray)

    def linear_coordinates(self, q_op) -> tuple[np.ndarray, np.ndarray]:
        """This trajectory in the coordinates of the linearized system at ``q_op``.

        See :func:`linear_coordinates`; returns (x, xdot), each (len(t), n).
        """
        return linear_coordinates(self.scene, q_op, self.q, self.v)

    def _summary(self) -> list[str]:
        return [
            f"t=[{self.t[0]:g}, {self.t[-1]:g}] s",
            f"method={self.method!r}",
            f"rtol={self.rtol:g}",
            f"nfev={self.nfev}",
            f"charts={self.charts}",
            f"elapsed={self.elapsed * 1e3:.1f} ms",
        ]


def _chart_groups(model: pin.Model) -> list[np.ndarray]:
    """Tangent indices whose size limits a chart: the rotation part of each SO(3), SE(3), SE(2) joint.

    Joints of other curved groups contribute all their tangent indices.  Flat
    groups (R^n, SO(2)) have a global chart and contribute nothing.
    """
    groups: list[np.ndarray] = []
    for jid in range(1, model.njoints):
        joint = model.joints[jid]
        name = joint.lieGroup().name
        if name.startswith(_FLAT_GROUPS):
            continue
        start = joint.idx_v
        if name == "SE(3)":
            groups.append(np.arange(start + 3, start + 6))
        elif name == "SE(2)":
            groups.append(np.array([start + 2]))
        else:
            groups.append(np.arange(start, start + joint.nv))
    return groups


class _Dynamics:
    """Free accelerations a_f(q, v) of a scene: M_ff a_f = Q_f - h_f, prescribed accelerations zero."""

    def __init__(self, scene: Scene):
        self.scene = scene
        self.model = scene.model
        self.ws = workspace(scene)  # this call's thread owns it for the whole integration
        self.data = self.ws.data
        self.free = scene.free_dofs
        self.prescribed = bool(scene.prescribed)
        self.zero = np.zeros(self.model.nv)

    def acceleration(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        model, data = self.model, self.data
        ev = Evaluation(self.scene, q, v, self.ws)
        fext = external_forces(self.scene, ev)
        Q = np.zeros(model.nv)
        for group in self.scene.groups:  # joint-space elements, vectorized by class
            group.add_force(ev, Q)
        extra = () if fext is None else (fext,)
        if not self.prescribed:
            return np.array(pin.aba(model, data, q, v, Q, *extra))
        # Prescribed joints move at constant velocity (zero acceleration): the actuator
        # holding them supplies whatever torque that takes, so only the free rows count.
        h = np.array(pin.rnea(model, data, q, v, self.zero, *extra))
        f = self.free
        M = ev.mass_matrix()[np.ix_(f, f)]
        return scipy.linalg.cho_solve(scipy.linalg.cho_factor(M), Q[f] - h[f])


def _initial_velocity(scene: Scene, v0) -> np.ndarray:
    nv, n = scene.model.nv, scene.n
    v = np.array(scene.v0, dtype=float)
    if v0 is None:
        return v
    try:
        arr = np.array(v0, dtype=float)
    except (TypeError, ValueError):
        raise ConfigurationError(f"v0 must be an array of numbers, got {v0!r:.80}") from None
    if arr.shape == (nv,):
        if not np.all(np.isfinite(arr)):
            raise ConfigurationError(f"v0 has non-finite entries: {arr}")
        for name, omega in scene.prescribed.items():
            i = scene.robot.joint(name).idx_v
            if arr[i] != omega:
                raise ConfigurationError(
                    f"v0[{i}] = {arr[i]!r} for prescribed joint {name!r}, but the scene prescribes "
                    f"{omega!r}; give the full velocity with the prescribed values, or only the {n} free velocities"
                )
        return arr
    if arr.shape == (n,):
        if not np.all(np.isfinite(arr)):
            raise ConfigurationError(f"v0 has non-finite entries: {arr}")
        v[scene.free_dofs] = arr
        return v
    sizes = f"nv = {nv}" if n == nv else f"nv = {nv} (all joints) or n = {n} (free joints)"
    raise ConfigurationError(f"v0 has shape {arr.shape}; scene needs a velocity of size {sizes}")


def simulate(
    scene: Scene,
    q0,
    v0=None,
    t=None,
    *,
    method: str = "DOP853",
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_step: float = np.inf,
    chart_radius: float = 1.0,
) -> Simulation:
    """Integrate the nonlinear equations of motion of a scene (issue 5 part 4; SPEC sections 1-2).

    The free coordinates obey

    .. math::
        M_{ff}(q)\\, a_f = Q_{e,f}(q, v) - h_f(q, v), \\qquad
        h = \\mathrm{rnea}(q, v, 0, f_{ext})

    with every scene element: joint springs, dampers and Rayleigh damping
    through their generalized forces Q_e, follower and dead wrenches through
    Pinocchio's ``fext`` (:func:`pinlin.assembly.external_forces`), gravity in
    the scene's model.  Prescribed joints keep their constant velocity (their
    acceleration is zero; the torque that takes is not computed).  Without
    prescribed joints the accelerations come from ``aba`` directly.

    The configuration lives on Pinocchio's manifold (nq != nv for continuous,
    spherical and free-flyer joints).  The state integrated is (dq, v_f) in a
    local chart q = ``pin.integrate(q_b, dq)`` around a base point q_b, with

    .. math::  \\dot{dq} = \\left(\\partial\\, \\mathrm{integrate}(q_b, dq) / \\partial dq\\right)^{-1} v

    (the identity for revolute, prismatic and continuous joints, whose chart is
    global).  When the rotation part of dq on a spherical, free-flyer or planar
    joint exceeds ``chart_radius``, integration stops (a ``solve_ivp`` event),
    the base point moves to the current configuration and integration restarts.

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

    Returns
    -------
    Simulation
        The (len(t), nq) array of configurations (also ``.q``), with ``.v``
        (len(t), nv), ``.t``, solver statistics and elapsed time as attributes.

    Raises
    ------
    ConfigurationError
        q0 or v0 of the wrong size or not finite; v0 contradicting a prescribed velocity.
    ParameterError
        Bad time grid (not 1-D, non-finite, not strictly increasing), unknown
        method, non-positive tolerances.
    IntegrationError
        The solver failed or the state became non-finite (``t_reached`` says where).
    """
    t_start = time.perf_counter()
    if not isinstance(scene, Scene):
        raise ParameterError("scene", f"expected a pinlin.Scene, got {type(scene).__name__}")
    if t is None:
        raise ParameterError("t", "the output times are required")
    times = check_times(t)
    q_init = scene.check_configuration(q0, "q0")
    v_init = _initial_velocity(scene, v0)
    if method not in EXPLICIT_METHODS + IMPLICIT_METHODS:
        raise ParameterError(
            "method", f"unknown method {method!r}; explicit: {EXPLICIT_METHODS}, implicit (stiff): {IMPLICIT_METHODS}"
        )
    rtol = check_tolerance(rtol, "rtol")
    atol = check_tolerance(atol, "atol")
    max_step = float(max_step)
    if not max_step > 0:
        raise ParameterError("max_step", f"must be positive, got {max_step!r}")
    chart_radius = check_tolerance(chart_radius, "chart_radius")
    if chart_radius > 3.0:
        raise ParameterError("chart_radius", f"must be at most 3 rad (charts are singular at pi), got {chart_radius!r}")

    model = scene.model
    nv = model.nv
    free = scene.free_dofs
    dyn = _Dynamics(scene)
    groups = _chart_groups(model)
    v_full = v_init.copy()

    q_out = np.empty((len(times), model.nq))
    v_out = np.empty((len(times), nv))
    q_out[0], v_out[0] = q_init, v_init
    stats = {"nfev": 0, "njev": 0, "nlu": 0}
    charts = 1
    message = "a single time point: nothing to integrate"

    if len(times) > 1:
        q_base = q_init
        y = np.concatenate([np.zeros(nv), v_init[free]])
        t_now = times[0]
        done = 1  # output rows filled

        def rhs(tt, yy):
            q = pin.integrate(model, q_base, yy[:nv])
            v_full[free] = yy[nv:]
            if groups:
                J = pin.dIntegrate(model, q_base, yy[:nv], pin.ArgumentPosition.ARG1)
                dq = np.linalg.solve(J, v_full)
            else:
                dq = v_full.copy()
            a = dyn.acceleration(q, v_full)
            out = np.concatenate([dq, a])
            if not np.all(np.isfinite(out)):
                raise _NonFinite(tt)
            return out

        events = None
        if groups:

            def leave_chart(tt, yy):
                return chart_radius - max(float(np.linalg.norm(yy[g])) for g in groups)

            leave_chart.terminal = True
            leave_chart.direction = -1
            events = leave_chart

        while done < len(times):
            try:
                sol = solve_ivp(
                    rhs,
                    (t_now, times[-1]),
                    y,
                    method=method,
                    t_eval=times[done:],
                    rtol=rtol,
                    atol=atol,
                    max_step=max_step,
                    events=events,
                )
            except _NonFinite as exc:
                raise IntegrationError(
                    f"simulate: the state or the accelerations became non-finite at t = {exc.t:.6g} s "
                    f"(the motion diverged, or the mass matrix became singular)",
                    t_reached=exc.t,
                ) from None
            for key in stats:
                stats[key] += int(getattr(sol, key))
            message = sol.message
            if sol.status == -1:
                raise IntegrationError(
                    f"simulate: solve_ivp ({method}) failed at t = {sol.t[-1] if sol.t.size else t_now:.6g} s: "
                    f"{sol.message}; try method='Radau' for a stiff scene or looser tolerances",
                    t_reached=float(sol.t[-1]) if sol.t.size else float(t_now),
                )
            k = sol.t.size
            for i in range(k):
                q_out[done + i] = pin.integrate(model, q_base, sol.y[:nv, i])
                v_out[done + i] = v_init
                v_out[done + i, free] = sol.y[nv:, i]
            done += k
            if sol.status == 1 and done < len(times):
                # Left the chart: re-centre at the event point and continue.
                y_event = sol.y_events[0][0]
                t_now = float(sol.t_events[0][0])
                q_base = pin.integrate(model, q_base, y_event[:nv])
                y = np.concatenate([np.zeros(nv), y_event[nv:]])
                charts += 1
                if t_now >= times[done]:  # pragma: no cover (event exactly on an output time)
                    q_out[done] = q_base
                    v_out[done] = v_init
                    v_out[done, free] = y[nv:]
                    done += 1
            elif done < len(times):  # pragma: no cover (solve_ivp contract)
                raise IntegrationError(f"simulate: solve_ivp stopped early: {sol.message}", t_reached=float(sol.t[-1]))

    return Simulation(
        q_out,
        scene=scene,
        t=times,
        v=v_out,
        method=method,
        rtol=rtol,
        atol=atol,
        nfev=stats["nfev"],
        njev=stats["njev"],
        nlu=stats["nlu"],
        charts=charts,
        elapsed=time.perf_counter() - t_start,
        message=message,
    )


def linear_coordinates(scene: Scene, q_op, q, v=None) -> tuple[np.ndarray, np.ndarray]:
    """Nonlinear configurations as coordinates x of the linearized system at ``q_op``.

    .. math::
        x = \\mathrm{difference}(q_{op}, q)_f, \\qquad
        \\dot x = \\left(\\partial\\, \\mathrm{difference}(q_{op}, q) / \\partial q\\; v\\right)_f

    restricted to the free coordinates f (the tangent-space coordinates in
    which :func:`pinlin.linearize` differentiates, SPEC section 1).  Pinocchio's
    ``difference`` acts joint by joint, so the advancing angle of a prescribed
    joint does not enter: for a steady motion x is the deviation from it.
    xdot is the exact time derivative of x (not just v_f, which differs from
    it at second order on curved joints).

    Parameters
    ----------
    scene : Scene
    q_op : (nq,) array
        The operating point (the configuration ``linearize`` was given).
    q : (nq,) or (len(t), nq) array
        Configurations.
    v : (nv,) or (len(t), nv) array, optional
        Velocities; without them xdot is None.

    Returns
    -------
    x, xdot : ndarray
        (n,) or (len(t), n) each; xdot is None when v is not given.

    Raises
    ------
    ConfigurationError
        Wrong sizes or non-finite values.
    """
    q_op = scene.check_configuration(q_op, "q_op")
    model = scene.model
    try:
        qs = np.array(q, dtype=float)
    except (TypeError, ValueError):
        raise ConfigurationError(f"q must be an array of numbers, got {q!r:.80}") from None
    single = qs.ndim == 1
    qs = np.atleast_2d(qs)
    if qs.ndim != 2 or qs.shape[1] != model.nq:
        raise ConfigurationError(f"q has shape {np.shape(q)}; expected (nq,) or (len(t), nq) with nq = {model.nq}")
    if not np.all(np.isfinite(qs)):
        raise ConfigurationError("q has non-finite entries")
    vs = None
    if v is not None:
        try:
            vs = np.atleast_2d(np.array(v, dtype=float))
        except (TypeError, ValueError):
            raise ConfigurationError(f"v must be an array of numbers, got {v!r:.80}") from None
        if vs.shape != (qs.shape[0], model.nv):
            raise ConfigurationError(f"v has shape {np.shape(v)}; expected ({qs.shape[0]}, {model.nv}) like q")
        if not np.all(np.isfinite(vs)):
            raise ConfigurationError("v has non-finite entries")
    f = scene.free_dofs
    x = np.empty((qs.shape[0], len(f)))
    xdot = None if vs is None else np.empty_like(x)
    for i, qi in enumerate(qs):
        x[i] = pin.difference(model, q_op, qi)[f]
        if vs is not None:
            J = pin.dDifference(model, q_op, qi, pin.ArgumentPosition.ARG1)
            xdot[i] = (J @ vs[i])[f]
    if single:
        return x[0], (None if xdot is None else xdot[0])
    return x, xdot
