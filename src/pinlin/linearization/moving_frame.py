"""The velocity term a moving reference adds to deviations in its tangent space (theory: steady motions).

Along a steady motion Pinocchio's velocity v0 is constant and the reference is
q*(t) = integrate(q0, t v0).  Deviations are right (local) increments,
q(t) = integrate(q*(t), x(t)), and the velocity of q(t) is

.. math::  v = v_0 + \\dot x + A x + O(|x|^2)

with A block-diagonal over the joints: for a joint whose configuration is a Lie group
g with right increments, g = g_0 exp(t v_0) exp(x) has the body velocity
Ad_{exp(-x)} v_0 + x' + O(|x|^2), so A = ad_{v_0}.  That is Pinocchio's
``pin.Motion(v0).action`` on a free flyer ((linear, angular) twist order), [w0]x on a
spherical joint, the se(2) ad on a planar joint, and 0 on joints whose configuration
space is a vector space or abelian (1-DOF joints, translation).

The linearized equations then read M x'' + (C + M A) x' + (K + C A) x = 0 with C and
K the derivatives of the equations at (q0, v0, a = 0).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..errors import ConfigurationError, ParameterError

__all__ = ["moving_frame_matrix", "ABELIAN_JOINTS"]

#: Multi-DOF joints whose configuration space is a vector space (integrate is q + v): A = 0 on them, as
#: on every 1-DOF joint (a revolute, prismatic, helical or continuous joint's group is abelian).
ABELIAN_JOINTS = frozenset({"JointModelTranslation", "JointModelSphericalZYX", "JointModelUniversal"})


def moving_frame_matrix(model, v0) -> np.ndarray:
    """A (nv x nv) with v = v0 + x' + A x + O(|x|^2) for q(t) = integrate(integrate(q0, t v0), x(t)).

    Parameters
    ----------
    model : pinocchio.Model
    v0 : (nv,) array
        The reference velocity (Pinocchio's: a free flyer's in its local frame).

    Returns
    -------
    (nv, nv) ndarray
        Block-diagonal: ad_{v0} per free-flyer, spherical or planar joint, zero elsewhere.
        It does not depend on q0.

    Raises
    ------
    ConfigurationError
        v0 is not nv finite numbers.
    ParameterError
        Named ``model``: a joint whose configuration space is not handled (composite,
        mimic, ellipsoid joints), naming the joint.

    Examples
    --------
    A free flyer spinning about z at 2 rad/s: the deviations turn with the body frame.

    >>> import pinocchio as pin
    >>> model = pin.Model()
    >>> _ = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "body")
    >>> A = moving_frame_matrix(model, [0, 0, 0, 0, 0, 2.0])
    >>> print(np.round(A[:3, :3], 6) + 0.0)
    [[ 0. -2.  0.]
     [ 2.  0.  0.]
     [ 0.  0.  0.]]
    """
    v0 = np.asarray(v0, dtype=float)
    if v0.shape != (model.nv,) or not np.all(np.isfinite(v0)):
        raise ConfigurationError(f"v0 must be {model.nv} finite numbers (nv), got shape {v0.shape}")
    A = np.zeros((model.nv, model.nv))
    for jid in range(1, model.njoints):
        joint = model.joints[jid]
        kind, i, k = joint.shortname(), joint.idx_v, joint.nv
        w = v0[i : i + k]
        if kind == "JointModelFreeFlyer":
            A[i : i + 6, i : i + 6] = pin.Motion(w).action
        elif kind == "JointModelSpherical":
            A[i : i + 3, i : i + 3] = pin.skew(w)
        elif kind == "JointModelPlanar":
            # se(2), v = (vx, vy, wz): ad_v (x_v, x_w) = (wz J x_v - x_w J v_xy, 0), J the quarter turn
            A[i : i + 3, i : i + 3] = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [0.0, 0.0, 0.0]]
        elif not ((k == 1 and "Mimic" not in kind) or kind in ABELIAN_JOINTS):
            raise ParameterError(
                "model",
                f"joint {model.names[jid]!r} ({kind}): the moving-frame term is known for free-flyer, spherical, "
                f"planar, 1-DOF and {sorted(ABELIAN_JOINTS)} joints",
            )
    return A
