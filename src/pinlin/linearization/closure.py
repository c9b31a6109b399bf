"""Loop closure: closing a scene's loops from a configuration that violates them (theory: constraints).

Levenberg-Marquardt on Phi(q) = 0 on the configuration manifold: with the exact
J = dPhi/dq = U S V^T (singular values below ``rank_tol`` times the largest dropped),

.. math::  \\Delta x = -V \\,\\mathrm{diag}\\!\\left(\\frac{s_k}{s_k^2 + \\mu}\\right) U^T \\Phi,
           \\qquad \\mu = \\|\\Phi\\|^2

then ``pin.integrate`` with an Armijo backtracking on ||Phi||.  As the gap closes,
mu vanishes and the step becomes the minimum-norm Gauss-Newton step (quadratic
convergence; it moves the configuration as little as the closure needs, so the
closed configuration stays near the start); while the gap is large (a target out
of reach, a chain near its stretched, singular pose) the damping keeps the steps
short, and the iteration settles at the closest configuration, whose gap the
error reports in metres.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..errors import LoopClosureError, ParameterError
from ..errors.deprecated import renamed_keywords
from ..model.scene import Scene
from ..results import Result
from .constraint_set import RANK_TOL, ConstraintState, evaluate_constraints
from .newton import ARMIJO

__all__ = ["ClosureResult", "close_loops", "project", "CLOSURE_TOL", "SETTLED"]

#: Default gap [m] (and rotation [rad]) at which loops count as closed: the iteration
#: converges quadratically, so it reaches ~1e-15 m on metre-sized linkages; 1e-12 m
#: leaves margin for rounding in long chains and large coordinates.
CLOSURE_TOL = 1e-12
#: The iteration has settled (the targets are out of reach) when three steps reduced ||Phi||
#: by less than this fraction: converging steps cut it by orders of magnitude, while the
#: slow approach to the closest configuration still gets the reported gap right to ~1e-6.
SETTLED = 1e-6


@dataclass(frozen=True, repr=False, eq=False)
class ClosureResult(Result):
    """A configuration that satisfies the constraints, found by :func:`close_loops`.

    Attributes
    ----------
    q : (nq,) ndarray
        The closed configuration.
    gap, rotation_gap : float
        Largest remaining distance [m] and rotation [rad] between a frame and its target.
    initial_gap, initial_rotation_gap : float
        The same at the start.
    iterations : int
        Levenberg-Marquardt steps taken.
    history : tuple of float
        ||Phi|| before each step and at the end.
    elapsed : float
        Seconds.
    method : str
        ``"levenberg-marquardt (mu = ||Phi||^2)"``.
    error : float
        The headline error figure: ``gap`` [m] (absolute).
    held : tuple of str
        Joints kept where they were.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    >>> loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0), name="loop")
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", 50.0, rest=0.2)], constraints=[loop])
    >>> closed = pinlin.close_loops(scene, np.array([0.3, 0.0, 0.0]), hold=["crank_joint"])
    >>> closed.held, bool(closed.error == closed.gap <= 1e-12), closed.initial_gap > 0.01
    (('crank_joint',), True, True)
    """

    q: np.ndarray
    gap: float
    rotation_gap: float
    initial_gap: float
    initial_rotation_gap: float
    iterations: int
    history: tuple[float, ...]
    elapsed: float
    held: tuple[str, ...] = ()
    method: str = "levenberg-marquardt (mu = ||Phi||^2)"

    @property
    def error(self) -> float:
        """The largest remaining gap [m]."""
        return self.gap

    def __repr__(self) -> str:
        return (
            f"ClosureResult(gap={self.gap:.2e} m (from {self.initial_gap:.3g} m), iterations={self.iterations}, "
            f"elapsed={self.elapsed * 1e3:.2f} ms)"
        )


def _step(state: ConstraintState, held: np.ndarray) -> np.ndarray:
    """The Levenberg-Marquardt step (module docstring), held columns removed."""
    J = state.J_closure.copy()
    J[:, held] = 0.0
    U, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > state.rank_tol * s[0] if len(s) and s[0] > 0 else np.zeros(len(s), dtype=bool)
    s = s[keep]
    mu = float(state.phi @ state.phi)
    return -(Vt[keep].T @ ((U[:, keep].T @ state.phi) * (s / (s * s + mu))))


def _closed(state: ConstraintState, tol: float) -> bool:
    gap, rot, _ = state.gaps()
    return gap <= tol and rot <= tol


def project(
    scene: Scene,
    q: np.ndarray,
    *,
    tol: float = CLOSURE_TOL,
    max_iterations: int = 50,
    held: np.ndarray | None = None,
    rank_tol: float = RANK_TOL,
    min_step: float = 1e-10,
    calls: list[str] | None = None,
) -> tuple[np.ndarray, ConstraintState, list[float], bool]:
    """Levenberg-Marquardt closure from q: (q, its constraint state, ||Phi|| history, converged).

    Armijo's condition is on f = ||Phi||^2 / 2 with its predicted decrease
    alpha Phi^T J dx, so steps toward an out-of-reach target's closest
    configuration are taken as long as they make progress.  The Pinocchio
    algorithms run are appended to ``calls`` when given.
    """
    held = np.zeros(0, dtype=int) if held is None else held
    calls = [] if calls is None else calls
    state = evaluate_constraints(scene, q, closure=True, rank_tol=rank_tol)
    calls.extend(state.calls)
    history = [float(np.linalg.norm(state.phi))]
    for _ in range(max_iterations):
        if _closed(state, tol):
            return q, state, history, True
        dx = _step(state, held)
        alpha, norm = 1.0, history[-1]
        slope = float(state.phi @ (state.J_closure @ dx))  # d f / d alpha at alpha = 0 (< 0)
        while True:
            trial = pin.integrate(scene.model, q, alpha * dx)
            trial_state = evaluate_constraints(scene, trial, closure=True, rank_tol=rank_tol)
            calls.extend(trial_state.calls)
            trial_norm = float(np.linalg.norm(trial_state.phi))
            if math.isfinite(trial_norm) and 0.5 * trial_norm**2 <= 0.5 * norm**2 + ARMIJO * alpha * slope:
                break
            alpha /= 2
            if alpha < min_step:
                return q, state, history, False
        q, state = trial, trial_state
        history.append(trial_norm)
        if len(history) > 4 and history[-1] > (1 - SETTLED) * history[-4] and not _closed(state, tol):
            return q, state, history, False  # settled at a gap it cannot close
    return q, state, history, _closed(state, tol)


def _velocity_range(scene: Scene, joint: str) -> tuple[int, int]:
    j = scene.robot.joint(joint)
    return j.idx_v, j.idx_v + j.nv


@renamed_keywords(tol="closure_tol")
def close_loops(
    scene: Scene,
    q0=None,
    *,
    hold: Sequence[str] = (),
    closure_tol: float = CLOSURE_TOL,
    max_iterations: int = 100,
    rank_tol: float = RANK_TOL,
) -> ClosureResult:
    """Close the scene's constraints from ``q0``: the loop-closure step (theory: constraints).

    Levenberg-Marquardt steps q <- q (+) alpha dx (module docstring), alpha by
    Armijo backtracking on ||Phi||.  :func:`pinlin.find_equilibrium` runs it first
    and reports it; call it yourself to close a linkage at a given input angle
    (``hold=["crank"]``).

    Parameters
    ----------
    scene : Scene
        A scene with constraints.
    q0 : (nq,) array, optional
        Start; default Pinocchio's neutral configuration.
    hold : sequence of str
        Joints that keep their value in q0 (the input of a mechanism).
    closure_tol : float
        Largest gap [m] and rotation [rad] accepted as closed (``tol`` before 0.4, deprecated).
    max_iterations : int
    rank_tol : float
        Relative singular-value threshold of the least-squares steps.

    Raises
    ------
    ParameterError
        The scene has no constraints, or a bad tolerance.
    JointNotFoundError
        A held joint does not exist.
    ConfigurationError
        q0 has the wrong size or is not finite.
    LoopClosureError
        The targets cannot be reached from q0: the message and ``gap`` say by how many
        metres (and radians) the closest configuration found misses them.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    >>> loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0), name="loop")
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", 50.0, rest=0.2)], constraints=[loop])
    >>> closed = pinlin.close_loops(scene, np.array([0.3, 0.0, 0.0]), hold=["crank_joint"])
    >>> bool(closed.gap <= 1e-12), closed.iterations > 0, float(closed.q[0])
    (True, True, 0.3)
    """
    t0 = time.perf_counter()
    if not scene.constraints:
        raise ParameterError("scene", "has no constraints to close")
    if not (math.isfinite(closure_tol) and closure_tol > 0):
        raise ParameterError("closure_tol", f"must be a positive number, got {closure_tol!r}")
    q = scene.check_configuration(scene.neutral() if q0 is None else q0, "q0")
    if isinstance(hold, str):
        hold = [hold]
    held = np.array([i for name in hold for i in range(*_velocity_range(scene, name))], dtype=int)
    start = evaluate_constraints(scene, q, rank_tol=rank_tol)
    gap0, rot0, _ = start.gaps()
    q, state, history, ok = project(
        scene, q, tol=closure_tol, max_iterations=max_iterations, held=held, rank_tol=rank_tol
    )
    gap, rot, worst = state.gaps()
    if not ok:
        raise LoopClosureError(
            f"loop closure failed: the constraints cannot be closed from q0; the closest configuration found "
            f"leaves a gap of {gap:.6g} m" + (f" and {rot:.3g} rad" if rot > closure_tol else "") + f" at constraint "
            f"{worst!r} (from {gap0:.6g} m at q0, after {len(history) - 1} steps); the target may be out of "
            f"reach, or the start too far from an assembled configuration",
            gap,
            rot,
            [worst],
            history,
        )
    return ClosureResult(
        q, gap, rot, gap0, rot0, len(history) - 1, tuple(history), time.perf_counter() - t0, tuple(hold)
    )
