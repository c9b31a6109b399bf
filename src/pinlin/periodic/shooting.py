"""Periodic reference motions by shooting (theory: Floquet): :func:`periodic_orbit`.

With x = (dq_f, v_f) the free coordinates (tangent displacement from q0) and velocities, the flow over
one period is integrated with the variational equation Phi' = A(t) Phi alongside (A from
:mod:`.coefficients`: Pinocchio's RNEA derivatives at the actual acceleration), and Newton solves

.. math::
    F(s) = x(T; s) - s = 0, \\qquad J = \\Phi(T) - I

for a forced orbit (T the scene's period).  For an autonomous orbit the period is an unknown and a phase
condition f(s_0) . (s - s_0) = 0 (a Poincare section through the start s_0, f the vector field there) is
added: J = [[Phi(T) - I, f(x(T))], [f(s_0)^T, 0]], each step its minimum-norm solution (singular values
below :data:`RANK_RTOL` of the largest dropped).  A conservative scene's orbits come in one-parameter families
(the energy), which makes J singular along the family: there the condition of :mod:`.family` (the start's
energy, or a kept coordinate) borders J to a regular square system, so Newton returns the user's orbit.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from scipy.integrate import solve_ivp

from ..errors import InputError, OrbitLimitError, ParameterError, PeriodicOrbitError
from ..errors.deprecated import renamed_keywords
from ..linearization.assembly import assemble
from ..model.scene import Scene
from ..nonlinear.charts import chart_groups
from ..nonlinear.dynamics import FreeDynamics, initial_velocity
from .coefficients import evaluate_point
from .family import Family, conservative_family, return_time
from .orbit_result import PeriodicOrbit
from .period import scene_period

__all__ = ["periodic_orbit", "BACKTRACKS", "RANK_RTOL", "CONSTANT_TOL", "LIMIT_SAMPLES", "RESIDUAL_TOL",
           "FLOW_RTOL", "FLOW_ATOL", "MAX_ITERATIONS"]

#: Relative cut-off of the singular values of the Newton matrix (a conservative family's direction).
RANK_RTOL = 1e-9
#: Largest relative equilibrium residual ||r_f|| / (||tau|| + ||Q_e|| + ||K||) along the period for which
#: the free coordinates count as staying at rest (a ``constant`` orbit): Pinocchio's rounding is about
#: 1e-16 of that scale, an actual forcing many orders more.
CONSTANT_TOL = 1e-12
#: Relative residual ||x(T) - x(0)|| / max_t ||x(t) - x(0)|| at which Newton stops.
RESIDUAL_TOL = 1e-10
#: DOP853 tolerances (relative, absolute) of every flow: the state and its variational equation.
FLOW_RTOL, FLOW_ATOL = 1e-13, 1e-15
#: Newton steps allowed.
MAX_ITERATIONS = 30
#: Halvings of a Newton step tried before the shooting gives up (the residual must decrease).
BACKTRACKS = 8
#: Times per period at which the orbit is checked against the joint limits and its excursion measured.
LIMIT_SAMPLES = 256


@dataclass(frozen=True)
class _Shooting:
    """The shooting's options (validated by :func:`periodic_orbit`)."""

    residual_tol: float
    rtol: float
    atol: float
    max_iterations: int


