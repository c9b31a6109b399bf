"""A scene's constraints at one configuration: Phi, J_c, its rank and the multipliers (theory: constraints).

:func:`evaluate_constraints` stacks the constraints of a scene in scene order
(3 rows per point constraint, 6 per frame constraint).  The rank of J_c comes from
a rank-revealing factorization, the column-pivoted QR of J_c (LAPACK ``dgeqp3``:
J_c P = Q R with |R_11| >= |R_22| >= ...): the rank is the number of diagonal
entries |R_kk| > ``rank_tol`` |R_11| (:data:`RANK_TOL`); the same factorization
picks the dependent joints of the default coordinates (:mod:`.coordinates`).  The
multipliers are the minimum-norm least-squares solution of J_c^T lambda = r: at
full row rank the unique one (LAPACK ``dgels``, a Householder QR of J_c^T), else
LAPACK ``dgelsy`` (a complete orthogonal factorization with the same threshold;
the SVD truncated at the rank if the two rank decisions ever differ): a redundant
set (a planar loop's point constraint has an out-of-plane equation that is always
satisfied, so its force along that direction is not determined) gets the
minimum-norm forces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg.lapack as lapack

from ..errors import ConstraintViolationError, OverconstrainedError
from ..model.constraints import ConstraintForce, ContactStatus, dead_wrench_stiffness, stack_wrenches
from ..model.evaluation import Evaluation, Workspace
from ..model.scene import Scene
from ..numerics.norms import fro
from .assembly import Assembly, assemble

__all__ = [
    "ConstraintState",
    "ConstrainedPoint",
    "linearization_point",
    "constrained_point",
    "relative_residual",
    "constraint_notes",
    "evaluate_constraints",
    "constraint_forces",
    "contact_statuses",
    "check_motion_left",
    "RANK_TOL",
    "CONSTRAINT_TOL",
]

#: A pivot |R_kk| of the column-pivoted QR of J_c counts as zero when it is at most
#: RANK_TOL |R_11|: rounding leaves ~1e-15 relative in an exactly dependent row, while a
#: linkage 1e-8 rad from a toggle still has ~1e-8; 1e-9 separates the two with margin.
RANK_TOL = 1e-9

#: Default largest constraint gap [m] (and rotation [rad]) that ``linearize`` accepts as
#: closed: the equilibrium solver closes loops to ~1e-15 m; 1e-8 m leaves room for
#: configurations assembled by other tools while staying far below any physical gap.
CONSTRAINT_TOL = 1e-8


class _once:
    """A lazily computed attribute, stored in the instance on first access (no lock: a state is one caller's)."""

    def __init__(self, compute):
        self.compute, self.name, self.__doc__ = compute, compute.__name__, compute.__doc__

    def __get__(self, obj, owner=None):
        if obj is None:
            return self
        value = obj.__dict__[self.name] = self.compute(obj)
        return value


@dataclass
class ConstraintState:
    """The constraints of a scene evaluated at q.

    Attributes
    ----------
    scene : Scene
    q : (nq,) ndarray
    phi : (m,) ndarray
        Phi(q), stacked in scene order [m, rad].
    J : (m, nv) ndarray
        J_c in velocity form (world-axes relative velocity of each frame).
    J_closure : (m, nv) ndarray or None
        dPhi/dq, exact off the manifold (only when asked for).
    rows : tuple of slice
        The rows of each constraint.
    calls : list of str
        Pinocchio algorithms run.
    ev : Evaluation
        The kinematics at q (frame Jacobians, placements), kept for K_lambda.
    rank_tol : float
        Relative threshold of the rank decisions.
    frames : (k, 6, nv) ndarray or None
        The constrained frames' Jacobians (LOCAL_WORLD_ALIGNED) when every constraint
        holds a point at a world point (``scene.world_points``): K_lambda in one product.
    """

    scene: Scene
    q: np.ndarray
    phi: np.ndarray
    J: np.ndarray
    J_closure: np.ndarray | None
    rows: tuple[slice, ...]
    calls: list[str]
    ev: Evaluation
    rank_tol: float = RANK_TOL
    frames: np.ndarray | None = None

    @_once
    def qr(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Column-pivoted QR of J_c: (LAPACK's packed Q and R, 0-based column pivots, Householder tau)."""
        qr, pivots, tau, _, _ = lapack.dgeqp3(self.J)
        return qr, pivots - 1, tau

    @_once
    def rank(self) -> int:
        """Numerical rank of J_c: pivots |R_kk| above ``rank_tol`` |R_11|."""
        d = self.qr[0].diagonal().tolist()  # a few entries: Python floats, the same comparisons
        if not d or d[0] == 0:
            return 0
        cut = self.rank_tol * abs(d[0])
        return len([x for x in d if abs(x) > cut])

    @_once
    def svd(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Full SVD of J_c: U (m x m), s, Vt (nv x nv) (bases of the null spaces, minimum-norm multipliers)."""
        return np.linalg.svd(self.J, full_matrices=True)

    @_once
    def m(self) -> int:
        """Number of constraint equations."""
        return len(self.phi)

    @_once
    def left_null(self) -> np.ndarray:
        """Orthonormal basis of ker J_c^T (m x (m - rank)): the dependent combinations of the equations."""
        return self.svd[0][:, self.rank :]

    def kernel(self) -> np.ndarray:
        """Orthonormal basis of ker J_c (nv x (nv - rank))."""
        return self.svd[2][self.rank :].T

    def multipliers(self, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Minimum-norm lambda minimizing ||r - J_c^T lambda||, and g = r - J_c^T lambda.

        .. math::  \\lambda = \\arg\\min \\|\\lambda\\| \\ \\text{among the minimizers of}
                   \\ \\|r - J_c^T \\lambda\\|

        At full row rank (rank J_c = m: a standing robot's contacts) the minimizer is
        unique and LAPACK's ``dgels`` gives it (a Householder QR of J_c^T, backward
        stable like ``dgelsy``, without the pivoting and rank estimation this state's
        rank decision has already done); otherwise ``dgelsy`` with ``rank_tol``.
        """
        k, (nv, m) = self.rank, self.J.T.shape
        if not k:
            return np.zeros(m), r.copy()
        if k == m and nv >= m:
            _, x, info = lapack.dgels(self.J.T, r[:, None])
            if info == 0:  # info > 0: an exactly zero pivot, which the rank decision excludes
                lam = x[:m, 0]
                return lam, r - self.J.T @ lam
        b = np.zeros((max(nv, m), 1))
        b[:nv, 0] = r
        mn = min(nv, m)
        _, x, _, rank, _ = lapack.dgelsy(self.J.T, b, np.zeros(m, dtype=np.int32), self.rank_tol, max(mn + 3 * m + 1, 2 * mn + 1))
        if rank == k:
            lam = x[:m, 0]
        else:  # the two rank decisions differ at the threshold: follow this state's rank
            U, s, Vt = self.svd
            lam = U[:, :k] @ ((Vt[:k] @ r) / s[:k])
        return lam, r - self.J.T @ lam

    def force_stiffness(self, lam: np.ndarray) -> np.ndarray:
        """K_lambda = d(J_c^T lambda)/dq at fixed lambda (nv x nv; theory: constraints)."""
        before = self.scene.robot.dof_supports
        if self.frames is not None:
            return dead_wrench_stiffness(self.frames, lam.reshape(-1, 3), None, before, linear=self.J)
        terms = [t for c, rows in zip(self.scene.constraints, self.rows) for t in c.wrench_terms(self.ev, lam[rows])]
        return dead_wrench_stiffness(*stack_wrenches(terms), before)

    def gaps(self) -> tuple[float, float, str]:
        """Largest distance [m], largest rotation [rad], and the label of the constraint with the largest distance."""
        scene = self.scene
        values = self.phi.tolist()  # a few constraints: Python floats, the sums numpy would form
        worst, largest = 0, math.nan
        for i, row in enumerate(scene.position_rows[:, 0].tolist()):
            x, y, z = values[row], values[row + 1], values[row + 2]
            d2 = x * x + y * y + z * z
            if not i or d2 > largest or (d2 != d2 and largest == largest):  # the first largest; a NaN wins
                worst, largest = i, d2
        rot = 0.0
        if len(scene.rotation_rows):
            R = self.phi[scene.rotation_rows]
            rot = math.sqrt(float((R * R).sum(axis=1).max()))
        return math.sqrt(largest), rot, scene.constraints[worst].label

    def contacts_violated(self, lam: np.ndarray) -> bool:
        """True when a contact needs the ground to pull or more friction than its mu.

        On Python floats (a handful of contacts: cheaper than numpy's fixed costs), in
        the order of the sums :meth:`ContactStatus <pinlin.model.constraints.PointConstraint.contact_status>`
        reports: f_n = n . lambda, t = lambda - f_n n, violated when f_n < 0 or |t|^2 > (mu f_n)^2.
        """
        scene = self.scene
        if not scene.contact_index:
            return False
        values = lam.tolist()
        for row, (a, b, c), mu in zip(scene.contact_rows[:, 0].tolist(), scene.contact_normals.tolist(),
                                      scene.contact_friction.tolist()):  # fmt: skip
            x, y, z = values[row], values[row + 1], values[row + 2]
            fn = x * a + y * b + z * c
            tx, ty, tz = x - fn * a, y - fn * b, z - fn * c
            mu_fn = mu * fn
            if fn < 0 or tx * tx + ty * ty + tz * tz > mu_fn * mu_fn:
                return True
        return False

    def row_owners(self, vector: np.ndarray, share: float) -> list[str]:
        """Labels of the constraints whose rows carry at least ``share`` of a unit vector (m,)."""
        weights = [float(np.linalg.norm(vector[rows])) for rows in self.rows]
        top = max(weights) if weights else 0.0
        return [c.label for c, w in zip(self.scene.constraints, weights) if top > 0 and w >= share * top]


def evaluate_constraints(
    scene: Scene,
    q: np.ndarray,
    *,
    closure: bool = False,
    rank_tol: float = RANK_TOL,
    ws: Workspace | None = None,
) -> ConstraintState:
    """Phi(q) and J_c(q) of every constraint of ``scene``, stacked (and dPhi/dq if ``closure``).

    ``q`` must already be checked (:meth:`Scene.check_configuration`).  Runs
    ``computeJointJacobians`` + ``updateFramePlacements`` once.
    """
    ev = Evaluation(scene, q, scene.v0, ws, at_rest=True)  # constraints refuse prescribed velocities: v0 = 0
    if scene.world_points is not None:  # points at world points: one group, same numbers
        ids, targets = scene.world_points
        frames = np.array([ev.world_aligned_jacobian(i) for i in ids])  # runs the kinematics, once
        oMf = ev.data.oMf  # a few frames: one proxy each costs less than converting every frame
        phi = (np.array([oMf[i].translation for i in ids]) - targets).ravel()
        J = frames[:, :3].reshape(-1, scene.model.nv)
        return ConstraintState(scene, q, phi, J, J if closure else None, scene.constraint_rows, ev.calls, ev, rank_tol, frames)
    constraints = scene.constraints
    phi = np.concatenate([c.residual(ev) for c in constraints])
    J = np.vstack([c.jacobian(ev) for c in constraints])
    Jx = np.vstack([c.closure_jacobian(ev) for c in constraints]) if closure else None
    return ConstraintState(scene, q, phi, J, Jx, scene.constraint_rows, ev.calls, ev, rank_tol)


def constraint_forces(scene: Scene, lam: np.ndarray) -> tuple[ConstraintForce, ...]:
    """One :class:`~pinlin.ConstraintForce` per constraint, in scene order.

    One copy of ``lam``, read-only; each force (and torque) is a view of its own rows of it.
    """
    lam = np.array(lam, dtype=float)
    lam.flags.writeable = False  # the forces are part of a frozen result
    return tuple([c.force(lam[rows], copy=False) for c, rows in zip(scene.constraints, scene.constraint_rows)])


def contact_statuses(scene: Scene, lam: np.ndarray) -> tuple[ContactStatus, ...]:
    """The status of every contact (``PointConstraint(..., contact=True)``), in scene order."""
    rows = scene.constraint_rows
    return tuple(scene.constraints[i].contact_status(lam[rows[i]]) for i in scene.contact_index)


def constrained_point(scene: Scene, q: np.ndarray, state: ConstraintState, stiffness: bool = False, **asked):
    """(lambda, g = r - J_c^T lambda, assembly, K - K_lambda or None) at q.

    The assembly is the scene's own (as without constraints); lambda are the
    minimum-norm multipliers of its residual.
    """
    asm = assemble(scene, q, stiffness=stiffness, **asked)
    lam, g = state.multipliers(asm.residual)
    if not stiffness:
        return lam, g, asm, None
    K_lambda = state.force_stiffness(lam)
    asm.rounding_scale_K += fro(K_lambda)  # K - K_lambda carries the rounding of both
    return lam, g, asm, asm.K - K_lambda


def relative_residual(g: np.ndarray, state: ConstraintState, lam: np.ndarray, asm: Assembly, Kt: np.ndarray) -> float:
    """||g|| / (||tau|| + ||Q_e|| + ||K|| + ||J_c^T lambda|| + ||K - K_lambda||)."""
    scale = asm.force_scale + fro(asm.residual - g) + fro(Kt)  # r - g = J_c^T lambda
    return fro(g) / scale if scale > 0 else 0.0


def constraint_notes(scene: Scene, state: ConstraintState, lam: np.ndarray, all_contacts: bool) -> tuple[list[str], tuple]:
    """Notes on redundancy and on contacts the ground cannot hold, and the contact statuses.

    The statuses are built for every contact when ``all_contacts``, else only when
    one is violated (the vectorized check is cheaper than the objects).
    """
    notes = []
    if state.rank < state.m:
        notes.append(
            f"{state.m - state.rank} of the {state.m} constraint equations "
            f"{'is' if state.m - state.rank == 1 else 'are'} redundant (rank J_c = "
            f"{state.rank}): the constraint forces are the minimum-norm ones, not unique"
        )
    contacts = ()
    if all_contacts or state.contacts_violated(lam):
        contacts = contact_statuses(scene, lam)
        notes.extend(c.describe() for c in contacts if not c.feasible)
    return notes, contacts


def check_motion_left(scene: Scene, state: ConstraintState) -> None:
    """Refuse constraints that hold every degree of freedom (rank J_c = nv): no motion is left to find an
    equilibrium of or to linearize (one check for :func:`pinlin.find_equilibrium` and :func:`pinlin.linearize`).

    Raises
    ------
    OverconstrainedError
        rank J_c = nv at the evaluated configuration.
    """
    nv = scene.model.nv
    if state.rank == nv:
        labels = [c.label for c in scene.constraints]
        raise OverconstrainedError(
            f"no motion left: the constraints {labels} have rank J_c = {state.rank} = nv, so they hold every "
            f"degree of freedom of {scene.robot.name!r}; there is no motion to find an equilibrium of or to linearize",
            state.rank,
            nv,
            labels,
        )


@dataclass(frozen=True)
class ConstrainedPoint:
    """What one linearization reads of a scene with constraints at q, each evaluated once.

    Attributes
    ----------
    state : ConstraintState
        Phi, J_c and its factorizations at q (closure gaps, rank, basis).
    lam, g : ndarray
        The minimum-norm multipliers (m,) and g = r - J_c^T lambda (nv,).
    assembly : Assembly
        The scene's own M, C, K and residual at q.
    Kt : (nv, nv) ndarray
        K - K_lambda, the stiffness the projection reads.
    relative_residual : float
        ||g|| over the force scale (:func:`relative_residual`).
    notes : list of str
        Redundancy and contact notes (:func:`constraint_notes`).
    forces : tuple of ConstraintForce
        The constraint forces, in scene order.
    """

    state: ConstraintState
    lam: np.ndarray
    g: np.ndarray
    assembly: Assembly
    Kt: np.ndarray
    relative_residual: float
    notes: list
    forces: tuple


def linearization_point(scene: Scene, q: np.ndarray, *, rank_tol: float, constraint_tol: float) -> ConstrainedPoint:
    """The constraints, the assembly and the multipliers at a checked q, in one pass (what linearize reads).

    Raises
    ------
    ConstraintViolationError
        q violates the constraints by more than ``constraint_tol`` (the gap [m] attached).
    OverconstrainedError
        No motion is left: rank J_c = nv.
    """
    state = evaluate_constraints(scene, q, rank_tol=rank_tol)
    gap, rot, worst = state.gaps()
    if gap > constraint_tol or rot > constraint_tol:
        raise ConstraintViolationError(
            f"q violates the constraints: constraint {worst!r} is open by {gap:.4g} m"
            + (f" (largest rotation gap {rot:.3g} rad)" if rot > constraint_tol else "")
            + f" > constraint_tol {constraint_tol:g}; close them first with find_equilibrium or close_loops",
            gap,
            rot,
            [worst],
        )
    check_motion_left(scene, state)  # decides the rank: the projection reads it, and m, from the state
    lam, g, asm, Kt = constrained_point(scene, q, state, stiffness=True, damping=True, mass=True)
    notes, _ = constraint_notes(scene, state, lam, all_contacts=False)
    return ConstrainedPoint(
        state, lam, g, asm, Kt, relative_residual(g, state, lam, asm, Kt), notes, constraint_forces(scene, lam)
    )
