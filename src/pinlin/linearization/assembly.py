"""Evaluate the equation of motion of a scene and its analytic derivatives at one point.

The equation of the free coordinates is r(q, v, a) = tau(q, v, a, fext) - Q_e(q, v)
= 0 (theory: equations).  :func:`assemble` evaluates r at (q, v0, a = 0) and,
on request, M = dr/da, C = dr/dv and K = dr/dq on the whole tangent space,
running only the Pinocchio algorithms the scene calls for:

============================  ==========================================================
scene                          Pinocchio algorithms
============================  ==========================================================
no prescribed joint            ``crba`` for M (if asked); for K and the residual
                               ``computeStaticTorqueDerivatives`` with ``fext`` when the
                               scene has wrenches, else ``computeGeneralizedGravityDerivatives``
                               when gravity is nonzero, else nothing.  No velocity
                               derivative is computed: C comes from the elements alone.
prescribed joint velocities    ``computeRNEADerivatives`` (with ``fext`` only when the
                               scene has wrenches): K, C and M in one pass.
dead wrench                    adds ``computeJointJacobians`` + ``updateFramePlacements``
                               (its orientation and Jacobian; no kinematic Hessian).
Rayleigh damping (alpha > 0)   M, from the pass above or ``crba``.
residual only                  ``computeStaticTorque`` / ``computeGeneralizedGravity`` /
                               ``rnea``, or nothing.
============================  ==========================================================
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..model.evaluation import Evaluation, Workspace, symmetric_from_upper
from ..model.scene import Scene
from ..numerics.norms import fro
from .plan import plan_of

__all__ = ["Assembly", "assemble", "external_forces"]






@dataclass(slots=True)
class Assembly:
    """Residual and derivatives of one scene at one point, on the full tangent space.

    Attributes
    ----------
    residual : (nv,) ndarray
        r = tau(q, v, 0, fext) - Q_e(q, v).
    force_scale : float
        ||tau|| + ||Q_e|| (+ ||K||_F when K is computed): the size of the forces
        that should balance, or that a unit displacement [rad or m] would create,
        used for relative residuals.  The stiffness term keeps the scale honest
        when nothing is loaded in the generalized sense at equilibrium (a load
        along a bar, or a wrench alone balancing a spring, where tau vanishes).
    M, C, K : (nv, nv) ndarray or None
        dr/da, dr/dv, dr/dq when asked for.  At rest, C may be the scene plan's
        constant element damping (a read-only view): do not modify it in place.
    rounding_scale_C, rounding_scale_K : float
        Norm of the parts of C and K that carry rounding breaking their exact
        (skew-)symmetry: what Pinocchio computed, plus the elements whose
        stiffness is not exactly symmetric.
    coriolis_D : (nv, nv) ndarray or None
        Symmetric part of Pinocchio's dtau/dv (zero in exact arithmetic for a
        time-invariant steady motion; rounding otherwise); C itself when the
        elements add no damping (``plan.undamped``): its symmetric part is then
        the one the split forms from C, entry for entry (not formed twice).
    calls : list of str
        The Pinocchio algorithms run.
    """

    residual: np.ndarray
    force_scale: float
    M: np.ndarray | None
    C: np.ndarray | None
    K: np.ndarray | None
    rounding_scale_C: float
    rounding_scale_K: float
    coriolis_D: np.ndarray | None
    calls: list[str]


def external_forces(scene: Scene, ev: Evaluation) -> pin.StdVec_Force | None:
    """The scene's wrenches as Pinocchio's ``fext`` (one force per joint, joint frames), or None.

    Follower wrenches come from the scene's precomputed constant part; world-fixed
    wrenches are re-expressed at ``ev.q``.
    """
    if scene.constant_fext is None:
        return None
    if not scene.varying_wrenches:
        return scene.constant_fext
    fext = pin.StdVec_Force(scene.constant_fext)
    for wrench in scene.varying_wrenches:
        jid, f = wrench.joint_wrench(ev, scene.model, scene.robot)
        fext[jid] = fext[jid] + f
    return fext


def _dynamics(ev: Evaluation, fext, stiffness: bool, derivatives: bool, a: np.ndarray | None = None):
    """Pinocchio's part at (q, v, a) (a = 0 unless given): (tau, K, C, M or None); only the algorithm the
    point needs.

    ``derivatives``: any of K, C, M asked for (with a velocity or an acceleration, one
    RNEA-derivative pass gives all three).  tau, K and C are fresh arrays the caller may modify.
    """
    model, data, q = ev.model, ev.data, ev.q
    extra = () if fext is None else (fext,)
    if not ev.at_rest or a is not None:
        zero = np.zeros(model.nv) if a is None else a
        if not derivatives:
            return np.array(ev.call("rnea", pin.rnea, model, data, q, ev.v, zero, *extra)), None, None, None
        dq, dv, Mu = ev.call("computeRNEADerivatives", pin.computeRNEADerivatives, model, data, q, ev.v, zero, *extra)
        ev.provide_mass_matrix(symmetric_from_upper(Mu, ev.ws))  # views of Data: copied
        return data.tau.copy(), np.array(dq), np.array(dv), ev.mass_matrix()
    if fext is not None:
        if stiffness:  # the binding returns a fresh array
            K = ev.call("computeStaticTorqueDerivatives", pin.computeStaticTorqueDerivatives, model, data, q, fext)
            return data.tau.copy(), K, None, None
        return ev.call("computeStaticTorque", pin.computeStaticTorque, model, data, q, fext), None, None, None
    if ev.scene.has_gravity:
        if stiffness:
            K = ev.call("computeGeneralizedGravityDerivatives", pin.computeGeneralizedGravityDerivatives, model, data, q)
            return data.g.copy(), K, None, None
        return ev.call("computeGeneralizedGravity", pin.computeGeneralizedGravity, model, data, q), None, None, None
    nv = model.nv
    return np.zeros(nv), (np.zeros((nv, nv)) if stiffness else None), None, None


def assemble(
    scene: Scene,
    q: np.ndarray,
    v: np.ndarray | None = None,
    *,
    stiffness: bool = True,
    damping: bool = False,
    mass: bool = False,
    ws: Workspace | None = None,
    a: np.ndarray | None = None,
) -> Assembly:
    """Evaluate r and, as asked, K, C and M of ``scene`` at (q, v, a), with a = 0 unless given.

    ``q`` must already be checked (:meth:`Scene.check_configuration`); ``v``
    defaults to the steady velocity ``scene.v0``.  The static algorithms are
    used whenever v = 0 and no acceleration is given.  ``a`` (nv,): the actual
    acceleration of a motion (theory: Floquet: the variational equation along a
    periodic orbit), evaluated with ``computeRNEADerivatives(q, v, a)``; the residual is
    then tau(q, v, a) - Q_e.  Pinocchio writes into ``ws`` (default: the calling
    thread's workspace for the scene).
    """
    plan = plan_of(scene)
    if v is None:
        v0, at_rest = scene.v0, not plan.moving
    else:
        v0 = np.asarray(v, dtype=float)
        at_rest = not np.count_nonzero(v0)
    ev = Evaluation(scene, q, v0, ws, at_rest=at_rest)
    nv = scene.model.nv
    tau, K, C, M = _dynamics(ev, external_forces(scene, ev), stiffness, stiffness or damping or mass, a)
    coriolis_D = None
    scale_C = 0.0
    each_damping = damping  # the groups add their damping at this point
    if C is not None:
        scale_C = fro(C)
        if damping:
            if plan.undamped:  # C stays Pinocchio's alone: the split's D of C is this part, bitwise
                coriolis_D = C
            else:
                coriolis_D = C + C.T  # (C + C^T) / 2
                coriolis_D *= 0.5
    elif damping:  # at rest: C is the elements' damping alone
        if plan.rest_damping is None:
            C = np.zeros((nv, nv))
        else:  # constant: added up once per scene, bitwise the same sum (read-only)
            C, each_damping = plan.rest_damping.C.view(), False
    if mass and M is None:
        M = ev.mass_matrix()
    scale_K = fro(K) if stiffness else 0.0
    Q = np.zeros(nv)
    for group in scene.groups:
        group.add_force(ev, Q)
        if stiffness:
            group.add_stiffness(ev, K)
        if each_damping:
            group.add_damping(ev, C)
    if stiffness:
        for wrench in scene.varying_wrenches:
            wrench.add_stiffness(ev, K)
    K_norm = fro(K) if stiffness else 0.0
    if stiffness and not plan.symmetric_elements:
        scale_K += K_norm
    return Assembly(
        residual=tau - Q,
        force_scale=fro(tau) + fro(Q) + K_norm,
        M=M,
        C=C,
        K=K,
        rounding_scale_C=scale_C,
        rounding_scale_K=scale_K,
        coriolis_D=coriolis_D,
        calls=ev.calls,
    )