class _Flow:
    """The ODE of the state and its variational equation; q = integrate(q0, dq) (global charts only)."""

    def __init__(self, scene: Scene, q0: np.ndarray, v0: np.ndarray):
        self.scene, self.q0, self.v_full = scene, q0, v0.copy()
        self.dyn = FreeDynamics(scene)
        self.nv, self.n = scene.model.nv, scene.n

    def rhs(self, t, y):
        nv, n = self.nv, self.n
        q = pin.integrate(self.scene.model, self.q0, y[:nv])
        v = self.v_full
        v[self.scene.free_dofs] = y[nv : nv + n]
        p = evaluate_point(self.scene, self.dyn, q, v, t)
        Phi = y[nv + n :].reshape(2 * n, 2 * n)
        out = np.concatenate([v, p.a_free, (p.first_order() @ Phi).ravel()])
        if not np.all(np.isfinite(out)):
            raise _Diverged(t)
        return out

    def field(self, t: float, s: np.ndarray) -> np.ndarray:
        """f(s) = (v_f, a_f) at time t and state s (tangent coordinates from q0)."""
        n, nv = self.n, self.nv
        dq = np.zeros(nv)
        dq[self.scene.free_dofs] = s[:n]
        q = pin.integrate(self.scene.model, self.q0, dq)
        v = self.v_full.copy()
        v[self.scene.free_dofs] = s[n:]
        a_p = self.dyn.apply_motions(t, q, v)
        a = self.dyn.acceleration(q, v, a_p)
        return np.concatenate([s[n:], a if a.shape[0] == n else a[self.scene.free_dofs]])

    def run(self, s: np.ndarray, T: float, rtol: float, atol: float, dense: bool = False):
        n, nv = self.n, self.nv
        y0 = np.zeros(nv + n + 4 * n * n)
        y0[self.scene.free_dofs] = s[:n]
        y0[nv : nv + n] = s[n:]
        y0[nv + n :] = np.eye(2 * n).ravel()
        try:
            sol = solve_ivp(self.rhs, (0.0, T), y0, method="DOP853", rtol=rtol, atol=atol, dense_output=dense)
        except (_Diverged, np.linalg.LinAlgError) as exc:
            t = exc.t if isinstance(exc, _Diverged) else float("nan")
            raise PeriodicOrbitError(f"periodic_orbit: the motion diverged (non-finite state or singular mass "
                                     f"matrix) at t = {t:.6g} s", period=T) from None
        if sol.status != 0:
            raise PeriodicOrbitError(f"periodic_orbit: solve_ivp (DOP853) failed: {sol.message}", period=T)
        yT = sol.y[:, -1]
        xT = np.concatenate([yT[self.scene.free_dofs], yT[nv : nv + n]])
        return xT, yT[nv + n :].reshape(2 * n, 2 * n), sol


class _Diverged(Exception):
    def __init__(self, t: float):
        super().__init__(t)
        self.t = t


def _excursion(sol, flow: _Flow, T: float, s: np.ndarray) -> float:
    """max_t ||x(t) - x(0)|| over :data:`LIMIT_SAMPLES` times of the dense output."""
    ts = np.linspace(0.0, T, LIMIT_SAMPLES + 1)
    Y = sol.sol(ts)
    X = np.vstack([Y[flow.scene.free_dofs], Y[flow.nv : flow.nv + flow.n]])
    return float(np.max(np.linalg.norm(X - s[:, None], axis=0)))


def _check_limits(scene: Scene, orbit: PeriodicOrbit, history) -> None:
    """Refuse an orbit whose free 1-DOF joints leave the model's finite position limits."""
    model = scene.model
    checks = []
    for name in scene.robot.joint_names:
        j = scene.robot.joint(name)
        if j.nq != 1 or j.idx_v not in set(scene.free_dofs.tolist()):
            continue
        lo, hi = float(model.lowerPositionLimit[j.idx_q]), float(model.upperPositionLimit[j.idx_q])
        if abs(lo) < 1e300 and abs(hi) < 1e300 and lo < hi:
            checks.append((name, j.idx_q, lo, hi))
    if not checks:
        return
    for t in np.linspace(0.0, orbit.period, LIMIT_SAMPLES + 1):
        q = orbit.q(t)
        for name, i, lo, hi in checks:
            if not lo <= q[i] <= hi:
                raise OrbitLimitError(
                    f"periodic_orbit: joint {name!r} reaches {q[i]:.6g} at t = {t:.6g} s, outside its limits "
                    f"[{lo:.6g}, {hi:.6g}] of the model: the periodic motion found leaves the model's range",
                    name, t, q[i], lo, hi, history, orbit.period)


def _constant_residual(scene: Scene, q0: np.ndarray, v0: np.ndarray, T: float) -> float:
    """Largest relative free residual at rest along the period (q_f, v_f held; prescribed joints moving)."""
    dyn = FreeDynamics(scene)
    worst = 0.0
    turning = [(scene.robot.joint(name).idx_v, omega) for name, omega in scene.prescribed.items()]
    for t in np.linspace(0.0, T, 33)[:-1] + 0.0123 * T:
        dq = np.zeros(scene.model.nv)
        for i, omega in turning:  # constant-speed joints advance with time
            dq[i] = omega * t
        q, v = pin.integrate(scene.model, q0, dq), v0.copy()
        a_p = dyn.apply_motions(t, q, v)
        asm = assemble(scene, q, v, stiffness=True, a=a_p)
        r = float(np.linalg.norm(asm.residual[scene.free_dofs]))
        worst = max(worst, r / asm.force_scale if r else 0.0)
    return worst


