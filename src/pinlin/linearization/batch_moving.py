"""The batched linearization of a steady motion (prescribed joint velocities): Pinocchio per point, the rest stacked.

:func:`pinlin.linearize_many` takes this path for scenes whose prescribed joints
move (the turntable of theory: turntable) when every prescribed joint's time invariance is
proved once per scene (``plan_of(scene).proofs``, within the call's
``periodic_tol``: no numerical check per call), there is no constraint and no
world-fixed wrench, and the elements are joint springs and dampers.  Per point
remain the configuration's normalization, the one Pinocchio pass ``linearize``
runs (``computeRNEADerivatives``: K, C and M) and the element groups' own
per-point methods on an :class:`~.workspace.Evaluation` (what
:func:`~.assembly.assemble` calls, in its order); the norms, the checks, the
restriction to the free coordinates and the splits of K into S and N and of C
into D and G (the Coriolis rounding dropped as :func:`~.split.split_damping`
drops it) run once on the stacks.

The matrices are bitwise those of ``linearize``; the figures agree to rounding,
and exactly where they decide (:func:`~.batch_common.near`).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..model.evaluation import BatchPoints, Evaluation, live_view, workspace
from ..model.scene import Scene
from ..numerics.norms import fro
from .batch_common import TINY, build_systems, check_points, halves, near, norms, relative_residuals, rows_or_zero
from .options import LinearizeOptions
from .plan import plan_of
from .system import LinearizedSystem

__all__ = ["applies", "linearize_moving"]


def applies(scene: Scene, periodic_tol: float) -> bool:
    """True when the scene is of the kind this path linearizes with this ``periodic_tol`` (module docstring)."""
    plan = plan_of(scene)
    return (
        plan.moving
        and not plan.unproved
        and periodic_tol >= plan.largest_departure
        and not scene.constraints
        and not scene.varying_wrenches
        and all(g.batched for g in scene.groups)
    )


def _evaluate(scene: Scene, qs: np.ndarray):
    """(tau, Q, K, C, M, Pinocchio's K, Pinocchio's C) on all coordinates, as :func:`~.assembly.assemble` forms them.

    Pinocchio's parts are kept apart (the rounding scales are their norms); the
    elements are added per point by their groups' own methods, in assembly order,
    on an Evaluation of that point (the batched groups, joint springs and dampers,
    read only its q and v, not the Pinocchio Data, which holds the last point).
    """
    model, ws = scene.model, workspace(scene)
    data, v0 = ws.data, scene.v0
    P, nv = len(qs), model.nv
    extra = () if scene.constant_fext is None else (scene.constant_fext,)
    zero = np.zeros(nv)
    tau, pinocchio_K, pinocchio_C, upper = (np.empty((P, nv)),) + tuple(np.empty((P, nv, nv)) for _ in range(3))
    derivatives = pin.computeRNEADerivatives
    view, live = live_view(data, "tau")
    for q, t, k, c, m in zip(qs, tau, pinocchio_K, pinocchio_C, upper):
        k[...], c[...], m[...] = derivatives(model, data, q, v0, zero, *extra)  # views of Data: copied
        t[...] = view if live else data.tau
    M = np.where(ws.lower, upper.transpose(0, 2, 1), upper)  # symmetric_from_upper on every point at once
    Q, K, C = np.zeros((P, nv)), pinocchio_K.copy(), pinocchio_C.copy()
    groups = scene.groups
    for q, Qp, Kp, Cp in zip(qs, Q, K, C):
        ev = Evaluation(scene, q, v0, ws, at_rest=False)
        for group in groups:
            group.add_force(ev, Qp)
            group.add_stiffness(ev, Kp)
            group.add_damping(ev, Cp)
    return tau, Q, K, C, M, pinocchio_K, pinocchio_C


def linearize_moving(scene: Scene, qs: np.ndarray, options: LinearizeOptions, elapsed0: float, clock,
                     batch: BatchPoints | None = None) -> tuple[LinearizedSystem, ...]:  # fmt: skip
    """The systems at the rows of ``qs`` (checked configurations, (P, nq), owned) of a scene for which :func:`applies`.

    ``options``: its ``structure_tol`` set (not None).  ``batch`` is taken for the paths' common call
    and not read: this path evaluates its elements point by point on Evaluations (their own memo).
    """
    equilibrium_tol, tol, balancing = options.equilibrium_tol, options.structure_tol, options.balancing
    plan = plan_of(scene)
    tau, Q, K, C, M, pinocchio_K, pinocchio_C = _evaluate(scene, qs)
    scale_C, scale_K = norms(pinocchio_C), norms(pinocchio_K)
    residual = tau - Q
    r = residual[:, plan.rows]
    force_scale, rel = relative_residuals(tau, Q, K, r, equilibrium_tol)
    rounding_K = scale_K if plan.symmetric_elements else scale_K + norms(K)
    block = (slice(None),) + plan.block  # the free coordinates of every point
    M = M[block]
    check_points(scene, residual, force_scale, rel, M, C[block], equilibrium_tol, balancing)
    S, N = halves(K[block])
    N_sizes = 0.5 * norms(N) / np.maximum(rounding_K, TINY)
    for i in near(N_sizes, tol):  # as split_stiffness, where it decides (its scale: the whole K)
        exact = fro(pinocchio_K[i]) if plan.symmetric_elements else fro(pinocchio_K[i]) + fro(K[i])
        N_sizes[i] = 0.5 * fro(N[i]) / max(exact, TINY)
    N *= 0.5
    D, G, D_sizes, G_sizes = _split_damping(plan, C[block], pinocchio_C, scale_C, tol)
    for a in (M, D, G, S, N, qs, r):
        a.flags.writeable = False
    zero = np.zeros(S.shape[1:])
    zero.flags.writeable = False
    dropped: list[dict[str, float]] = [{} for _ in range(len(qs))]  # in the single call's order: N, Coriolis D, G
    N = rows_or_zero(N, N_sizes.tolist(), tol, "N", zero, dropped)
    for p, size in enumerate(D_sizes.tolist()):
        if size <= tol and size:
            dropped[p]["D (Coriolis rounding)"] = size
    G = rows_or_zero(G, G_sizes.tolist(), tol, "G", zero, dropped)
    matrices = {"M": M, "D": D, "G": G, "S": S, "N": N}
    elapsed = (clock() - elapsed0) / len(qs)
    return build_systems(scene, ("computeRNEADerivatives",), plan.proof_notes, elapsed, balancing, matrices, qs, rel.tolist(), r, dropped)


def _split_damping(plan, C: np.ndarray, pinocchio_C: np.ndarray, scale_C: np.ndarray, tol: float):
    """(D, G before its rounding test, size of the Coriolis D, size of G) of each point: :func:`~.split.split_damping`.

    Pinocchio's dtau/dv is skew in exact arithmetic: its symmetric part is
    removed from D where it is at rounding level (all of D when the elements add
    no damping), G is tested against the same scale, both against the norm of
    Pinocchio's part, as the single call does.
    """
    D, difference = halves(C)
    if plan.undamped:  # C is Pinocchio's alone: its symmetric part is D itself
        D_rnea = None
        D_sizes = norms(D) / np.maximum(scale_C, TINY)
    else:
        coriolis_D = pinocchio_C + pinocchio_C.transpose(0, 2, 1).copy()  # as assemble: (C + C^T) / 2
        coriolis_D *= 0.5
        D_rnea = coriolis_D[(slice(None),) + plan.block]
        D_sizes = norms(D_rnea) / np.maximum(scale_C, TINY)
    G_sizes = 0.5 * norms(difference) / np.maximum(scale_C, TINY)
    for i in near(D_sizes, tol):
        D_sizes[i] = fro(D[i] if D_rnea is None else D_rnea[i]) / max(fro(pinocchio_C[i]), TINY)
    for i in near(G_sizes, tol):
        G_sizes[i] = 0.5 * fro(difference[i]) / max(fro(pinocchio_C[i]), TINY)
    rounding = D_sizes <= tol
    if rounding.any():
        if D_rnea is None:
            D[rounding] = 0.0  # D - D: exactly zero, D being finite (checked before the split)
        else:
            D[rounding] -= D_rnea[rounding]
    difference *= 0.5
    return D, difference, D_sizes, G_sizes
