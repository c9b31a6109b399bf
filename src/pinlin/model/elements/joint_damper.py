"""Viscous joint dampers."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from .base import Element, ElementGroup, as_matrix, check_psd

if TYPE_CHECKING:  # pragma: no cover
    from ...linearization.workspace import Evaluation
    from ..robot import Robot

__all__ = ["JointDamper", "DamperGroup"]


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
    symmetric_stiffness: ClassVar[bool] = True

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

    @classmethod
    def group(cls, elements: tuple[Element, ...], robot: Robot) -> ElementGroup:
        return DamperGroup(elements, robot)


class DamperGroup(ElementGroup):
    """Dampers on 1-DOF joints as arrays; the others one by one."""

    def __init__(self, elements: tuple[JointDamper, ...], robot: Robot):
        simple = [e for e in elements if robot.joint(e.joint).nv == 1 and e.damping.ndim < 2]
        super().__init__(tuple(e for e in elements if e not in simple))
        self.iv = np.array([robot.joint(e.joint).idx_v for e in simple], dtype=int)
        self.c = np.array([float(np.ravel(e.damping)[0]) for e in simple])
        self.unique = len(set(self.iv.tolist())) == len(self.iv)
        self.symmetric_stiffness = True

    def add_force(self, ev: Evaluation, Q: np.ndarray) -> None:
        if len(self.iv) and not ev.at_rest:
            if self.unique:
                Q[self.iv] -= self.c * ev.v[self.iv]
            else:
                np.subtract.at(Q, self.iv, self.c * ev.v[self.iv])
        super().add_force(ev, Q)

    def add_damping(self, ev: Evaluation, C: np.ndarray) -> None:
        if len(self.iv):
            if self.unique:
                C[self.iv, self.iv] += self.c
            else:
                np.add.at(C, (self.iv, self.iv), self.c)
        super().add_damping(ev, C)