def _newton_step(J: np.ndarray, F: np.ndarray, residual: float = 0.0) -> np.ndarray:
    """The minimum-norm solution of J d = -F with singular values below max(RANK_RTOL, residual) s_max
    dropped: away from the orbit a conservative family's direction has a singular value of the order of
    the residual, which no step should trust."""
    U, sv, Vt = np.linalg.svd(J)
    keep = sv > max(RANK_RTOL, residual) * sv[0]
    return -(Vt[keep].T @ ((U[:, keep].T @ F) / sv[keep]))


def _start(scene: Scene, q0, v0, period):
    """Checked (q0, v0, T, autonomous): q0 and v0 full, the prescribed motions at t = 0."""
    if not isinstance(scene, Scene):
        raise ParameterError("scene", f"expected a pinlin.Scene, got {type(scene).__name__}")
    if scene.constraints:
        raise ParameterError("scene", "periodic_orbit integrates open trees only: the scene has constraints")
    if chart_groups(scene.model):
        raise ParameterError("scene", "periodic_orbit handles revolute, prismatic and continuous joints only "
                                      "(a free-flyer, spherical or planar joint needs moving charts)")
    q = scene.check_configuration(q0, "q0")
    v = initial_velocity(scene, v0)
    FreeDynamics(scene).apply_motions(0.0, q, v)
    forced = scene_period(scene, q)
    if forced is None:
        if period is None:
            raise InputError("periodic_orbit: the scene is autonomous (nothing moves periodically): give "
                                "period=, a guess of the free oscillation's period [s]")
        T = float(period)
        if not (np.isfinite(T) and T > 0):
            raise ParameterError("period", f"expected a finite positive guess [s], got {period!r}")
        return q, v, T, True
    if period is not None:
        k = float(period) / forced
        if not (np.isfinite(k) and round(k) >= 1 and abs(k - round(k)) <= 1e-12 * k):
            raise InputError(f"periodic_orbit: period = {period!r} s is not a whole multiple of the scene's "
                                f"forcing period {forced:.12g} s: a forced scene has no periodic motion of it")
        forced *= round(k)
    return q, v, forced, False


class _Trial:
    """One flow from (s, T): its defect F = x(T) - s, relative residual, monodromy and dense output."""

    def __init__(self, flow: _Flow, s: np.ndarray, T: float, opts: _Shooting):
        self.s, self.T = s, T
        self.xT, self.Phi, self.sol = flow.run(s, T, opts.rtol, opts.atol, dense=True)
        self.F = self.xT - s
        self.scale = _excursion(self.sol, flow, T, s)
        self.residual = float(np.linalg.norm(self.F)) / self.scale if self.scale else 0.0


def _equilibrium_reached(trial: _Trial, history, tol: float) -> None:
    if not trial.scale > tol * (np.linalg.norm(trial.s) + 1.0):
        raise PeriodicOrbitError(
            f"periodic_orbit: the shooting reached an equilibrium (excursion {trial.scale:.2e}), not an orbit: "
            f"no periodic motion of a period near the guess; residuals {history}", history, trial.T)


def _step(flow: _Flow, trial: _Trial, s0, f0, autonomous: bool, family: Family | None):
    """The Newton step (ds, dT): of the family's bordered system, else the minimum-norm one."""
    n2 = trial.s.size
    J = trial.Phi - np.eye(n2)
    if not autonomous:
        return _newton_step(J, trial.F), 0.0
    fT = flow.field(trial.T, trial.xT)
    phase = f0 @ (trial.s - s0)
    if family is not None:
        return family.step(np.hstack([J, fT[:, None]]), trial.F, trial.s, f0, phase)
    J = np.block([[J, fT[:, None]], [f0[None, :], np.zeros((1, 1))]])
    d = _newton_step(J, np.concatenate([trial.F, [phase]]), trial.residual)
    return d[:n2], float(d[n2])


