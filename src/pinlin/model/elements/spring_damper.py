"""A linear spring and dashpot along the line between two points (SPEC section 11)."""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from ...errors import ConfigurationError, ParameterError
from .base import Element, ElementGroup, check_vector3
from .frame_pairs import (
    FramePairElement,
    ancestor_mask,
    cross,
    cross_motion,
    fixed_wrench_stiffness,
    support_mask,
)

if TYPE_CHECKING:  # pragma: no cover
    from ...linearization.workspace import Evaluation
    from ..robot import Robot

__all__ = ["LinearSpringDamper", "SpringDamperGroup", "COINCIDENT_RTOL"]

#: Below this length, relative to the size of the points' positions (and 1 m), the
#: line between them is rounding noise and has no direction.
COINCIDENT_RTOL = 1e-12


def _number(value, label: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected a number, got {value!r}") from None
    if not np.isfinite(x) or x < 0:
        raise ParameterError(label, f"must be finite and >= 0, got {value!r}")
    return x


@dataclass(frozen=True, eq=False)
class LinearSpringDamper(FramePairElement):
    """A spring and a dashpot along the line from the origin of ``frame`` to ``target``.

    With p_a the frame origin, p_b the target, d = p_b - p_a, l = |d|, u = d / l
    and ldot = u . (pdot_b - pdot_a), the tension and the generalized force are

    .. math::  T = k (l - l_0) + c\\,\\dot l,\\qquad Q = -J_{rel}^T\\, T u

    (force T u on a, -T u on b; J_rel = J_b - J_a, linear velocities in world
    axes).  At v = 0 the element adds (SPEC section 11)

    .. math::  K \\mathrel{+}= J_{rel}^T\\Big[k u u^T + \\frac{T}{l}(I - u u^T)\\Big] J_{rel}
               - \\frac{\\partial (J_a^T F_a + J_b^T F_b)}{\\partial q}\\Big|_{F},\\qquad
               C \\mathrel{+}= c\\, J_{rel}^T u u^T J_{rel}

    the transverse term T/l of a preloaded spring (the force turns with the
    line), and the dead-force term of F_a = T u, F_b = -T u (computed from the
    world Jacobian, see :mod:`.frame_pairs`).  At v != 0 (prescribed joints)
    the q-derivative of the dashpot's ldot is included exactly.  The elastic
    stiffness (Rayleigh's K_e) is k J_rel^T u u^T J_rel.

    Parameters
    ----------
    frame : str
        Frame whose origin is the first end.
    target : str or 3 floats
        A frame (its origin) or a fixed world point [m].
    stiffness : float
        k [N/m], >= 0.
    damping : float
        c [N s/m], >= 0.
    rest_length : float
        l0 [m], >= 0.

    Raises
    ------
    ParameterError
        Non-finite or negative values, a target that is neither a frame name nor
        3 numbers, or ``target == frame``.
    ConfigurationError
        (when evaluated) the two points coincide while the rest length or the
        damping is nonzero: the line has no direction.
    """

    frame: str
    target: str | np.ndarray
    _: KW_ONLY
    stiffness: float
    damping: float = 0.0
    rest_length: float = 0.0

    kind: ClassVar[str] = "spring_damper"

    def __post_init__(self):
        label = f"LinearSpringDamper({self.frame!r})"
        if not isinstance(self.frame, str):
            raise ParameterError(f"{label}.frame", f"expected a frame name, got {self.frame!r}")
        if isinstance(self.target, str):
            if self.target == self.frame:
                raise ParameterError(f"{label}.target", "is the frame itself: the spring would have no length")
        else:
            object.__setattr__(self, "target", check_vector3(self.target, f"{label}.target"))
        for name in ("stiffness", "damping", "rest_length"):
            object.__setattr__(self, name, _number(getattr(self, name), f"{label}.{name}"))

    @classmethod
    def group(cls, elements: tuple[Element, ...], robot: Robot) -> ElementGroup:
        return SpringDamperGroup(elements, robot)


class _Line:
    """The geometry of every spring of a group at one evaluation.

    Arrays put the 3 components first: end points ``p_a``, ``p_b`` and the
    springs' ``u``, ``F`` are (3, E); what is attached to frames is summed per
    distinct frame (U of them) through the incidence matrix B (E x U, +1 at
    the target's frame, -1 at the frame's), so that no (3, E, nv) array is formed:
    J_rel = B C (C the frames' point Jacobians, (3, U, nv)).
    """

    def __init__(self, group: SpringDamperGroup, ev: Evaluation, velocity: bool):
        self.p_f = ev.frame_positions(group.frame_ids).T  # (3, U)
        p_a = self.p_f[:, group.ia]
        p_b = np.where(group.world_b, group.world_points, self.p_f[:, group.ib])
        d = p_b - p_a
        self.l = np.sqrt(np.einsum("ie,ie->e", d, d))
        size = np.maximum(np.abs(p_a).max(axis=0), np.abs(p_b).max(axis=0))
        self.zero = self.l <= COINCIDENT_RTOL * np.maximum(size, 1.0)
        bad = self.zero & ((group.l0 != 0) | (group.c != 0))
        if bad.any():
            e = group.elements[int(np.flatnonzero(bad)[0])]
            raise ConfigurationError(
                f"LinearSpringDamper({e.frame!r}, {e.target!r}): the two points coincide (distance "
                f"{self.l[bad][0]:.3g} m), so the line has no direction while rest_length = {e.rest_length:g} m "
                f"and damping = {e.damping:g} N s/m need one; move the points apart or use rest_length = 0 "
                f"without damping"
            )
        self.safe_l = np.where(self.zero, 1.0, self.l)
        self.u = np.where(self.zero, 0.0, d / self.safe_l)
        self.J0 = ev.world_jacobian()
        self.r = np.zeros_like(d)  # relative velocity pdot_b - pdot_a [m/s]
        if velocity:
            Z = self.J0 @ (group.m_f * ev.v).T  # (6, U) spatial twists of the frames' bodies
            self.r = (Z[:3] + cross(Z[3:], self.p_f)) @ group.B.T
        self.ldot = np.einsum("ie,ie->e", self.u, self.r)
        self.T = group.k * (self.l - group.l0) + group.c * self.ldot
        self.F = self.T * self.u  # force on the frame [N], world axes, (3, E)
        self.F_f = -self.F @ group.B  # total force on each frame (3, U)
        self._C: np.ndarray | None = None
        self._W: np.ndarray | None = None
        self._g: np.ndarray | None = None

    def wrench_columns(self, group: SpringDamperGroup) -> np.ndarray:
        """(6, nv): per dof, the spatial wrenches of the springs on the bodies it supports."""
        if self._W is None:
            self._W = np.concatenate([self.F_f, cross(self.p_f, self.F_f)]) @ group.m_f
        return self._W

    def point_jacobians(self, group: SpringDamperGroup) -> np.ndarray:
        """(3, U, nv): linear Jacobians of the frames' origins in world axes, v_k + omega_k x p."""
        if self._C is None:
            J0 = self.J0
            self._C = (J0[:3, None, :] + cross(J0[3:, None, :], self.p_f[:, :, None])) * group.m_f
        return self._C

    def axial_rows(self, group: SpringDamperGroup) -> np.ndarray:
        """(E, nv): u^T J_rel, the rates of change of the lengths per joint velocity."""
        if self._g is None:
            self._g = self.rows(self.u, group, self.point_jacobians(group))
        return self._g

    @staticmethod
    def rows(weights: np.ndarray, group: SpringDamperGroup, C: np.ndarray) -> np.ndarray:
        """(E, nv): w_e^T J_rel_e for a (3, E) array of vectors w (u^T J_rel: the rates of the lengths)."""
        E, U = group.B.shape
        WB = (weights[:, :, None] * group.B).transpose(1, 0, 2).reshape(E, 3 * U)
        return WB @ C.reshape(3 * U, -1)


class SpringDamperGroup(ElementGroup):
    """All the spring-dampers of a scene as arrays: small products, no loop over springs.

    Positions are read once per evaluation for all distinct frames; Jacobians
    come from the world Jacobian (one copy of Pinocchio's ``data.J``) and the
    frames' support masks; sums over springs are products with the incidence
    matrix B (the transverse stiffness is sum_i C_i^T B^T diag(T / l) B C_i).
    """

    def __init__(self, elements: tuple[LinearSpringDamper, ...], robot: Robot):
        super().__init__(elements)
        model = robot.model
        self.symmetric_stiffness = False
        fa = [robot.frame_id(e.frame) for e in elements]
        fb = [robot.frame_id(e.target) if isinstance(e.target, str) else -1 for e in elements]
        self.frame_ids = tuple(sorted(set(fa) | {f for f in fb if f >= 0}))
        self.ia = np.array([self.frame_ids.index(f) for f in fa], dtype=int)
        self.ib = np.array([self.frame_ids.index(f) if f >= 0 else 0 for f in fb], dtype=int)
        self.world_b = np.array([f < 0 for f in fb])
        self.world_points = np.zeros((3, len(elements)))
        for i, e in enumerate(elements):
            if not isinstance(e.target, str):
                self.world_points[:, i] = e.target
        self.B = np.zeros((len(elements), len(self.frame_ids)))
        np.add.at(self.B, (np.arange(len(elements)), self.ia), -1.0)
        np.add.at(self.B, (np.arange(len(elements))[~self.world_b], self.ib[~self.world_b]), 1.0)
        self.m_f = np.array([support_mask(model, model.frames[f].parentJoint) for f in self.frame_ids])
        self.T = ancestor_mask(model)
        self.k = np.array([e.stiffness for e in elements])
        self.c = np.array([e.damping for e in elements])
        self.l0 = np.array([e.rest_length for e in elements])

    def _line(self, ev: Evaluation) -> _Line:
        """The geometry at ``ev``, computed once for the force, stiffness and damping of one evaluation
        (kept on the evaluation, which one caller owns: the group is shared with the scene)."""
        return ev.memo(self, lambda: _Line(self, ev, velocity=not ev.at_rest and bool(self.c.any())))

    def _laplacian(self, C: np.ndarray, w: np.ndarray) -> np.ndarray:
        """sum_e w_e J_rel_e^T J_rel_e (nv x nv) = sum_i C_i^T (B^T diag(w) B) C_i."""
        L = self.B.T @ (w[:, None] * self.B)
        flat = C.reshape(-1, C.shape[2])
        return flat.T @ np.matmul(L, C).reshape(flat.shape)

    def add_force(self, ev: Evaluation, Q: np.ndarray) -> None:
        line = self._line(ev)
        Q += np.einsum("ik,ik->k", line.J0, line.wrench_columns(self))

    def add_damping(self, ev: Evaluation, C: np.ndarray) -> None:
        if not self.c.any():
            return
        g = self._line(ev).axial_rows(self)
        C += g.T @ (self.c[:, None] * g)

    def add_elastic_stiffness(self, ev: Evaluation, K: np.ndarray) -> None:
        line = self._line(ev)
        g = line.axial_rows(self)
        K += g.T @ (self.k[:, None] * g)
        if line.zero.any():  # zero-length spring (l0 = 0): its energy k |d|^2 / 2 is isotropic
            K += self._laplacian(line.point_jacobians(self), np.where(line.zero, self.k, 0.0))

    def add_stiffness(self, ev: Evaluation, K: np.ndarray) -> None:
        line = self._line(ev)
        Cf = line.point_jacobians(self)
        g = line.axial_rows(self)
        # J_rel^T [k u u^T + (T / l)(I - u u^T)] J_rel; a zero-length spring: k I
        tl = np.where(line.zero, self.k, line.T / line.safe_l)
        K += self._laplacian(Cf, tl) + g.T @ ((self.k - tl)[:, None] * g)
        if not ev.at_rest and self.c.any():  # d(ldot)/dq: the line turns, and the relative velocity changes
            h = line.rows(line.r - line.ldot * line.u, self, Cf)
            dr = line.rows(line.u, self, self._velocity_derivative(ev, line))
            K += g.T @ ((self.c / line.safe_l)[:, None] * h + self.c[:, None] * dr)
        # the dead-force term: d(sum J_f^T F_f)/dq with the frames' forces F_f held in world axes
        dead = fixed_wrench_stiffness(line.J0, self.T, line.wrench_columns(self))
        FxC = cross(line.F_f[:, :, None], Cf)  # (3, U, nv)
        for i in range(3):
            dead -= line.J0[3 + i][:, None] * (self.m_f.T @ FxC[i])
        K -= dead

    def _velocity_derivative(self, ev: Evaluation, line: _Line) -> np.ndarray:
        """d(pdot)/dq at fixed v of each frame's origin (3, U, nv)."""
        J0 = line.J0
        weights = self.m_f * ev.v  # (U, nv)
        Z = J0 @ weights.T  # (6, U) spatial twists of the bodies
        dZ = cross_motion(J0[:, None, :], (J0[:, None, :] * weights[None]) @ self.T)  # (6, U, nv)
        return dZ[:3] - cross(line.p_f[:, :, None], dZ[3:]) + cross(Z[3:, :, None], line.point_jacobians(self))
