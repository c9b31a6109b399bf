"""Equilibria and steady motions: Newton on the configuration manifold (theory: equilibrium)."""

from __future__ import annotations

import time

import numpy as np
import pinocchio as pin

from ..errors import ConfigurationError, ConvergenceError
from ..errors.deprecated import renamed_keywords
from ..model.scene import Scene
from ..numerics.norms import fro
from .assembly import assemble
from .constrained_equilibrium import find_constrained_equilibrium
from .equilibrium_result import EquilibriumResult
from .newton import (
    ARMIJO,
    MAX_ITERATIONS,
    MIN_STEP,
    STALL_RATIO,
    RTOL,
    check_solver_parameters,
    newton_step,
)
from .periodicity import refuse_motions

__all__ = ["find_equilibrium", "equilibrium_residual"]





def _relative(r: np.ndarray, scale: float) -> float:
    norm = fro(r)
    return norm / scale if scale > 0 else 0.0




def _check_start(scene: Scene, q: np.ndarray, r: np.ndarray) -> None:
    """Raise ConfigurationError when the residual at the start is not finite (the forces overflow)."""
    bad = np.flatnonzero(~np.isfinite(r))
    if bad.size:
        names = [scene.dof_names[i] for i in bad[:5]]
        raise ConfigurationError(
            f"q0 = {np.array2string(q, precision=4, threshold=8)} gives non-finite generalized forces on {names}: "
            f"the scene's forces overflow double precision there, so no Newton step can start; start from "
            f"a configuration of physical size"
        )


def _result(q, norm, rel, iteration, history, least_squares, t0) -> EquilibriumResult:
    method, notes = "newton", ()
    if least_squares:
        method = f"newton (least-squares steps at iterations {least_squares})"
        notes = (
            f"the stiffness K was singular or nearly so at iterations {least_squares}: the minimum-norm "
            f"least-squares step was taken there (the equilibrium may not be isolated)",
        )
    return EquilibriumResult(
        q, norm, rel, iteration, tuple(history), time.perf_counter() - t0, method=method, notes=notes
    )


def equilibrium_residual(scene: Scene, q) -> np.ndarray:
    """r(q) = tau(q, v0, 0, fext) - Q_e(q, v0) on the free coordinates (n,).

    Constraint forces are not included: with constraints, the equilibrium
    condition is r = J_c^T lambda (theory: constraints), and
    :func:`find_equilibrium` reports ||r - J_c^T lambda|| as its residual.

    Raises
    ------
    ConfigurationError
        q has the wrong size or is not finite.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0)])
    >>> pinlin.equilibrium_residual(scene, np.zeros(2))  # hanging straight down: balanced
    array([0., 0.])
    """
    q = scene.check_configuration(q)
    return assemble(scene, q, stiffness=False).residual[scene.free_dofs]




