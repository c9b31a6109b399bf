"""Follower (body-fixed) and dead (world-fixed) wrenches on a frame."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from .base import WrenchElement, check_vector3

__all__ = ["FollowerWrench", "DeadWrench"]


def _skew(a: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


@dataclass(frozen=True, eq=False)
class FollowerWrench(WrenchElement):
    """A force and torque at a frame origin, constant in the frame's own axes.

    The load turns with the body, so its stiffness is in general not symmetric:
    its skew part is the circulatory matrix N (theory: elements).  Pinocchio's
    ``computeRNEADerivatives`` with ``fext`` differentiates exactly this load
    (the wrench held constant in the joint frame), so the element adds nothing
    to K itself.

    Parameters
    ----------
    frame : str
        Frame name (link, joint or fixed frame).
    force : 3 floats
        [N], in the frame's axes.
    torque : 3 floats
        [N m], in the frame's axes.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> push = pinlin.FollowerWrench("tip", force=[0.0, 0.0, 1.0])  # along the bar: Ziegler's column
    >>> sys = pinlin.linearize(pinlin.Scene(robot, [push]), np.zeros(2))
    >>> np.round(sys.N, 6)  # a follower load is circulatory
    array([[ 0.  ,  0.35],
           [-0.35,  0.  ]])
    """

    frame: str
    force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    torque: np.ndarray = field(default_factory=lambda: np.zeros(3))

    kind: ClassVar[str] = "follower"
    invariance: ClassVar[str] = "body-fixed load"
    symmetric_stiffness: ClassVar[bool] = True  # it adds nothing: Pinocchio differentiates it
    body_fixed: ClassVar[bool] = True

    def __post_init__(self):
        object.__setattr__(self, "force", check_vector3(self.force, f"FollowerWrench({self.frame!r}).force"))
        object.__setattr__(self, "torque", check_vector3(self.torque, f"FollowerWrench({self.frame!r}).torque"))

    def local_wrench(self, ev) -> np.ndarray:
        return np.concatenate([self.force, self.torque])


@dataclass(frozen=True, eq=False)
class DeadWrench(WrenchElement):
    """A force and torque at a frame origin, constant in world axes.

    In the frame's axes the wrench is (R^T F, R^T T), which turns against the
    body; with R(q + dq) = R exp([J_w dq]x) its derivative is
    d(R^T F)/dq = [R^T F]x J_w.  So beyond Pinocchio's follower derivative
    the element adds

    .. math::  K \\mathrel{-}= J^T \\begin{bmatrix}[F_l]_\\times\\\\ [T_l]_\\times\\end{bmatrix} J_\\omega

    with J the frame Jacobian in local axes and J_w its angular rows; no
    kinematic Hessian is needed.  A pure dead force is conservative (symmetric
    stiffness); a dead torque in three dimensions is not.

    Parameters
    ----------
    frame : str
        Frame name.
    force : 3 floats
        [N], in world axes.
    torque : 3 floats
        [N m], in world axes.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> weight = pinlin.DeadWrench("tip", force=[0.0, 0.0, -1.0])
    >>> sys = pinlin.linearize(pinlin.Scene(robot, [weight]), np.zeros(2))
    >>> bool(np.any(sys.N))  # a dead load is conservative
    False
    """

    frame: str
    force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    torque: np.ndarray = field(default_factory=lambda: np.zeros(3))

    kind: ClassVar[str] = "dead"
    invariance: ClassVar[str] = "dead load"

    def __post_init__(self):
        object.__setattr__(self, "force", check_vector3(self.force, f"DeadWrench({self.frame!r}).force"))
        object.__setattr__(self, "torque", check_vector3(self.torque, f"DeadWrench({self.frame!r}).torque"))

    def local_wrench(self, ev) -> np.ndarray:
        R = ev.frame_rotation(ev.robot.frame_id(self.frame))
        return np.concatenate([R.T @ self.force, R.T @ self.torque])

    def add_stiffness(self, ev, K: np.ndarray) -> None:
        fid = ev.robot.frame_id(self.frame)
        J = ev.frame_jacobian(fid)
        w = self.local_wrench(ev)
        dw = np.vstack([_skew(w[:3]), _skew(w[3:])]) @ J[3:]
        K -= J.T @ dw
