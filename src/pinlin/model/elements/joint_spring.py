"""Joint torsion / translational springs."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pinocchio as pin

from ...errors import ParameterError
from ...numerics.arrays import readonly
from ..evaluation import BatchPoints
from ..numbers import numeric_array
from .base import DiagonalIndex, Element, ElementGroup, as_matrix, check_psd, contiguous
from .lie_log import joint_log

__all__ = ["JointSpring", "SpringGroup"]


@dataclass(frozen=True, eq=False)
class JointSpring(Element):
    """A linear spring on one joint (theory: elements).

    .. math::  Q = -K_s\\, e(q), \\qquad e = \\mathrm{difference}(q_{rest}, q_j)

    e is the joint angle [rad] or displacement [m] from rest, or on a multi-DOF joint
    the difference on its Lie group (from :mod:`.lie_log`, more accurate than Pinocchio
    4.1's ``dDifference`` at small rotations); dQ/dq = -K_s de/dq.  An anisotropic K_s on a
    rotation group far from rest is not conservative: its stiffness may have a skew part.

    Parameters
    ----------
    joint : str
        Joint name.
    stiffness : float, (nv,) or (nv, nv) array
        [N m/rad] or [N/m]; a number, a diagonal, or a symmetric psd matrix.
    rest : float or (nq,) array, optional
        Unstressed configuration of the joint: an angle / displacement for a
        1-DOF joint (continuous joints too), else a configuration vector of the
        joint.  Default: Pinocchio's neutral (zero angle).

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> spring = pinlin.JointSpring("joint1", 2.0)
    >>> sys = pinlin.linearize(pinlin.Scene(robot, [spring], gravity=(0, 0, 0)), np.zeros(2))
    >>> np.round(sys.S, 6)
    array([[2., 0.],
           [0., 0.]])
    """

    joint: str
    stiffness: float | np.ndarray
    rest: float | np.ndarray | None = None

    kind: ClassVar[str] = "spring"
    invariance: ClassVar[str] = "joint-space"

    def __post_init__(self):
        object.__setattr__(self, "stiffness", check_psd(self.stiffness, f"JointSpring({self.joint!r}).stiffness"))
        if self.rest is not None:
            rest = numeric_array(self.rest, f"JointSpring({self.joint!r}).rest", "finite numbers")
            if rest.ndim > 1 or not np.all(np.isfinite(rest)):
                raise ParameterError(f"JointSpring({self.joint!r}).rest", f"must be finite numbers, got {self.rest!r}")
            object.__setattr__(self, "rest", readonly(rest))

    def matrix(self, j) -> np.ndarray:
        """The stiffness as a (nv_j x nv_j) matrix.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> pinlin.JointSpring("joint1", 2.0).matrix(robot.joint("joint1"))
        array([[2.]])
        """
        return as_matrix(self.stiffness, j.nv, f"JointSpring({self.joint!r}).stiffness")

    def rest_configuration(self, robot) -> np.ndarray:
        """Rest configuration of the joint (nq_j,).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> pinlin.JointSpring("joint1", 2.0, rest=0.1).rest_configuration(robot)
        array([0.1])
        """
        j = robot.joint(self.joint)
        jm = robot.model.joints[j.id]
        if self.rest is None:
            return np.zeros(1) if j.nq == 1 else np.asarray(jm.lieGroup().neutral, dtype=float)
        rest = np.atleast_1d(self.rest)
        if j.nq == 2 and j.nv == 1 and rest.size == 1:
            return np.array([np.cos(rest[0]), np.sin(rest[0])])
        if rest.shape != (j.nq,):
            raise ParameterError(
                f"JointSpring({self.joint!r}).rest",
                f"joint {self.joint!r} ({j.kind}) needs a rest of {j.nq} value(s), got shape {rest.shape}",
            )
        return rest

    def check(self, robot) -> None:
        j = robot.joint(self.joint)
        self.matrix(j)
        self.rest_configuration(robot)

    def deflection(self, ev) -> tuple[np.ndarray, np.ndarray | None]:
        """e (nv_j,) and de/dq (nv_j x nv_j), the latter None when it is the identity.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> spring = pinlin.JointSpring("joint1", 2.0, rest=0.1)
        >>> scene = pinlin.Scene(robot, [spring])
        >>> e, de_dq = spring.deflection(pinlin.linearization.Evaluation(scene, np.array([0.3, 0.0]), np.zeros(2)))
        >>> np.round(e, 6), de_dq
        (array([0.2]), None)
        """
        j = ev.robot.joint(self.joint)
        rest = self.rest_configuration(ev.robot)
        qj = ev.q[j.q_slice]
        if j.nq == 1:
            return qj - rest, None
        log = _lie_log(ev.model.joints[j.id], rest)
        if j.nv == 1:  # SO(2): the derivative of the angle difference is 1
            return log.difference(qj), None
        return log.evaluate(qj)

    def generalized_force(self, ev) -> np.ndarray:
        j = ev.robot.joint(self.joint)
        Q = np.zeros(ev.model.nv)
        e, _ = self.deflection(ev)
        Q[j.v_slice] = -np.dot(self.matrix(j), e)
        return Q

    def add_stiffness(self, ev, K: np.ndarray) -> None:
        j = ev.robot.joint(self.joint)
        _, jac = self.deflection(ev)
        Ks = self.matrix(j)
        K[j.v_slice, j.v_slice] += Ks if jac is None else np.dot(Ks, jac)

    def add_elastic_stiffness(self, ev, K: np.ndarray) -> None:
        """The spring's matrix K_s: psd, the elastic stiffness in Rayleigh's beta K_e."""
        j = ev.robot.joint(self.joint)
        K[j.v_slice, j.v_slice] += self.matrix(j)

    @classmethod
    def group(cls, elements: tuple[Element, ...], robot) -> ElementGroup:
        return SpringGroup(elements, robot)


class SpringGroup(ElementGroup):
    """Joint springs with everything that does not depend on q prepared once per scene.

    Springs on joints with nq = nv = 1 and a scalar stiffness are arrays:
    Q[iv] -= k (q[iq] - rest) and K[iv, iv] += k as one flat-index update of the
    diagonal.  Every other spring (multi-DOF joints, continuous joints, matrix
    stiffness) keeps its joint's slices, rest configuration, Lie group and
    stiffness matrix (read-only, prepared here, :attr:`prepared`), so a point
    costs only the group's ``difference`` (force) or ``dDifference`` (stiffness)
    and one product.  The results are those of the elements' own methods,
    bitwise.
    """

    def __init__(self, elements: tuple[JointSpring, ...], robot):
        simple = [e for e in elements if robot.joint(e.joint).nq == 1 and e.stiffness.ndim < 2]
        super().__init__(tuple(e for e in elements if e not in simple))
        joints = [robot.joint(e.joint) for e in simple]
        self.iq = readonly(np.array([j.idx_q for j in joints], dtype=int))
        self.iv = readonly(np.array([j.idx_v for j in joints], dtype=int))
        self.k = readonly(np.array([float(np.ravel(e.stiffness)[0]) for e in simple]))
        self.rest = readonly(np.array([0.0 if e.rest is None else float(np.ravel(e.rest)[0]) for e in simple]))
        self.unique = len(set(self.iv.tolist())) == len(self.iv)
        #: iq and iv as slices when consecutive (every joint of a chain sprung): views, updated in place.
        self.q_index, self.v_index = contiguous(self.iq), contiguous(self.iv)
        self.v_slice = isinstance(self.v_index, slice)
        self.diagonal = DiagonalIndex(self.iv, robot.nv)
        self.prepared = tuple(_prepare(e, robot) for e in self.elements)
        self.symmetric_stiffness = all(robot.joint(e.joint).nv == 1 for e in self.elements)
        self.constant_damping = True  # springs add no damping

    def add_force(self, ev, Q: np.ndarray) -> None:
        q = ev.q
        if len(self.iv):
            force = self.k * (q[self.q_index] - self.rest)
            if self.v_slice:  # a view: updated in place, no write-back
                view = Q[self.v_index]
                view -= force
            elif self.unique:
                Q[self.iv] -= force
            else:
                np.subtract.at(Q, self.iv, force)
        for qs, vs, rest, log, Ks, derivative in self.prepared:
            view = Q[vs]
            if log is None:
                view -= np.dot(Ks, q[qs] - rest)
            elif derivative:  # e and de/dq from one evaluation of the log, kept for add_stiffness
                view -= np.dot(Ks, ev.memo(log, lambda log=log, qs=qs: log.evaluate(q[qs]))[0])
            else:
                view -= np.dot(Ks, log.difference(q[qs]))

    def add_stiffness(self, ev, K: np.ndarray) -> None:
        if len(self.iv):
            self.diagonal.add(K, self.k)
        q = ev.q
        for qs, vs, _, log, Ks, derivative in self.prepared:
            view = K[vs, vs]
            view += np.dot(Ks, ev.memo(log, lambda log=log, qs=qs: log.evaluate(q[qs]))[1]) if derivative else Ks

    batched = True

    def add_many(self, qs: np.ndarray, Q: np.ndarray, K: np.ndarray, batch: BatchPoints | None = None) -> None:
        """:meth:`add_force` and :meth:`add_stiffness` at each row of ``qs`` (P, nq), into Q (P, nv) and K (P, nv, nv).

        A multi-DOF spring's log is evaluated once per row for both, as the single
        call shares it through its evaluation; with ``batch`` (qs its chunk of rows)
        once for all the call's rows.
        """
        if len(self.iv):
            force = self.k * (qs[:, self.q_index] - self.rest)
            if self.v_slice:
                view = Q[:, self.v_index]
                view -= force
            elif self.unique:
                Q[:, self.iv] -= force
            else:  # repeated joints: in order, as element by element
                np.subtract.at(Q.T, self.iv, force.T)
            self.diagonal.add_many(K, self.k)
        for qs_j, vs, rest, log, Ks, derivative in self.prepared:
            if derivative:  # the log of every row at once, then the single call's products row by row
                if batch is None:
                    E, J = log.evaluate_many(qs[:, qs_j])
                else:
                    E, J = batch.memo(log, lambda log=log, qs_j=qs_j: log.evaluate_many(batch.qs[:, qs_j]))
                    E, J = E[batch.rows], J[batch.rows]
                # the single call's products row by row: matmul hands each matrix of a stack to the BLAS
                # routine np.dot calls for one (gemv, gemm), with the same arguments
                forces, stiffnesses = np.matmul(Ks, E[:, :, None])[:, :, 0], np.matmul(Ks, J)
                view, block = Q[:, vs], K[:, vs, vs]
                view -= forces  # entry for entry the single call's updates, on all rows at once
                block += stiffnesses
                continue
            for q, row, Kp in zip(qs, Q, K):
                view, block = row[vs], Kp[vs, vs]
                if log is None:
                    view -= np.dot(Ks, q[qs_j] - rest)
                else:
                    view -= np.dot(Ks, log.difference(q[qs_j]))
                block += Ks

    def add_damping(self, ev, C: np.ndarray) -> None:
        """Springs add no damping."""

    def add_elastic_stiffness(self, ev, K: np.ndarray) -> None:
        if len(self.iv):
            np.add.at(K, (self.iv, self.iv), self.k)
        for _, vs, _, _, Ks, _ in self.prepared:
            K[vs, vs] += Ks


def _prepare(spring: JointSpring, robot) -> tuple:
    """(q slice, v slice, rest, log or None, stiffness matrix, whether de/dq is not the identity).

    The log (:func:`_lie_log`) is None on a 1-DOF joint with nq = 1 (e = q_j - rest);
    de/dq is the identity there and on SO(2) (a continuous joint).
    """
    j = robot.joint(spring.joint)
    rest = readonly(spring.rest_configuration(robot))
    log = None if j.nq == 1 else _lie_log(robot.model.joints[j.id], rest)
    return (j.q_slice, j.v_slice, rest, log, readonly(spring.matrix(j)), j.nv > 1)


class _GroupLog:
    """Pinocchio's ``difference`` and ``dDifference`` on a joint's Lie group, as :class:`.lie_log.JointLog` offers them."""

    __slots__ = ("group", "rest", "name")

    def __init__(self, group, rest: np.ndarray):
        self.group, self.rest, self.name = group, rest, group.name

    def difference(self, q: np.ndarray) -> np.ndarray:
        return np.asarray(self.group.difference(self.rest, q), dtype=float)

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        return np.asarray(self.group.dDifference(self.rest, q, pin.ARG1), dtype=float)

    def evaluate(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return self.difference(q), self.jacobian(q)

    def evaluate_many(self, qs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`evaluate` at each row of ``qs`` (P, nq_j), stacked: (P, nv_j) and (P, nv_j, nv_j)."""
        pairs = [self.evaluate(q) for q in qs]
        return np.array([e for e, _ in pairs]), np.array([jacobian for _, jacobian in pairs])


def _lie_log(joint: pin.JointModel, rest: np.ndarray):
    """The joint's log at ``rest``: :mod:`.lie_log`'s on SE(3), SO(3), SE(2) (accurate at every angle), else Pinocchio's."""
    return joint_log(joint, rest) or _GroupLog(joint.lieGroup(), rest)
