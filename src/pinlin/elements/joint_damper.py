"""Viscous joint dampers."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from .base import Element, Evaluation, as_matrix, check_psd

if TYPE_CHECKING:  # pragma: no cover
    from ..robot import Robot

__all__ = ["JointDamper"]


@dataclass(frozen=True, eq=False)
class JointDamper(Element):
    """A viscous damper on one joint's velocity (SPEC section 2).

    .. math::  Q = -c\\, v_j

    Parameters
    ----------
    joint : str
        Joint name.
    damping : float, (nv,) or (nv, nv) array
        [N m s/rad] or [N s/m]; a number, a diagonal, or a symmetric psd matrix.
    """

    joint: str
    damping: float | np.ndarray

    kind: ClassVar[str] = "damper"

    def __post_init__(self):
        object.__setattr__(self, "damping", check_psd(self.damping, f"JointDamper({self.joint!r}).damping"))

    def check(self, robot: Robot) -> None:
        j = robot.joint(self.joint)
        as_matrix(self.damping, j.nv, f"JointDamper({self.joint!r}).damping")

    def generalized_force(self, ev: Evaluation) -> np.ndarray:
        j = ev.robot.joint(self.joint)
        Q = np.zeros(ev.model.nv)
        Q[j.v_slice] = -as_matrix(self.damping, j.nv, "damping") @ ev.v[j.v_slice]
        return Q

    def add_damping(self, ev: Evaluation, C: np.ndarray) -> None:
        j = ev.robot.joint(self.joint)
        C[j.v_slice, j.v_slice] += as_matrix(self.damping, j.nv, "damping")