def _shoot(flow: _Flow, s: np.ndarray, T: float, autonomous: bool, opts: _Shooting,
           family: Family | None) -> tuple[_Trial, list, int]:
    """Newton on F(s, T) = 0 with backtracking (the step is halved, up to :data:`BACKTRACKS` times, until
    the relative residual decreases): (the converged trial, residual history, Newton steps)."""
    s0, f0 = s.copy(), flow.field(0.0, s)
    trial = _Trial(flow, s, T, opts)
    history = [trial.residual]
    for it in range(opts.max_iterations):
        if autonomous:
            _equilibrium_reached(trial, history, opts.residual_tol)
        if trial.residual <= opts.residual_tol:
            return trial, history, it
        ds, dT = _step(flow, trial, s0, f0, autonomous, family)
        for _ in range(BACKTRACKS + 1):
            if trial.T + dT > 0:
                try:
                    new = _Trial(flow, trial.s + ds, trial.T + dT, opts)
                except PeriodicOrbitError:
                    new = None
                if new is not None and new.residual < trial.residual:
                    break
            ds, dT = 0.5 * ds, 0.5 * dT
        else:
            history.append(float("nan"))
            break
        trial = new
        history.append(trial.residual)
    if autonomous:
        _equilibrium_reached(trial, history, opts.residual_tol)
    if trial.residual <= opts.residual_tol:
        return trial, history, len(history) - 1
    raise PeriodicOrbitError(
        f"periodic_orbit: the shooting did not converge to residual_tol = {opts.residual_tol:g} in {len(history) - 1} Newton "
        f"steps; relative residuals ||x(T) - x(0)|| per step: {[float(f'{h:.3e}') for h in history]} (no "
        f"periodic motion near the start, or a start too far from it)", history, trial.T)


