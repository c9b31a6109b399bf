"""Viscous joint dampers."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ...numerics.arrays import readonly
from .base import DiagonalIndex, Element, ElementGroup, as_matrix, check_psd, contiguous

__all__ = ["JointDamper", "DamperGroup"]


@dataclass(frozen=True, eq=False)
class JointDamper(Element):
    """A viscous damper on one joint's velocity (theory: elements).

    .. math::  Q = -c\\, v_j

    Parameters
    ----------
    joint : str
        Joint name.
    damping : float, (nv,) or (nv, nv) array
        [N m s/rad] or [N s/m]; a number, a diagonal, or a symmetric psd matrix.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointDamper("joint2", 0.3)])
    >>> np.round(pinlin.linearize(scene, np.zeros(2)).D, 6)
    array([[0. , 0. ],
           [0. , 0.3]])
    """

    joint: str
    damping: float | np.ndarray

    kind: ClassVar[str] = "damper"
    invariance: ClassVar[str] = "joint-space"
    symmetric_stiffness: ClassVar[bool] = True

    def __post_init__(self):
        object.__setattr__(self, "damping", check_psd(self.damping, f"JointDamper({self.joint!r}).damping"))

    def check(self, robot) -> None:
        j = robot.joint(self.joint)
        as_matrix(self.damping, j.nv, f"JointDamper({self.joint!r}).damping")

    def generalized_force(self, ev) -> np.ndarray:
        j = ev.robot.joint(self.joint)
        Q = np.zeros(ev.model.nv)
        Q[j.v_slice] = -np.dot(as_matrix(self.damping, j.nv, "damping"), ev.v[j.v_slice])
        return Q

    def add_damping(self, ev, C: np.ndarray) -> None:
        j = ev.robot.joint(self.joint)
        C[j.v_slice, j.v_slice] += as_matrix(self.damping, j.nv, "damping")

    @classmethod
    def group(cls, elements: tuple[Element, ...], robot) -> ElementGroup:
        return DamperGroup(elements, robot)


class DamperGroup(ElementGroup):
    """Joint dampers with their matrices prepared once per scene.

    Dampers on 1-DOF joints with a scalar coefficient are arrays (C[iv, iv] += c
    as one flat-index update of the diagonal); the others keep their joint's
    velocity slice and damping matrix (read-only, :attr:`prepared`).  At rest
    (v = 0) the force is zero and :meth:`add_force` returns at once.  Results
    are those of the elements' own methods, bitwise.
    """

    def __init__(self, elements: tuple[JointDamper, ...], robot):
        simple = [e for e in elements if robot.joint(e.joint).nv == 1 and e.damping.ndim < 2]
        super().__init__(tuple(e for e in elements if e not in simple))
        self.iv = readonly(np.array([robot.joint(e.joint).idx_v for e in simple], dtype=int))
        self.c = readonly(np.array([float(np.ravel(e.damping)[0]) for e in simple]))
        self.unique = len(set(self.iv.tolist())) == len(self.iv)
        self.v_index = contiguous(self.iv)  # a slice when consecutive: cheaper indexing
        self.diagonal = DiagonalIndex(self.iv, robot.nv)
        self.prepared = tuple(
            (j.v_slice, readonly(as_matrix(e.damping, j.nv, "damping")))
            for e, j in ((e, robot.joint(e.joint)) for e in self.elements)
        )
        self.symmetric_stiffness = True
        self.constant_damping = True  # add_damping reads only the prepared matrices

    def add_force(self, ev, Q: np.ndarray) -> None:
        if ev.at_rest:  # Q = -C v = 0
            return
        v = ev.v
        if len(self.iv):
            if self.unique:
                Q[self.v_index] -= self.c * v[self.v_index]
            else:
                np.subtract.at(Q, self.iv, self.c * v[self.iv])
        for vs, Cm in self.prepared:
            view = Q[vs]  # a view: updated in place, no write-back
            view -= np.dot(Cm, v[vs])

    batched = True

    def add_many(self, qs: np.ndarray, Q: np.ndarray, K: np.ndarray, batch=None) -> None:
        """Forces at rest (v = 0) and stiffness at each row of ``qs``: none."""

    def add_damping(self, ev, C: np.ndarray) -> None:
        """Add the dampers' matrices (the same at every point; ``ev`` is not read and may be None)."""
        if len(self.iv):
            self.diagonal.add(C, self.c)
        for vs, Cm in self.prepared:
            view = C[vs, vs]
            view += Cm
