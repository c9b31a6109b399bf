"""Equilibria of scenes with constraints: closed loops and contacts (theory: constraints).

With constraints Phi(q) = 0 (m equations, Jacobian J_c) and multipliers lambda
(the constraint forces on each constraint's frame, world axes):

.. math::
    r(q) = J_c(q)^T \\lambda,\\qquad \\Phi(q) = 0

A loop-closure step closes the constraints (:mod:`.closure`), then Newton on
(q, lambda) with the KKT matrix [[K - K_lambda, -J_c^T], [J_c, 0]] (independent
rows of J_c only, chosen by a column-pivoted QR of J_c^T), each step followed by
a re-closure onto the manifold and an Armijo line search on ||r - J_c^T lambda||
with lambda the minimum-norm multipliers at the trial point.  K_lambda =
d(J_c^T lambda)/dq is the constraint stiffness (:mod:`.constrained`).
"""

from __future__ import annotations

import math
import time

import numpy as np
import pinocchio as pin
import scipy.linalg

from ..errors import ConvergenceError
from ..errors.deprecated import renamed_keywords
from ..model.scene import Scene
from ..numerics.norms import fro
from .closure import CLOSURE_TOL, close_loops, project
from .constraint_set import (
    RANK_TOL,
    ConstraintState,
    check_motion_left,
    constrained_point,
    constraint_forces,
    constraint_notes,
    evaluate_constraints,
    relative_residual,
)
from .equilibrium_result import EquilibriumResult
from .newton import ARMIJO, MAX_ITERATIONS, MIN_STEP, RTOL, check_solver_parameters, newton_step

__all__ = ["find_constrained_equilibrium", "PROJECTION_ITERATIONS"]

#: Closure steps after each Newton step: a step of size h opens the loops
#: by O(h^2), which quadratic convergence closes in two or three.
PROJECTION_ITERATIONS = 10


def _kkt_step(Kt: np.ndarray, state: ConstraintState, g: np.ndarray) -> tuple[np.ndarray, bool]:
    """dx from [[K - K_lambda, -J_s^T], [J_s, 0]] [dx; dlambda] = [-g; -Phi_s], J_s independent rows."""
    nv, r = Kt.shape[0], state.rank
    rows = np.sort(scipy.linalg.qr(state.J.T, mode="r", pivoting=True, check_finite=False)[1][:r])
    Js = state.J[rows]
    A = np.block([[Kt, -Js.T], [Js, np.zeros((r, r))]])
    step, lstsq = newton_step(A, np.concatenate([g, state.phi[rows]]))  # solves A step = -(g, Phi_s)
    return step[:nv], lstsq


