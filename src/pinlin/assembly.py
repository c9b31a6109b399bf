"""Evaluate the equation of motion of a scene and its analytic derivatives at one point.

The equation of the free coordinates is r(q, v, a) = tau(q, v, a, fext) - Q_e(q, v)
= 0 (SPEC section 1).  :func:`assemble` evaluates r at (q, v0, a = 0) and,
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

from .elements import Evaluation
from .scene import Scene

__all__ = ["Assembly", "assemble", "external_forces"]


def _symmetric_from_upper(a: np.ndarray) -> np.ndarray:
    upper = np.triu(a)
    return upper + np.triu(upper, 1).T


def _fro(a: np.ndarray) -> float:
    return float(np.linalg.norm(a))


@dataclass
class Assembly:
    """Residual and derivatives of one scene at one point, on the full tangent space.

    Attributes
    ----------
    residual : (nv,) ndarray
        r = tau(q, v0, 0, fext) - Q_e(q, v0).
    force_scale : float
        ||tau|| + ||Q_e||, the size of what should balance (for relative residuals).
    M, C, K : (nv, nv) ndarray or None
        dr/da, dr/dv, dr/dq when asked for.
    C_pin, K_pin : (nv, nv) ndarray or None
        The parts of C and K computed by Pinocchio (they carry rounding that
        breaks exact symmetry); K_nonsym_elements is True when the elements'
        own stiffness is not exactly symmetric.
    calls : list of str
        The Pinocchio algorithms run.
    """

    residual: np.ndarray
    force_scale: float
    M: np.ndarray | None
    C: np.ndarray | None
    K: np.ndarray | None
    C_pin: np.ndarray | None
    K_pin: np.ndarray | None
    rounding_scale_C: float
    rounding_scale_K: float
    calls: list[str]


def external_forces(scene: Scene, ev: Evaluation) -> pin.StdVec_Force | None:
    """The scene's wrenches as Pinocchio's ``fext`` (one force per joint, joint frames), or None."""
    if not scene.wrenches:
        return None
    fext = pin.StdVec_Force()
    for _ in range(scene.model.njoints):
        fext.append(pin.Force.Zero())
    for wrench in scene.wrenches:
        jid, f = wrench.joint_wrench(ev)
        fext[jid] = fext[jid] + f
    return fext


def assemble(
    scene: Scene,
    q: np.ndarray,
    v: np.ndarray | None = None,
    *,
    stiffness: bool = True,
    damping: bool = False,
    mass: bool = False,
) -> Assembly:
    """Evaluate r and, as asked, K, C and M of ``scene`` at (q, v), with a = 0.

    ``q`` must already be checked (:meth:`Scene.check_configuration`); ``v``
    defaults to the steady velocity ``scene.v0``.  The static algorithms are
    used whenever v = 0.
    """
    model, data = scene.model, scene.data
    nv = model.nv
    v0 = np.asarray(scene.v0 if v is None else v, dtype=float)
    ev = Evaluation(scene, q, v0)
    fext = external_forces(scene, ev)
    extra = () if fext is None else (fext,)
    M = C = K = None

    if np.any(v0):
        zero = np.zeros(nv)
        if stiffness or damping or mass:
            dq, dv, Mu = ev.call("computeRNEADerivatives", pin.computeRNEADerivatives, model, data, q, v0, zero, *extra)
            K, C = np.array(dq), np.array(dv)
            ev.provide_mass_matrix(_symmetric_from_upper(np.array(Mu)))
            tau = np.array(data.tau)
        else:
            tau = np.array(ev.call("rnea", pin.rnea, model, data, q, v0, zero, *extra))
    elif fext is not None:
        if stiffness:
            K = np.array(ev.call("computeStaticTorqueDerivatives", pin.computeStaticTorqueDerivatives, model, data, q, fext))
            tau = np.array(data.tau)
        else:
            tau = np.array(ev.call("computeStaticTorque", pin.computeStaticTorque, model, data, q, fext))
    elif scene.has_gravity:
        if stiffness:
            K = np.array(ev.call("computeGeneralizedGravityDerivatives", pin.computeGeneralizedGravityDerivatives, model, data, q))
            tau = np.array(data.g)
        else:
            tau = np.array(ev.call("computeGeneralizedGravity", pin.computeGeneralizedGravity, model, data, q))
    else:
        tau = np.zeros(nv)
        if stiffness:
            K = np.zeros((nv, nv))
    if damping and C is None:
        C = np.zeros((nv, nv))
    if mass:
        M = ev.mass_matrix()

    C_pin = None if C is None else C.copy()
    K_pin = None if K is None else K.copy()
    Q = np.zeros(nv)
    K_el = np.zeros((nv, nv)) if stiffness else None
    C_el = np.zeros((nv, nv)) if damping else None
    for element in scene.elements:
        if not element.is_wrench:
            Q += element.generalized_force(ev)
        if stiffness:
            element.add_stiffness(ev, K_el)
        if damping:
            element.add_damping(ev, C_el)

    def rounding(pin_part, el_part):
        if pin_part is None:
            return 0.0
        scale = _fro(pin_part)
        if el_part is not None and np.any(el_part != el_part.T):
            scale += _fro(el_part)
        return scale

    scale_K = rounding(K_pin, K_el)
    scale_C = rounding(C_pin, C_el)
    if stiffness:
        K = K + K_el
    if damping:
        C = C + C_el
    return Assembly(
        residual=tau - Q,
        force_scale=_fro(tau) + _fro(Q),
        M=M,
        C=C,
        K=K,
        C_pin=C_pin,
        K_pin=K_pin,
        rounding_scale_C=scale_C,
        rounding_scale_K=scale_K,
        calls=ev.calls,
    )
