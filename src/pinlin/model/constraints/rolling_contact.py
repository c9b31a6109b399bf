"""The rolling contact of a thin disk on a plane: contact point, Jacobian, derivatives (theory: constraints).

A thin rigid disk of radius r is centred at a frame's origin o, its axle along the
unit vector a of that frame (a_w = R a in world axes).  On a plane of unit normal n
(world axes) the contact point is the rim's lowest point

.. math::  u = \\frac{n - (n\\cdot a_w)\\, a_w}{|n - (n\\cdot a_w)\\, a_w|},\\qquad c = o - r u

and the velocity of the wheel's material point at c is J(q) v with
J = J_lin + r [u]x J_ang, from the frame's LOCAL_WORLD_ALIGNED Jacobian.  The normal
row n^T J is the gradient of the holonomic condition n.c = height; the two other
rows are the nonholonomic conditions of rolling without slipping.

The kernels below give c, J and the derivatives a linearization needs, all in the
tangent space of Pinocchio's right increments ``pin.integrate(q, dq)``:

- :func:`contact_velocity_derivative`: P0 = d(J(q) v)/dq at fixed v, which is also
  the drift of the constraint, d/dt(J) v = P0(q, v) v;
- :func:`contact_force_stiffness`: K_lam = d(J(q)^T lam)/dq at fixed lam, the
  stiffness of a world force lam at the material point at c (c moves on the rim).

Both differentiate u through the axle's rotation, d a_w = (J_ang dq) x a_w.  Each
call runs the Pinocchio pass it needs on ``data`` (the caller's workspace).
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from ...errors import ConstraintError, ParameterError
from ..elements.base import check_vector3
from ..numbers import numeric_scalar
from .stiffness import CONSTANT_SUBSPACE_JOINTS, dead_wrench_stiffness

__all__ = [
    "FLAT_TOL",
    "contact_point",
    "contact_jacobian",
    "contact_velocity_derivative",
    "contact_force_stiffness",
]

#: Smallest |n - (n.a_w) a_w| (the sine of the angle between axle and normal) for which the
#: wheel has a lowest point; below it the wheel lies flat and u, with its 1/sine derivatives, is undefined.
FLAT_TOL = 1e-6

_LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def contact_point(model, data, frame_id, radius, axis, normal, q, *, flat_tol: float = FLAT_TOL) -> np.ndarray:
    """The contact point c = o - r u of a disk on a plane (3,), world axes [m].

    Parameters
    ----------
    model, data : pinocchio.Model, pinocchio.Data
        ``data`` is the workspace this call updates (frame placements at q).
    frame_id : int
        The wheel frame: its origin is the disk's centre.
    radius : float
        r > 0 [m].
    axis : 3 floats
        The axle in the wheel frame (normalized here).
    normal : 3 floats
        The plane's normal in world axes, pointing out of the ground (normalized here).
    q : (nq,) array
    flat_tol : float
        See :data:`FLAT_TOL`.

    Raises
    ------
    ParameterError
        A frame id out of range, a radius that is not a finite number > 0, an axis or a
        normal of zero length or not 3 finite numbers.
    ConstraintError
        The axle is parallel to the normal within ``flat_tol``: the wheel lies flat.

    Examples
    --------
    >>> import pinocchio as pin
    >>> model = pin.Model()
    >>> joint = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "disk")
    >>> wheel = model.addJointFrame(joint)
    >>> q = pin.neutral(model); q[:3] = (1.0, 2.0, 0.3)
    >>> c = contact_point(model, model.createData(), wheel, 0.3, (0, 1, 0), (0, 0, 1), q)
    >>> print(np.round(c, 12) + 0.0)
    [1. 2. 0.]
    """
    radius, axis, normal = _checked(model, frame_id, radius, axis, normal)
    pin.framesForwardKinematics(model, data, np.asarray(q, dtype=float))
    o, _, u, _ = _rim(model, data, frame_id, axis, normal, flat_tol)
    return o - radius * u


def contact_jacobian(
    model, data, frame_id, radius, axis, normal, q, *, height: float = 0.0, flat_tol: float = FLAT_TOL
) -> tuple[np.ndarray, float]:
    """J (3 x nv), the velocity of the wheel's material point at c, and the height gap h = n.c - height.

    .. math::  J = J_{lin}(o) + r\\,[u]_\\times J_{ang},\\qquad h = n\\cdot c - \\mathrm{height}

    J_lin, J_ang are the rows of the frame's LOCAL_WORLD_ALIGNED Jacobian; n^T J is dh/dq.
    Parameters as :func:`contact_point`; ``height`` [m] is the plane's offset along n.

    Returns
    -------
    J : (3, nv) ndarray
        World axes.
    h : float
        [m]; zero when the disk touches the plane.

    Raises
    ------
    ParameterError, ConstraintError
        As :func:`contact_point`; a height that is not a finite number.

    Examples
    --------
    >>> import pinocchio as pin
    >>> model = pin.Model()
    >>> joint = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "disk")
    >>> wheel = model.addJointFrame(joint)
    >>> q = pin.neutral(model); q[2] = 0.5
    >>> J, h = contact_jacobian(model, model.createData(), wheel, 0.3, (0, 1, 0), (0, 0, 1), q)
    >>> print(np.round(J, 12) + 0.0, f"{h:.6f}")
    [[ 1.   0.   0.   0.  -0.3  0. ]
     [ 0.   1.   0.   0.3  0.   0. ]
     [ 0.   0.   1.   0.   0.   0. ]] 0.200000
    """
    radius, axis, normal = _checked(model, frame_id, radius, axis, normal)
    height = numeric_scalar(height, "height")
    if not math.isfinite(height):
        raise ParameterError("height", f"must be a finite number, got {height!r}")
    pin.computeJointJacobians(model, data, np.asarray(q, dtype=float))
    o, J6, u, _ = _frame_terms(model, data, frame_id, axis, normal, flat_tol)
    c = o - radius * u
    return J6[:3] + radius * pin.skew(u) @ J6[3:], float(normal @ c - height)


def contact_velocity_derivative(
    model, data, frame_id, radius, axis, normal, q, v, *, flat_tol: float = FLAT_TOL
) -> np.ndarray:
    """P0 = d(J(q) v)/dq at fixed v (3 x nv), tangent space of ``pin.integrate``.

    .. math::  P_0 = \\frac{\\partial v_o}{\\partial q}
        + r\\left([u]_\\times \\frac{\\partial \\omega}{\\partial q} - [\\omega]_\\times \\frac{\\partial u}{\\partial q}\\right)

    with v_o, omega the frame's LOCAL_WORLD_ALIGNED velocity (Pinocchio's velocity derivatives,
    plus omega x do for the moving origin) and du/dq through the axle's rotation.  P0(q, v) v
    is the drift d/dt(J) v of the rolling constraint.  Parameters as :func:`contact_point`,
    with the velocity ``v`` (nv,).  A free flyer's velocity is Pinocchio's, in its local frame.

    Raises
    ------
    ParameterError, ConstraintError
        As :func:`contact_point`.

    Examples
    --------
    A free disk moving along x at 0.6 m/s and spinning at 2 rad/s about its axle (rolling):
    turning it about its axle turns its local velocity, whose vertical part changes by -0.6 per radian:

    >>> import pinocchio as pin
    >>> model = pin.Model()
    >>> joint = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "disk")
    >>> wheel = model.addJointFrame(joint)
    >>> q = pin.neutral(model); q[2] = 0.3
    >>> v = np.array([0.6, 0, 0, 0, 2.0, 0])
    >>> P0 = contact_velocity_derivative(model, model.createData(), wheel, 0.3, (0, 1, 0), (0, 0, 1), q, v)
    >>> print(np.round(P0, 12) + 0.0)
    [[ 0.   0.   0.   0.   0.   0. ]
     [ 0.   0.   0.   0.   0.   0. ]
     [ 0.   0.   0.   0.  -0.6  0. ]]
    """
    radius, axis, normal = _checked(model, frame_id, radius, axis, normal)
    q, v = np.asarray(q, dtype=float), np.asarray(v, dtype=float)
    pin.computeForwardKinematicsDerivatives(model, data, q, v, np.zeros(model.nv))  # also fills the joint Jacobians
    dvel_dq, _ = pin.getFrameVelocityDerivatives(model, data, frame_id, _LWA)
    dvel_dq = np.reshape(dvel_dq, (6, model.nv))  # (6,) from the binding when nv = 1
    _, J6, u, du = _frame_terms(model, data, frame_id, axis, normal, flat_tol)
    omega = J6[3:] @ v
    # Pinocchio's LOCAL_WORLD_ALIGNED derivative is that of the velocity of the world point at o held
    # fixed (v_o + omega x (p - o) at p = o); the origin moves by do = J_lin dq, which adds omega x do.
    dvo_dq = dvel_dq[:3] + pin.skew(omega) @ J6[:3]
    return dvo_dq + radius * (pin.skew(u) @ dvel_dq[3:] - pin.skew(omega) @ du)


def contact_force_stiffness(
    model, data, frame_id, radius, axis, normal, q, lam, *, flat_tol: float = FLAT_TOL
) -> np.ndarray:
    """K_lam = d(J(q)^T lam)/dq at fixed lam (nv x nv), tangent space of ``pin.integrate``.

    J^T lam is the generalized force of the world force lam [N] at the wheel's
    material point at c, i.e. of the wrench (lam, r lam x u) at the frame's origin.
    Its derivative is the dead-wrench stiffness of that wrench
    (:func:`~pinlin.model.constraints.dead_wrench_stiffness`) plus the turn of the
    torque arm as c moves on the rim:

    .. math::  K_\\lambda = K_{dead}(\\lambda, r\\,\\lambda\\times u) + r\\, J_{ang}^T [\\lambda]_\\times \\frac{\\partial u}{\\partial q}

    Parameters as :func:`contact_point`, with the force ``lam`` (3,) in world axes.

    Raises
    ------
    ParameterError, ConstraintError
        As :func:`contact_point`; a joint moving the frame whose motion subspace depends
        on the configuration (see :data:`~pinlin.model.constraints.CONSTANT_SUBSPACE_JOINTS`).

    Examples
    --------
    An upward load of 10 N on an upright disk: leaning it by a moves the contact point
    sideways by r a under the load, a lean moment of r * 10 * a that tips it further:

    >>> import pinocchio as pin
    >>> model = pin.Model()
    >>> joint = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "disk")
    >>> wheel = model.addJointFrame(joint)
    >>> q = pin.neutral(model); q[2] = 0.3
    >>> K = contact_force_stiffness(model, model.createData(), wheel, 0.3, (0, 1, 0), (0, 0, 1), q, (0, 0, 10.0))
    >>> print(f"{K[3, 3]:.6f}")
    3.000000
    """
    radius, axis, normal = _checked(model, frame_id, radius, axis, normal)
    lam = check_vector3(lam, "lam")
    _check_chain(model, frame_id)
    pin.computeJointJacobians(model, data, np.asarray(q, dtype=float))
    _, J6, u, du = _frame_terms(model, data, frame_id, axis, normal, flat_tol)
    torque = radius * np.cross(lam, u)
    K = dead_wrench_stiffness(J6[None], lam[None], torque[None], _dof_order(model))
    return K + radius * J6[3:].T @ pin.skew(lam) @ du


def _checked(model, frame_id, radius, axis, normal) -> tuple[float, np.ndarray, np.ndarray]:
    """The radius as a float, the axis and the normal as unit vectors; ParameterError for bad values."""
    if not (isinstance(frame_id, (int, np.integer)) and 0 <= frame_id < model.nframes):
        raise ParameterError("frame_id", f"expected a frame index in [0, {model.nframes}), got {frame_id!r}")
    r = numeric_scalar(radius, "radius")
    if not (math.isfinite(r) and r > 0):
        raise ParameterError("radius", f"must be a finite number > 0, got {radius!r}")
    units = []
    for label, value in (("axis", axis), ("normal", normal)):
        vec = check_vector3(value, label)
        size = float(np.linalg.norm(vec))
        if size == 0:
            raise ParameterError(label, "must not be zero")
        units.append(vec / size)
    return r, units[0], units[1]


def _rim(model, data, frame_id, axis, normal, flat_tol) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Origin o, axle a_w, lowest direction u and s = |n - (n.a_w) a_w| from ``data.oMf[frame_id]``."""
    placement = data.oMf[frame_id]
    a_w = placement.rotation @ axis
    p = normal - (normal @ a_w) * a_w
    s = float(np.linalg.norm(p))
    if not s > flat_tol:
        name = model.frames[frame_id].name
        raise ConstraintError(
            f"wheel frame {name!r}: the axle is parallel to the ground normal (|n - (n.a) a| = {s:.3g} <= "
            f"flat_tol = {flat_tol:g}): the wheel lies flat and has no lowest point",
            constraints=(name,),
        )
    return placement.translation.copy(), a_w, p / s, s


