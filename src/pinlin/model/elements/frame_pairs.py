"""Kinematics shared by the elements between two frames (spring-dampers, bushings).

Notation (theory: elements between frames).  J0 = :meth:`Evaluation.world_jacobian`: column k is
the world twist xi_k = (v_k, omega_k) of degree of freedom k (linear velocity of
the body point at the world origin).  A body's Jacobian is J0 on its supporting
joints, ``J0 * m`` with m its 0/1 support mask, and a point p of it moves with
c_k(p) = v_k + omega_k x p.

A spatial wrench W = (f, tau) (force, moment about the world origin) on a body
gives the generalized force Q_k = m_k xi_k . W.  When q moves along
degree of freedom l, xi_k turns with every joint that supports it:

.. math::  \\partial \\xi_k / \\partial q_l = T_{kl}\\, [\\xi_l, \\xi_k],\\qquad
           T_{kl} = 1 \\text{ if joint}(l) \\text{ supports joint}(k)

(its own joint included).  Hence, at fixed W,

.. math::  \\partial Q_k / \\partial q_l = T_{kl}\\, (\\xi_k \\times^* W_k) \\cdot \\xi_l

with W_k the sum of the wrenches on the bodies that degree of freedom k
supports: one (nv x nv) product for all the elements of a scene, no kinematic
Hessian.  This holds for joints whose motion subspace is constant in their own
frame and whose configuration moves by right multiplication (``pin.integrate``):
every 1-DOF joint, free-flyer, spherical, planar and translation joints;
:func:`check_supports` refuses the others.  Tests check it by finite differences
on the manifold (``pinlin.testing.check_element``).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pinocchio as pin

from ...errors import ParameterError
from ..numbers import numeric_array
from .base import Element, ElementGroup, check_vector3

__all__ = [
    "FramePairElement",
    "MULTI_DOF_JOINTS",
    "check_supports",
    "support_mask",
    "ancestor_mask",
    "as_placement",
    "cross",
    "cross_motion",
    "cross_force",
    "fixed_wrench_stiffness",
]

#: Multi-DOF joints whose motion subspace is constant in the joint frame and whose
#: configuration moves by right multiplication: the derivative rule above holds.
MULTI_DOF_JOINTS = frozenset({"JointModelFreeFlyer", "JointModelSpherical", "JointModelPlanar", "JointModelTranslation"})

_PLACEMENT = "a pin.SE3, a 4x4 homogeneous matrix or a mapping {'xyz': [m], 'rpy': [rad]}"

#: Largest deviation of R^T R from I (and of det R from 1) accepted for a rotation given by the user.
ROTATION_TOL = 1e-9


def check_supports(robot, frame: str, label: str) -> int:
    """The frame's id, after checking that every joint moving it follows the rule above.

    Raises
    ------
    FrameNotFoundError
        Unknown frame.
    ParameterError
        A joint moving the frame has a configuration-dependent motion subspace
        (spherical ZYX, universal, composite, mimic joints).
    """
    fid = robot.frame_id(frame)
    model = robot.model
    for jid in model.supports[model.frames[fid].parentJoint]:
        if jid == 0:
            continue
        joint = model.joints[jid]
        kind = joint.shortname()
        if not ((joint.nv == 1 and "Mimic" not in kind) or kind in MULTI_DOF_JOINTS):
            raise ParameterError(
                label,
                f"joint {model.names[jid]!r} ({kind}) moves frame {frame!r}; elements between frames support "
                f"1-DOF joints and {sorted(MULTI_DOF_JOINTS)} (constant motion subspace)",
            )
    return fid


def support_mask(model: pin.Model, joint_id: int) -> np.ndarray:
    """0/1 mask (nv,) of the degrees of freedom of the joints supporting ``joint_id`` (itself included)."""
    mask = np.zeros(model.nv)
    for jid in model.supports[joint_id]:
        if jid > 0:
            mask[model.idx_vs[jid] : model.idx_vs[jid] + model.nvs[jid]] = 1.0
    return mask


def ancestor_mask(model: pin.Model) -> np.ndarray:
    """T (nv x nv, 0/1): T[k, l] = 1 when the joint of dof l supports the joint of dof k."""
    T = np.zeros((model.nv, model.nv))
    for jid in range(1, model.njoints):
        rows = slice(model.idx_vs[jid], model.idx_vs[jid] + model.nvs[jid])
        T[rows] = support_mask(model, jid)
    return T


def as_placement(value, label: str) -> pin.SE3:
    """A placement from a ``pin.SE3``, a (4, 4) homogeneous matrix or a mapping ``{"xyz": [m], "rpy": [rad]}``.

    The mapping follows URDF's ``<origin>``: R = Rz(yaw) Ry(pitch) Rx(roll); a
    missing entry is zero.

    Raises
    ------
    ParameterError
        Not a placement: wrong shape, non-finite, last row not (0, 0, 0, 1), a
        rotation block that is not a rotation (to :data:`ROTATION_TOL`), or a
        mapping with other keys than xyz and rpy.
    """
    if isinstance(value, pin.SE3):
        value = value.homogeneous
    elif isinstance(value, Mapping):
        unknown = sorted(set(value) - {"xyz", "rpy"})
        if unknown:
            raise ParameterError(label, f"unknown key {unknown[0]!r}; a placement mapping has 'xyz' [m] and 'rpy' [rad]")
        xyz, rpy = (check_vector3(value.get(k, np.zeros(3)), f"{label}.{k}") for k in ("xyz", "rpy"))
        return pin.SE3(pin.rpy.rpyToMatrix(*rpy), xyz)
    H = numeric_array(value, label, _PLACEMENT)
    if H.shape != (4, 4):
        raise ParameterError(label, f"expected {_PLACEMENT}, got shape {H.shape}")
    if not np.all(np.isfinite(H)):
        raise ParameterError(label, "must be finite")
    if np.abs(H[3] - [0.0, 0.0, 0.0, 1.0]).max() > 0:
        raise ParameterError(label, f"the last row of a homogeneous matrix must be (0, 0, 0, 1), got {H[3]}")
    R = H[:3, :3]
    if np.abs(R.T @ R - np.eye(3)).max() > ROTATION_TOL or abs(np.linalg.det(R) - 1.0) > ROTATION_TOL:
        raise ParameterError(label, "the 3x3 block is not a rotation (orthonormal, determinant +1)")
    return pin.SE3(R, H[:3, 3])


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for 3-vectors stacked on axis 0, broadcasting the other axes ((3, ...) arrays).

    Written out by components: ``np.cross`` costs more than the products
    themselves on the small arrays of an element group.
    """
    return np.stack([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def cross_motion(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """[a, b] = ad(a) b for twists stacked on axis 0 ((6, ...) arrays)."""
    return np.concatenate([cross(a[3:], b[:3]) + cross(a[:3], b[3:]), cross(a[3:], b[3:])])


def cross_force(a: np.ndarray, f: np.ndarray) -> np.ndarray:
    """a x* f = -ad(a)^T f for a twist a and a wrench f stacked on axis 0 ((6, ...) arrays)."""
    return np.concatenate([cross(a[3:], f[:3]), cross(a[:3], f[:3]) + cross(a[3:], f[3:])])


def fixed_wrench_stiffness(J0: np.ndarray, T: np.ndarray, W: np.ndarray) -> np.ndarray:
    """dQ/dq at fixed spatial wrenches (nv x nv), with Q_k = xi_k . W_k.

    Parameters
    ----------
    J0 : (6, nv) world Jacobian.
    T : (nv, nv) ancestor mask (:func:`ancestor_mask`).
    W : (6, nv) column k: the sum of the spatial wrenches [N, N m] on the bodies dof k supports.
    """
    return T * (cross_force(J0, W).T @ J0)


class FramePairElement(Element):
    """An element between a frame and a target (a frame or the world), evaluated through its group.

    Subclasses (spring-dampers, bushings) have ``frame`` and ``target`` fields and a
    :meth:`~pinlin.Element.group` classmethod: one element alone is a group of one, so
    the element's own methods and the vectorized group share one implementation.
    """

    frame: str
    target: object

    def check(self, robot) -> None:
        label = f"{type(self).__name__}({self.frame!r})"
        check_supports(robot, self.frame, label)
        if isinstance(self.target, str):
            check_supports(robot, self.target, f"{label}.target")

    def needs(self) -> frozenset[str]:
        return frozenset({"frame_kinematics"})

    def _one(self, ev) -> ElementGroup:
        return type(self).group((self,), ev.robot)

    def generalized_force(self, ev) -> np.ndarray:
        Q = np.zeros(ev.model.nv)
        self._one(ev).add_force(ev, Q)
        return Q

    def add_stiffness(self, ev, K: np.ndarray) -> None:
        self._one(ev).add_stiffness(ev, K)

    def add_damping(self, ev, C: np.ndarray) -> None:
        self._one(ev).add_damping(ev, C)

    def add_elastic_stiffness(self, ev, K: np.ndarray) -> None:
        self._one(ev).add_elastic_stiffness(ev, K)