@renamed_keywords(tol="rtol")
def find_equilibrium(
    scene: Scene,
    q0=None,
    *,
    rtol: float = RTOL,
    max_iterations: int = MAX_ITERATIONS,
    min_step: float = MIN_STEP,
) -> EquilibriumResult:
    """Newton's method for r(q) = 0 on the configuration manifold (theory: equilibrium, constraints).

    Each step solves K dx = -r with the analytic stiffness K of the free
    coordinates (least squares if K is singular), then backtracks along
    ``pin.integrate(q, alpha dx)`` until ||r|| decreases (Armijo).  Prescribed
    joints stay where ``q0`` puts them.  Several equilibria may exist: the one
    found depends on the start.  The line search works on ||r||, so far from an
    equilibrium (a chain curled by several radians against its springs) it can
    stall at a local minimum of ||r|| where K is nearly singular; the error then
    says so.  Start closer, or raise the load in steps (continuation).

    A scene with constraints is solved by
    :func:`pinlin.linearization.constrained_equilibrium.find_constrained_equilibrium`: an
    loop-closure step closes the constraints from q0, then Newton on (q, lambda) with
    the KKT matrix [[K - K_lambda, -J_c^T], [J_c, 0]] solves
    r(q) = J_c(q)^T lambda, Phi(q) = 0; the result carries the constraint forces.

    Parameters
    ----------
    scene : Scene
    q0 : (nq,) array, optional
        Start; default Pinocchio's neutral configuration.
    rtol : float
        Stop when ||r|| / (||tau|| + ||Q_e|| + ||K||) <= rtol (``tol`` before 0.4, deprecated).
    max_iterations : int
    min_step : float
        Smallest line-search fraction before giving up, in (0, 1).

    Raises
    ------
    ParameterError
        ``rtol``, ``max_iterations`` or ``min_step`` is not valid.
    ConfigurationError
        q0 has the wrong size, is not finite (or has a revolute angle beyond
        :data:`~pinlin.model.scene.ANGLE_LIMIT`), or its forces overflow.
    ConvergenceError
        No convergence; ``.history`` holds the residual norms.
    LoopClosureError
        (With constraints) the constraints cannot be closed from q0.
    TimePeriodicError
        The scene has periodic prescribed motions (use :func:`pinlin.periodic_orbit`).

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0, rest=0.2)])
    >>> eq = pinlin.find_equilibrium(scene, np.zeros(2))
    >>> np.round(eq.q, 6), bool(eq.relative_residual <= 1e-12)
    (array([ 0.043987, -0.043987]), True)
    """
    check_solver_parameters(rtol, max_iterations, min_step)
    if scene.motions:  # no steady equilibrium: the periodic reference motion is pinlin.periodic_orbit's
        refuse_motions(scene)
    if scene.constraints:
        return find_constrained_equilibrium(scene, q0, rtol=rtol, max_iterations=max_iterations, min_step=min_step)
    t0 = time.perf_counter()
    q = scene.check_configuration(scene.neutral() if q0 is None else q0, "q0")
    f = scene.free_dofs
    model = scene.model
    history: list[float] = []
    least_squares: list[int] = []
    for iteration in range(max_iterations + 1):
        asm = assemble(scene, q, stiffness=True)
        r = asm.residual[f]
        norm = fro(r)
        if not iteration and not np.isfinite(norm):
            _check_start(scene, q, r)
        history.append(norm)
        rel = _relative(r, asm.force_scale)
        if rel <= rtol:
            return _result(q, norm, rel, iteration, history, least_squares, t0)
        if iteration == max_iterations:
            break
        dx = np.zeros(model.nv)
        dx[f], lstsq = newton_step(asm.K[np.ix_(f, f)], r)
        if lstsq:
            least_squares.append(iteration)
        alpha = 1.0
        while True:
            trial = pin.integrate(model, q, alpha * dx)
            r_trial = assemble(scene, trial, stiffness=False).residual[f]
            if fro(r_trial) <= (1 - ARMIJO * alpha) * norm:  # False for a non-finite trial
                q = trial
                break
            alpha /= 2
            if alpha < min_step:
                raise ConvergenceError(
                    f"find_equilibrium: the line search found no decrease of the residual at iteration "
                    f"{iteration} (||r|| = {norm:.3e}, relative {rel:.2e}); the scene may have no "
                    f"equilibrium near q0 (a floating base under gravity, a load beyond collapse); "
                    f"residual history: {[f'{h:.2e}' for h in history]}",
                    history,
                )
    stalled = len(history) > 4 and history[-1] > STALL_RATIO * history[-4]
    raise ConvergenceError(
        f"find_equilibrium: no convergence in {max_iterations} iteration{'s' if max_iterations != 1 else ''} (relative residual "
        f"{rel:.2e} > rtol {rtol:g})"
        + (
            "; the residual has stalled at a local minimum of ||r||, which Newton's line search "
            "cannot leave: start closer to the equilibrium, or raise the load in steps from a "
            "known equilibrium (continuation)"
            if stalled
            else ""
        )
        + f"; residual history: {[f'{h:.2e}' for h in history]}",
        history,
    )