def _frame_terms(model, data, frame_id, axis, normal, flat_tol):
    """o, the LOCAL_WORLD_ALIGNED frame Jacobian (6 x nv), u and du/dq (3 x nv), after the joint Jacobians.

    du/dq: d a_w = dtheta x a_w with dtheta = J_ang dq; p = n - (n.a_w) a_w, u = p / |p|.
    """
    pin.updateFramePlacement(model, data, frame_id)
    J6 = np.reshape(pin.getFrameJacobian(model, data, frame_id, _LWA), (6, model.nv))  # (6,) when nv = 1
    o, a_w, u, s = _rim(model, data, frame_id, axis, normal, flat_tol)
    da = -pin.skew(a_w) @ J6[3:]
    dp = -np.outer(a_w, normal @ da) - (normal @ a_w) * da
    du = (np.eye(3) - np.outer(u, u)) @ dp / s
    return o, J6, u, du


def _check_chain(model, frame_id) -> None:
    """ParameterError when a joint moving the frame has a configuration-dependent motion subspace."""
    for jid in model.supports[model.frames[frame_id].parentJoint]:
        joint = model.joints[jid]
        kind = joint.shortname()
        if jid and not ((joint.nv == 1 and "Mimic" not in kind) or kind in CONSTANT_SUBSPACE_JOINTS):
            raise ParameterError(
                "frame_id",
                f"joint {model.names[jid]!r} ({kind}) moves wheel frame {model.frames[frame_id].name!r}; the "
                f"contact stiffness supports 1-DOF joints and {sorted(CONSTANT_SUBSPACE_JOINTS)}",
            )


def _dof_order(model) -> np.ndarray:
    """(nv, nv) bool: [i, j] when the joint of degree of freedom j comes no later than that of i (parents first)."""
    dof_joint = np.zeros(model.nv, dtype=int)
    for jid in range(1, model.njoints):
        joint = model.joints[jid]
        dof_joint[joint.idx_v : joint.idx_v + joint.nv] = jid
    return dof_joint[None, :] <= dof_joint[:, None]
