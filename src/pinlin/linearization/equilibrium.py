"""Equilibria and steady motions: Newton on the configuration manifold (SPEC section 3)."""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg

from ..errors import ConfigurationError, ConvergenceError, ParameterError
from ..model.scene import Scene
from ..results import Result
from .assembly import assemble, fro

__all__ = [
    "EquilibriumResult",
    "find_equilibrium",
    "equilibrium_residual",
    "check_solver_parameters",
    "ARMIJO",
    "STALL_RATIO",
]

#: Armijo's sufficient-decrease constant of the line search: a step is taken when
#: ||r|| falls by at least ARMIJO * alpha of itself (the usual 1e-4 of Nocedal and
#: Wright: almost any decrease, so full Newton steps are kept near the solution).
ARMIJO = 1e-4
#: The residual has stalled when three steps reduced it by less than 1 - STALL_RATIO
#: (10 %): Newton converging would have cut it by orders of magnitude.
STALL_RATIO = 0.9


@dataclass(frozen=True, repr=False, eq=False)
class EquilibriumResult(Result):
    """An equilibrium (or steady motion) found by :func:`find_equilibrium`.

    Attributes
    ----------
    q : (nq,) ndarray
        The configuration (prescribed joints included, at their starting position).
    residual : float
        ||r(q)|| on the free coordinates [N, N m].
    relative_residual : float
        ||r|| / (||tau|| + ||Q_e|| + ||K||), see :class:`pinlin.assembly.Assembly`.
    iterations : int
        Newton steps taken.
    history : tuple of float
        ||r|| before each step and at the end.
    elapsed : float
        Seconds.
    method : str
        ``"newton"``, or ``"newton (least-squares steps at iterations [...])"`` when K
        was singular at some iterate and the minimum-norm step was taken instead.
    error : float
        The headline error figure: ``relative_residual``.
    notes : tuple of str
        Anything the solver wants the user to know (least-squares steps; for
        constraints: the assembly step, redundant equations, contacts whose force
        the ground cannot give).
    constraint_forces : tuple of ConstraintForce
        With constraints (SPEC section 10): one entry per constraint, in scene
        order, the world-axes force (``.force`` [N]) and, for a frame constraint,
        torque (``.torque`` [N m]) that the constraint applies on its frame (at the
        frame origin; the target frame receives the opposite).  Minimum-norm when
        the constraints are redundant (``redundant`` > 0).  Empty without constraints.
    contacts : tuple of ContactStatus
        One entry per contact (``PointConstraint(..., contact=True)``): normal and
        tangential force, whether the ground must pull or friction exceeds mu.
    redundant : int
        Number of redundant constraint equations, m - rank J_c.
    constraint_gap : float
        Largest distance [m] left between a constrained frame and its target.
    assembly : ClosureResult or None
        The assembly step that closed the constraints from q0 (None without constraints).

    For a scene with constraints, ``residual`` is ||r - J_c^T lambda|| and the
    relative residual divides it by ||tau|| + ||Q_e|| + ||J_c^T lambda|| + ||K - K_lambda||.
    """

    q: np.ndarray
    residual: float
    relative_residual: float
    iterations: int
    history: tuple[float, ...]
    elapsed: float
    method: str = "newton"
    notes: tuple[str, ...] = ()
    constraint_forces: tuple = ()
    contacts: tuple = ()
    redundant: int = 0
    constraint_gap: float = 0.0
    assembly: Result | None = None

    @property
    def error(self) -> float:
        """The relative residual ||r|| / (||tau|| + ||Q_e|| + ||K||)."""
        return self.relative_residual

    def __repr__(self) -> str:
        q = np.array2string(self.q, precision=6, threshold=12)
        return (
            f"EquilibriumResult(q={q}, residual={self.residual:.2e}, error={self.error:.1e}, "
            f"iterations={self.iterations}, method={self.method!r}, elapsed={self.elapsed * 1e3:.2f} ms)"
        )