@renamed_keywords(tol="residual_tol")
def periodic_orbit(scene: Scene, q0, v0=None, *, period: float | None = None, residual_tol: float = RESIDUAL_TOL,
                   rtol: float = FLOW_RTOL, atol: float = FLOW_ATOL, max_iterations: int = MAX_ITERATIONS,
                   constant_tol: float = CONSTANT_TOL, keep: str | None = None) -> PeriodicOrbit:
    """The T-periodic motion of a scene's free coordinates, by shooting (theory: Floquet).

    A scene driven by periodic prescribed motions (or by constant-speed joints its equations depend on)
    has the period T of :func:`~pinlin.periodic.period.scene_period`, and the orbit is the forced response
    through (q0, v0).  When the free coordinates stay at rest there (q0 an equilibrium at every time, v_f
    zero: the forcing does not reach them, like a pendulum hanging on a vertically vibrating pivot), the
    orbit is ``constant`` and no shooting is needed.  An autonomous scene needs ``period``: a guess of a
    free oscillation's period through the start (a large swing, a limit cycle), found with the period.
    A conservative autonomous scene (no damping, symmetric element stiffness, no follower wrench, held
    prescribed joints) has families of orbits: the orbit keeps the energy of (q0, v0), or with ``keep`` a
    joint's start position (``orbit.family``, ``orbit.period_derivative``: dT/dE or dT/dq_j); the guess
    is first replaced by the start's return time to the phase section (:mod:`pinlin.periodic.family`).

    Parameters
    ----------
    scene : Scene
    q0 : (nq,) array
        Start at t = 0 (full; periodically moving joints are set to their q_p(0)).
    v0 : (nv,) or (n,) array, optional
        Start velocity (default: zero on the free joints).
    period : float, optional
        Autonomous scene: the guess [s].  Forced scene: a whole multiple of the forcing period (a
        subharmonic orbit); default the forcing period.
    residual_tol : float
        :data:`RESIDUAL_TOL` (``tol`` is its deprecated spelling).
    rtol, atol : float
        :data:`FLOW_RTOL`, :data:`FLOW_ATOL`.
    max_iterations : int
        :data:`MAX_ITERATIONS`.
    constant_tol : float
        :data:`CONSTANT_TOL`.
    keep : str, optional
        A conservative scene: the free 1-DOF joint whose start position labels the orbit in its family
        (default: the energy labels it).

    Returns
    -------
    PeriodicOrbit

    Raises
    ------
    InputError
        An autonomous scene without ``period``; a period that is not a multiple of the forcing's.
    QuasiPeriodicError
        Incommensurate prescribed motions.
    PeriodicOrbitError
        The shooting did not converge (``history`` holds its residuals), diverged, reached an equilibrium
        instead of an orbit, or its period went non-positive.
    OrbitLimitError
        The orbit leaves a free joint's position limits.
    ParameterError
        Not a scene; constraints or curved joints (free-flyer, spherical, planar); a bad period guess;
        ``keep`` naming no free 1-DOF joint, or given for a forced or non-conservative scene.

    Examples
    --------
    The bundled pendulum on a vertically vibrating pivot (Kapitza): hanging, it stays at rest:

    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> print(orbit.constant, f"{orbit.period:.6f}")
    True 0.031416

    The bundled double pendulum near its first mode shape: the nonlinear mode of the start's energy:

    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> orbit = pinlin.periodic_orbit(scene, [0.1, 0.045], period=1.8)
    >>> print(orbit.family, f"{orbit.period:.3f}", orbit.period_derivative > 0, orbit.residual < 1e-10)
    energy 1.811 True True
    """
    start = time.perf_counter()
    q, v, T, autonomous = _start(scene, q0, v0, period)
    family = conservative_family(scene, q, v, keep, autonomous)
    flow = _Flow(scene, q, v)
    n = scene.n
    s = np.concatenate([np.zeros(n), v[scene.free_dofs]])
    f0 = None if family is None else flow.field(0.0, s)
    if family is not None and np.any(f0):  # the start lies on its orbit: the return time is the period
        T = return_time(flow.field, s, T, float(rtol), float(atol))
    if not autonomous and not np.any(s[n:]):
        worst = _constant_residual(scene, q, v, T)
        if worst <= constant_tol:
            return PeriodicOrbit(
                period=T, q0=q, v0=v, residual=worst, integration_error=0.0, error=worst, iterations=0,
                history=(worst,), constant=True, autonomous=False, monodromy=None,
                elapsed=time.perf_counter() - start, method=f"constant: the free coordinates stay at rest "
                f"(largest relative equilibrium residual {worst:.1e} along the period)", scene=scene, base=q,
                solution=None)
    opts = _Shooting(float(residual_tol), float(rtol), float(atol), int(max_iterations))
    trial, history, it = _shoot(flow, s, T, autonomous, opts, family)
    s, T, res, Phi = trial.s, trial.T, trial.residual, trial.Phi
    xT_loose, Phi_loose = flow.run(s, T, 10 * rtol, 10 * atol)[:2]
    integration_error = float(np.linalg.norm(trial.xT - xT_loose)) / trial.scale
    slope = (None, None) if family is None else family.slope(
        flow.field, s, T, f0, ((Phi, trial.xT), (Phi_loose, xT_loose)), res + integration_error)
    dq = np.zeros(scene.model.nv)
    dq[scene.free_dofs] = s[:n]
    v_start = v.copy()
    v_start[scene.free_dofs] = s[n:]
    solution = trial.sol.sol  # dense output of (dq, v_f, Phi); the orbit reads (dq, v_f)
    orbit = PeriodicOrbit(
        period=T, q0=pin.integrate(scene.model, q, dq), v0=v_start, residual=res,
        integration_error=integration_error, error=res + integration_error, iterations=it,
        history=tuple(history), constant=False, autonomous=autonomous, monodromy=Phi,
        elapsed=time.perf_counter() - start,
        method=f"shooting: Newton on x(T) - x(0) with the monodromy from the variational equation (DOP853, "
        f"rtol={rtol:g}, atol={atol:g}){'; period unknown, Poincare phase condition' if autonomous else ''}"
        f"{f'; {family.name} kept (bordered Newton)' if family is not None else ''}",
        scene=scene, base=q, solution=solution, family=None if family is None else family.name,
        family_value=None if family is None else family.label, period_derivative=slope[0],
        period_derivative_error=slope[1])
    _check_limits(scene, orbit, history)
    return orbit

