"""The batched linearization of a joint-space scene at rest: Pinocchio per point, the rest for all points at once.

:func:`pinlin.linearize_many` takes this path for scenes at rest (no prescribed
joint, no constraint) whose elements are joint springs and dampers and
body-fixed (follower) wrenches: per point only the configuration check, the
Pinocchio passes ``linearize`` runs (the static derivative algorithm and
``crba``, into rows of stacked arrays) and the multi-DOF springs' Lie-group
derivatives remain; the 1-DOF springs, the norms, the residual, finite, mass
and structure checks and the symmetric/skew split run once on the stacks (the
dampers' constant matrix and its split come from the scene's plan).

The matrices are bitwise those of ``linearize`` (the same operations entry by
entry); the norms behind the error figures (``residual``, ``dropped``) are taken
for all points in one reduction, so they agree with ``linearize``'s to rounding.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from ..errors import ComputationError
from ..model.scene import Scene
from .assembly import Assembly
from .linearize import _check_finite_and_mass, _check_mass, _equilibrium
from .system import LinearizedSystem
from .workspace import crba_is_symmetric, symmetric_from_upper, workspace

__all__ = ["applies", "linearize_at_rest"]

_TINY = float(np.finfo(float).tiny)


def applies(scene: Scene) -> bool:
    """True when the scene is of the kind this path linearizes (see the module docstring)."""
    plan = scene.linearization_plan
    return (
        plan.everything
        and not plan.moving
        and not scene.constraints
        and not scene.varying_wrenches
        and plan.rest_damping is not None
        and all(g.batched for g in scene.groups)
    )


def _norms(X: np.ndarray) -> np.ndarray:
    """Frobenius norm of each X[p] (P,), overflow-safe: scaled again where the squares overflow."""
    flat = X.reshape(len(X), -1)
    squares = np.einsum("pi,pi->p", flat, flat)
    if squares.sum() < math.inf:  # the usual case; False for an overflow, inf or NaN
        return np.sqrt(squares)
    out = np.sqrt(squares)
    bad = ~np.isfinite(out)  # entries beyond ~1e154 (or non-finite ones): scale by the largest entry
    with np.errstate(over="ignore", invalid="ignore"):
        big = np.abs(flat[bad]).max(axis=1)
        scaled = flat[bad] / np.where(big > 0, big, 1.0)[:, None]
        norm = big * np.sqrt(np.einsum("pi,pi->p", scaled, scaled))
    out[bad] = np.where(np.isfinite(big), norm, big)  # an infinite (NaN) entry: an infinite (NaN) norm, as fro
    return out


def _pinocchio(scene: Scene, points: list[np.ndarray]):
    """(tau (P, nv), K (P, nv, nv), M (P, nv, nv), calls): the Pinocchio passes of ``linearize``, per point."""
    model, data = scene.model, workspace(scene).data
    P, nv = len(points), model.nv
    tau, K, M = np.zeros((P, nv)), np.zeros((P, nv, nv)), np.empty((P, nv, nv))
    fext = scene.constant_fext
    if fext is not None:
        calls = ("computeStaticTorqueDerivatives", "crba")
        for q, t, k in zip(points, tau, K):
            k[:] = pin.computeStaticTorqueDerivatives(model, data, q, fext)
            t[:] = data.tau
    elif scene.has_gravity:
        calls = ("computeGeneralizedGravityDerivatives", "crba")
        for q, t, k in zip(points, tau, K):
            k[:] = pin.computeGeneralizedGravityDerivatives(model, data, q)
            t[:] = data.g
    else:
        calls = ("crba",)
    lower = None if crba_is_symmetric() else workspace(scene).lower
    for q, m in zip(points, M):
        m[:] = pin.crba(model, data, q) if lower is None else symmetric_from_upper(pin.crba(model, data, q), lower)
    return tau, K, M, calls


def linearize_at_rest(scene: Scene, points: list[np.ndarray], equilibrium_tol: float, tol: float,
                      balancing: bool, elapsed0: float, clock) -> tuple[LinearizedSystem, ...]:  # fmt: skip
    """The systems at ``points`` (checked configurations) of a scene for which :func:`applies`."""
    plan = scene.linearization_plan
    qs = np.array(points)
    tau, K, M, calls = _pinocchio(scene, points)
    scale_K = _norms(K)
    Q = np.zeros(tau.shape)
    for group in scene.groups:
        group.add_force_many(qs, Q)
        group.add_stiffness_many(qs, K)
    K_norm = _norms(K)
    rounding = scale_K if plan.symmetric_elements else scale_K + K_norm
    r = tau - Q
    force_scale = _norms(tau) + _norms(Q) + K_norm
    rel = _norms(r) / np.where(force_scale > 0, force_scale, 1.0)
    rel[force_scale <= 0] = 0.0
    _check_points(scene, r, force_scale, rel, M, equilibrium_tol, balancing)
    S = K.transpose(0, 2, 1).copy()  # as split.split_stiffness, entry by entry
    N = K - S
    sizes = 0.5 * _norms(N) / np.maximum(rounding, _TINY)
    S += K
    S *= 0.5
    N *= 0.5
    for a in (S, N, M, qs):
        a.flags.writeable = False
    zero = np.zeros(S.shape[1:])
    zero.flags.writeable = False
    elapsed = (clock() - elapsed0) / len(points)
    out = []
    for i in range(len(points)):
        dropped: dict[str, float] = {}
        size = float(sizes[i])
        Ni = N[i]
        if size <= tol:
            if size:
                dropped["N"] = size
            Ni = zero.view()
        D, G = plan.rest_damping.split(tol, dropped)
        notes = (f"held at q by constant actuator forces (relative residual {rel[i]:.2e})",) if balancing else ()
        out.append(
            LinearizedSystem.trusted(
                M[i], D, G, S[i], Ni, dof_names=scene.dof_names, q=qs[i], v=scene.v0, residual=float(rel[i]),
                balancing=r[i].copy() if balancing else None, elapsed=elapsed, calls=calls, dropped=dropped,
                notes=notes, method="analytic", frozen=True,
            )  # fmt: skip
        )
    return tuple(out)


def _check_points(scene, r, force_scale, rel, M, tol: float, balancing: bool) -> None:
    """The single call's equilibrium, finite-entry and mass checks on all points; its own errors at the first bad one."""
    plan = scene.linearization_plan
    if not balancing and (rel > tol).any():
        i = int(np.argmax(rel > tol))
        _equilibrium(scene, plan, _assembly(r[i], force_scale[i]), tol, balancing)  # raises
    C = plan.rest_damping.C
    if not (np.isfinite(force_scale).all() and np.isfinite(M).all() and np.isfinite(C).all()):
        for i in range(len(M)):
            _check_finite_and_mass(scene, M[i], C, _assembly(r[i], force_scale[i]))  # raises at the first bad point
        raise ComputationError("linearize_many: non-finite entries in M, C, K or the residual")  # pragma: no cover
    try:
        np.linalg.cholesky(M)  # all points at once (LAPACK's potrf, as linearize's check)
    except np.linalg.LinAlgError:
        for Mi in M:  # the single call's check, point by point, raises for the first singular M
            _check_mass(scene, Mi)


def _assembly(residual: np.ndarray, force_scale: float) -> Assembly:
    """A one-point Assembly carrying what the single call's checks read (for their error messages)."""
    return Assembly(residual=residual, force_scale=float(force_scale), M=None, C=None, K=None,
                    rounding_scale_C=0.0, rounding_scale_K=0.0, coriolis_D=None, calls=[])  # fmt: skip
