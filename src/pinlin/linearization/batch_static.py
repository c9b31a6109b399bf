"""The batched linearization of a joint-space scene at rest: Pinocchio per point, the rest for all points at once.

:func:`pinlin.linearize_many` takes this path for scenes at rest (no prescribed
joint, no constraint) whose elements are joint springs and dampers and
body-fixed (follower) wrenches: per point only the Pinocchio passes
``linearize`` runs (the static derivative algorithm and ``crba``, in one loop
into rows of stacked arrays) and the multi-DOF springs' Lie-group derivatives
remain; the 1-DOF springs, the norms, the residual, finite, mass and structure
checks and the symmetric/skew split run once on the stacks (the dampers'
constant matrix and its split come from the scene's plan), and the results are
built by :func:`~.batch_common.build_systems`.

The matrices are bitwise those of ``linearize`` (the same operations entry by
entry); the norms behind the error figures (``residual``, ``dropped``) are taken
for all points in one reduction, so they agree with ``linearize``'s to rounding.
Where such a figure decides something (the equilibrium check, whether N is
rounding) and lies within :data:`~.batch_common.DECISION_MARGIN` of its
tolerance, it is taken again exactly as ``linearize`` takes it, so the decisions
are the single call's.
"""

from __future__ import annotations


import numpy as np
import pinocchio as pin

from ..model.evaluation import BatchPoints, crba_is_symmetric, live_view, workspace
from ..model.scene import Scene
from ..numerics.norms import fro
from .batch_common import TINY, build_systems, check_points, halves, near, norms, relative_residuals, rows_or_zero
from .options import LinearizeOptions
from .plan import plan_of
from .system import LinearizedSystem

__all__ = ["applies", "linearize_at_rest"]


def applies(scene: Scene) -> bool:
    """True when the scene is of the kind this path linearizes (see the module docstring)."""
    plan = plan_of(scene)
    return (
        plan.everything
        and not plan.moving
        and not scene.constraints
        and not scene.varying_wrenches
        and plan.rest_damping is not None
        and all(g.batched for g in scene.groups)
    )


def _pinocchio(scene: Scene, qs: np.ndarray):
    """(tau (P, nv), K (P, nv, nv), M (P, nv, nv), calls): the Pinocchio passes of ``linearize``, per point.

    One loop over the points runs the static derivative algorithm and ``crba``
    (both bindings return fresh arrays, copied into rows of the stacks).
    """
    model, ws = scene.model, workspace(scene)
    data = ws.data
    P, nv = len(qs), model.nv
    tau, K, M = np.empty((P, nv)), np.empty((P, nv, nv)), np.empty((P, nv, nv))
    fext = scene.constant_fext
    crba = pin.crba
    if fext is not None:
        calls, derivatives = ("computeStaticTorqueDerivatives", "crba"), pin.computeStaticTorqueDerivatives
        view, live = live_view(data, "tau")
        for q, t, k, m in zip(qs, tau, K, M):
            k[...] = derivatives(model, data, q, fext)
            t[...] = view if live else data.tau
            m[...] = crba(model, data, q)
    elif scene.has_gravity:
        calls, derivatives = ("computeGeneralizedGravityDerivatives", "crba"), pin.computeGeneralizedGravityDerivatives
        view, live = live_view(data, "g")
        for q, t, k, m in zip(qs, tau, K, M):
            k[...] = derivatives(model, data, q)
            t[...] = view if live else data.g
            m[...] = crba(model, data, q)
    else:
        calls = ("crba",)
        tau[...] = 0.0
        K[...] = 0.0
        for q, m in zip(qs, M):
            m[...] = crba(model, data, q)
    if not crba_is_symmetric():  # a binding that returns crba's upper triangle only: mirrored, as linearize does
        M = np.where(ws.lower, M.transpose(0, 2, 1), M)  # symmetric_from_upper on every point at once
    return tau, K, M, calls


def linearize_at_rest(scene: Scene, qs: np.ndarray, options: LinearizeOptions, elapsed0: float, clock,
                      batch: BatchPoints | None = None) -> tuple[LinearizedSystem, ...]:  # fmt: skip
    """The systems at the rows of ``qs`` (checked configurations, (P, nq), owned) of a scene for which :func:`applies`.

    ``options``: its ``structure_tol`` set (not None); ``batch``: the call's points, qs its chunk (the
    element groups' work shared by the chunks).
    """
    equilibrium_tol, tol, balancing = options.equilibrium_tol, options.structure_tol, options.balancing
    plan = plan_of(scene)
    tau, K, M, calls = _pinocchio(scene, qs)
    scale_K = norms(K)
    Q = np.zeros(tau.shape)
    for group in scene.groups:
        group.add_many(qs, Q, K, batch)
    r = tau - Q
    force_scale, rel = relative_residuals(tau, Q, K, r, equilibrium_tol)
    rounding = scale_K if plan.symmetric_elements else scale_K + norms(K)
    check_points(scene, r, force_scale, rel, M, plan.rest_damping.C, equilibrium_tol, balancing)
    S, N = halves(K)
    sizes = 0.5 * norms(N) / np.maximum(rounding, TINY)
    for i in near(sizes, tol):  # as split_stiffness, where it decides; Pinocchio's part of K run again (rare)
        pinocchio_K = _pinocchio(scene, qs[i : i + 1])[1][0]  # deterministic: bitwise the same K
        exact = fro(pinocchio_K) if plan.symmetric_elements else fro(pinocchio_K) + fro(K[i])
        sizes[i] = 0.5 * fro(N[i]) / max(exact, TINY)
    N *= 0.5
    for a in (S, N, M, qs, r):
        a.flags.writeable = False
    damped: dict[str, float] = {}  # what the damping split drops: the same at every point
    D, G = plan.rest_damping.split(tol, damped)  # read-only views, one pair for the batch
    zero = np.zeros(S.shape[1:])
    zero.flags.writeable = False
    dropped: list[dict[str, float]] = [{} for _ in range(len(qs))]
    N = rows_or_zero(N, sizes.tolist(), tol, "N", zero, dropped)  # "N" first, as split_stiffness runs first
    if damped:
        for entry in dropped:
            entry.update(damped)
    matrices = {"M": M, "D": D, "G": G, "S": S, "N": N}
    return build_systems(scene, calls, (), (clock() - elapsed0) / len(qs), balancing, matrices, qs, rel.tolist(), r, dropped)