@renamed_keywords(tol="rtol")
def find_constrained_equilibrium(
    scene: Scene,
    q0=None,
    *,
    rtol: float = RTOL,
    max_iterations: int = MAX_ITERATIONS,
    min_step: float = MIN_STEP,
    closure_tol: float = CLOSURE_TOL,
    rank_tol: float = RANK_TOL,
) -> EquilibriumResult:
    """An equilibrium of a scene with constraints (theory: constraints); see the module docstring.

    Called by :func:`pinlin.find_equilibrium` for scenes with constraints.

    Parameters
    ----------
    scene : Scene
    q0 : (nq,) array, optional
        Start, which need not satisfy the constraints (the loop-closure step closes
        them and the result's notes and ``assembly`` say so); default neutral.
    rtol : float
        Stop when ||r - J_c^T lambda|| / (||tau|| + ||Q_e|| + ||J_c^T lambda|| +
        ||K - K_lambda||) <= rtol (``tol`` before 0.4, deprecated).
    max_iterations : int
    min_step : float
        Smallest line-search fraction before giving up.
    closure_tol : float
        Largest gap [m] and rotation [rad] accepted as closed.
    rank_tol : float
        Relative singular-value threshold of the rank decisions (:data:`RANK_TOL`).

    Raises
    ------
    ParameterError
        A bad tolerance, iteration count or ``min_step``.
    ConfigurationError
        q0 has the wrong size or is not finite.
    OverconstrainedError
        The constraints hold every degree of freedom (rank J_c = nv), as
        :func:`pinlin.linearize` refuses them.
    LoopClosureError
        The constraints cannot be closed from q0 (the gap in metres is attached).
    ConvergenceError
        Newton did not converge; ``.history`` holds the residual norms.
    """
    t0 = time.perf_counter()
    check_solver_parameters(rtol, max_iterations, min_step)
    closure = close_loops(scene, q0, closure_tol=closure_tol, rank_tol=rank_tol)
    q = closure.q
    state = evaluate_constraints(scene, q, rank_tol=rank_tol)
    check_motion_left(scene, state)  # as linearize does: at the closed configuration
    history: list[float] = []
    least_squares: list[int] = []
    for iteration in range(max_iterations + 1):
        lam, g, asm, Kt = constrained_point(scene, q, state, stiffness=True)
        norm = fro(g)
        history.append(norm)
        rel = relative_residual(g, state, lam, asm, Kt)
        if rel <= rtol:
            return _equilibrium_result(scene, q, state, lam, norm, rel, iteration, history, least_squares, closure, t0)
        if iteration == max_iterations:
            break
        dx, lstsq = _kkt_step(Kt, state, g)
        if lstsq:
            least_squares.append(iteration)
        alpha = 1.0
        while True:
            trial, trial_state, _, closed = project(
                scene,
                pin.integrate(scene.model, q, alpha * dx),
                tol=closure_tol,
                max_iterations=PROJECTION_ITERATIONS,
                rank_tol=rank_tol,
            )
            if closed:
                trial_norm = fro(constrained_point(scene, trial, trial_state)[1])
                if math.isfinite(trial_norm) and trial_norm <= (1 - ARMIJO * alpha) * norm:
                    q, state = trial, trial_state
                    break
            alpha /= 2
            if alpha < min_step:
                raise ConvergenceError(
                    f"find_equilibrium: the line search on the constraint manifold found no decrease of "
                    f"||r - J_c^T lambda|| at iteration {iteration} (relative residual {rel:.2e}); the scene "
                    f"may have no equilibrium near q0; residual history: {[f'{h:.2e}' for h in history]}",
                    history,
                )
    raise ConvergenceError(
        f"find_equilibrium: no convergence in {max_iterations} iteration{'s' if max_iterations != 1 else ''} on the constraint manifold "
        f"(relative residual {rel:.2e} > rtol {rtol:g}); residual history: {[f'{h:.2e}' for h in history]}",
        history,
    )


def _equilibrium_result(scene, q, state, lam, norm, rel, iteration, history, least_squares, closure, t0):
    notes, contacts = constraint_notes(scene, state, lam, all_contacts=True)
    if closure.initial_gap > closure.gap or closure.initial_rotation_gap > closure.rotation_gap:
        notes.insert(
            0,
            f"assembly step: q0 violated the constraints by {closure.initial_gap:.4g} m"
            + (f" and {closure.initial_rotation_gap:.3g} rad" if closure.initial_rotation_gap else "")
            + f"; {closure.iterations} Levenberg-Marquardt step{'s' if closure.iterations != 1 else ''} closed them to {closure.gap:.1e} m",
        )
    method = "newton-kkt (Newton on (q, lambda) with the KKT matrix, after closing the loops)"
    if least_squares:
        method += f"; least-squares steps at iterations {least_squares}"
        notes.append(
            f"the KKT matrix was singular or nearly so at iterations {least_squares}: the minimum-norm "
            f"least-squares step was taken there (the equilibrium may not be isolated)"
        )
    return EquilibriumResult(
        q,
        norm,
        rel,
        iteration,
        tuple(history),
        time.perf_counter() - t0,
        method=method,
        notes=tuple(notes),
        constraint_forces=constraint_forces(scene, lam),
        contacts=contacts,
        redundant=state.m - state.rank,
        constraint_gap=state.gaps()[0],
        closure=closure,
    )