def _relative(r: np.ndarray, scale: float) -> float:
    norm = fro(r)
    return norm / scale if scale > 0 else 0.0


def check_solver_parameters(tol, max_iterations, min_step) -> None:
    """Raise ParameterError unless tol > 0 is finite, max_iterations >= 0 an integer and 0 < min_step < 1."""
    if not (isinstance(tol, (int, float, np.integer, np.floating)) and 0 < tol < np.inf):
        raise ParameterError("tol", f"must be a positive number, got {tol!r}")
    if isinstance(max_iterations, bool) or not isinstance(max_iterations, (int, np.integer)) or max_iterations < 0:
        raise ParameterError("max_iterations", f"must be an integer >= 0, got {max_iterations!r}")
    if not (isinstance(min_step, (int, float, np.integer, np.floating)) and 0 < min_step < 1):
        raise ParameterError(
            "min_step", f"must be a line-search fraction in (0, 1), got {min_step!r}"
        )


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
    condition is r = J_c^T lambda (SPEC section 10), and
    :func:`find_equilibrium` reports ||r - J_c^T lambda|| as its residual.

    Raises
    ------
    ConfigurationError
        q has the wrong size or is not finite.
    """
    q = scene.check_configuration(q)
    return assemble(scene, q, stiffness=False).residual[scene.free_dofs]


def _newton_step(K: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, bool]:
    """Solve K dx = -r; least squares (minimum norm) when K is singular or nearly so.

    Returns the step and whether least squares was used (the caller reports it).
    """
    with warnings.catch_warnings():
        warnings.simplefilter("error", scipy.linalg.LinAlgWarning)
        try:
            step = scipy.linalg.solve(K, -r, check_finite=False)
            if np.all(np.isfinite(step)):
                return step, False
        except (np.linalg.LinAlgError, scipy.linalg.LinAlgWarning):
            pass
    return scipy.linalg.lstsq(K, -r, check_finite=False)[0], True


def find_equilibrium(
    scene: Scene,
    q0=None,
    *,
    tol: float = 1e-12,
    max_iterations: int = 50,
    min_step: float = 1e-10,
) -> EquilibriumResult:
    """Newton's method for r(q) = 0 on the configuration manifold (SPEC sections 3, 10).

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
    assembly step closes the constraints from q0, then Newton on (q, lambda) with
    the KKT matrix [[K - K_lambda, -J_c^T], [J_c, 0]] solves
    r(q) = J_c(q)^T lambda, Phi(q) = 0; the result carries the constraint forces.

    Parameters
    ----------
    scene : Scene
    q0 : (nq,) array, optional
        Start; default Pinocchio's neutral configuration.
    tol : float
        Stop when ||r|| / (||tau|| + ||Q_e|| + ||K||) <= tol.
    max_iterations : int
    min_step : float
        Smallest line-search fraction before giving up, in (0, 1).

    Raises
    ------
    ParameterError
        ``tol``, ``max_iterations`` or ``min_step`` is not valid.
    ConfigurationError
        q0 has the wrong size, is not finite (or has a revolute angle beyond
        :data:`~pinlin.model.scene.ANGLE_LIMIT`), or its forces overflow.
    ConvergenceError
        No convergence; ``.history`` holds the residual norms.
    AssemblyError
        (With constraints) the constraints cannot be closed from q0.
    """
    check_solver_parameters(tol, max_iterations, min_step)
    if scene.constraints:
        from .constrained_equilibrium import find_constrained_equilibrium

        return find_constrained_equilibrium(scene, q0, tol=tol, max_iterations=max_iterations, min_step=min_step)
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
        if rel <= tol:
            return _result(q, norm, rel, iteration, history, least_squares, t0)
        if iteration == max_iterations:
            break
        dx = np.zeros(model.nv)
        dx[f], lstsq = _newton_step(asm.K[np.ix_(f, f)], r)
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
        f"find_equilibrium: no convergence in {max_iterations} iterations (relative residual "
        f"{rel:.2e} > tol {tol:g})"
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
