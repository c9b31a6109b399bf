"""A linear spring and dashpot along the line between two points (theory: elements between frames)."""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass
from typing import ClassVar

import numpy as np

from ...errors import ConfigurationError, ParameterError
from ...numerics.arrays import readonly
from ..numbers import numeric_scalar
from .base import Element, ElementGroup, check_vector3
from .frame_pairs import (
    FramePairElement,
    ancestor_mask,
    cross,
    cross_motion,
    support_mask,
)

__all__ = ["LinearSpringDamper", "SpringDamperGroup", "COINCIDENT_RTOL"]

#: omega x p = M(p) omega with M(p) = (p @ _TURN).reshape(3, 3): row k of _TURN is the Levi-Civita
#: slice eps[:, :, k] (M(p)[i, j] = sum_k eps_ijk p_k), so all the frames' M come from one product.
_TURN = np.zeros((3, 3, 3))
_TURN[[0, 1, 2], [1, 2, 0], [2, 0, 1]] = 1.0
_TURN[[0, 1, 2], [2, 0, 1], [1, 2, 0]] = -1.0
_TURN = _TURN.transpose(2, 0, 1).reshape(3, 9)
_TURN.flags.writeable = False

#: Below this length, relative to the size of the points' positions (and 1 m), the
#: line between them is rounding noise and has no direction.
COINCIDENT_RTOL = 1e-12


def _number(value, label: str) -> float:
    x = numeric_scalar(value, label)
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
    axes).  At v = 0 the element adds (theory: elements between frames)

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

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> spring = pinlin.LinearSpringDamper("tip", np.array([1.0, 0.0, -1.2]), stiffness=10.0, damping=0.1)
    >>> sys = pinlin.linearize(pinlin.Scene(robot, [spring]), np.zeros(2), balancing=True)
    >>> sys.S.shape, bool(np.any(sys.D))
    ((2, 2), True)
    """

    frame: str
    target: str | np.ndarray
    _: KW_ONLY
    stiffness: float
    damping: float = 0.0
    rest_length: float = 0.0

    kind: ClassVar[str] = "spring_damper"
    invariance: ClassVar[str] = "unknown"  # between two frames: no proof

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
    def group(cls, elements: tuple[Element, ...], robot) -> ElementGroup:
        return SpringDamperGroup(elements, robot)


class _Line:
    """The geometry of every spring of a group at one evaluation.

    End points, the springs' ``u`` and ``F`` are (3, E) (components first);
    the frames' point Jacobians C are (U + 1, 3, nv), the extra frame a zero one
    standing for the world (a fixed target point does not move).  Each spring's
    relative Jacobian J_rel = C_b - C_a (E, 3, nv) is gathered once from C with
    prepared index arrays; no sum over springs is a loop.
    """

    def __init__(self, group: SpringDamperGroup, ev, velocity: bool):
        self.p_f = ev.frame_positions(group.frame_ids).T  # (3, U)
        p_a = self.p_f[:, group.ia]
        p_b = np.where(group.world_b, group.world_points, self.p_f[:, group.ib_frame])
        d = p_b - p_a
        self.l = np.sqrt(np.einsum("ie,ie->e", d, d))
        size = np.maximum(np.abs(p_a).max(axis=0), np.abs(p_b).max(axis=0))
        self.zero = self.l <= COINCIDENT_RTOL * np.maximum(size, 1.0)
        bad = self.zero & group.directed
        if bad.any():
            e = group.elements[int(np.flatnonzero(bad)[0])]
            raise ConfigurationError(
                f"LinearSpringDamper({e.frame!r}, {e.target!r}): the two points coincide (distance "
                f"{self.l[bad][0]:.3g} m), so the line has no direction while rest_length = {e.rest_length:g} m "
                f"and damping = {e.damping:g} N s/m need one; move the points apart or use rest_length = 0 "
                f"without damping"
            )
        self.any_zero = bool(self.zero.any())
        self.safe_l = np.where(self.zero, 1.0, self.l) if self.any_zero else self.l
        self.u = np.where(self.zero, 0.0, d / self.safe_l) if self.any_zero else d / self.l
        J0 = self.J0 = ev.world_jacobian()
        # point Jacobians of the frames' origins, v_k + omega_k x p on their supports; row U stays zero (the world)
        U = len(group.frame_ids)
        self.C = np.zeros((U + 1, 3, J0.shape[1]))
        C = self.C[:U]  # a contiguous view, filled in place
        np.matmul((self.p_f.T @ _TURN).reshape(3 * U, 3), J0[3:], out=C.reshape(3 * U, -1))  # omega_k x p_f
        C += J0[:3]
        C *= group.m_f[:, None, :]
        self.Jrel = np.take(self.C, group.ib, axis=0) - np.take(self.C, group.ia, axis=0)  # (E, 3, nv)
        self.uT = np.ascontiguousarray(self.u.T)  # (E, 3)
        self.g = np.matmul(self.uT[:, None, :], self.Jrel)[:, 0]  # u^T J_rel: rates of the lengths (E, nv)
        if velocity:
            self.r = (self.Jrel @ ev.v).T  # relative velocities pdot_b - pdot_a [m/s] (3, E)
            self.ldot = self.g @ ev.v
            self.T = group.k * (self.l - group.l0) + group.c * self.ldot
        else:
            self.r = None
            self.ldot = np.zeros_like(self.l)
            self.T = group.k * (self.l - group.l0)
        self.F = self.T * self.u  # force on the frame [N], world axes, (3, E)
        self.F_f = -self.F @ group.B  # total force on each frame (3, U)
        self._W: np.ndarray | None = None

    def wrench_columns(self, group: SpringDamperGroup) -> np.ndarray:
        """(6, nv): per dof, the spatial wrenches of the springs on the bodies it supports."""
        if self._W is None:
            self._W = np.concatenate([self.F_f, cross(self.p_f, self.F_f)]) @ group.m_f
        return self._W

    def rel(self, group: SpringDamperGroup, X: np.ndarray) -> np.ndarray:
        """(E, 3, nv): X_b - X_a per spring for a per-frame array X (U, 3, nv); zero on the world."""
        return X[group.ib_frame] * group.on_b[:, None, None] - X[group.ia]


class SpringDamperGroup(ElementGroup):
    """All the spring-dampers of a scene as arrays: gathers and products, no loop over springs.

    Built once per scene (immutable, read-only arrays: the group is shared by
    threads).  Positions are read once per evaluation for the distinct frames;
    Jacobians come from the world Jacobian (one copy of Pinocchio's ``data.J``)
    and the frames' support masks.  The stiffness of the lines is
    sum_e J_rel_e^T Y_e with Y_e = A_e J_rel_e (3 x nv, A_e the spring's 3 x 3
    stiffness), formed for all springs at once and summed in one product
    (:meth:`_quadratic`); the damping and elastic stiffness are products of
    the length rates g = u^T J_rel; the dead-force term is two (nv x nv)
    products whatever the number of springs (:meth:`_dead_force_stiffness`).
    """

    def __init__(self, elements: tuple[LinearSpringDamper, ...], robot):
        super().__init__(elements)
        model = robot.model
        self.symmetric_stiffness = False
        E = len(elements)
        fa = [robot.frame_id(e.frame) for e in elements]
        fb = [robot.frame_id(e.target) if isinstance(e.target, str) else -1 for e in elements]
        self.frame_ids = tuple(sorted(set(fa) | {f for f in fb if f >= 0}))
        U = len(self.frame_ids)
        index = {f: i for i, f in enumerate(self.frame_ids)}
        world_b = np.array([f < 0 for f in fb], dtype=bool).reshape(E)
        self.ia = readonly(np.array([index[f] for f in fa], dtype=np.intp))
        # the target's frame, U (the zero row of the point Jacobians) for a world point
        self.ib = readonly(np.array([index[f] if f >= 0 else U for f in fb], dtype=np.intp))
        self.ib_frame = readonly(np.where(world_b, 0, self.ib))  # a valid frame index for gathers from (3, U)
        self.world_b = readonly(world_b)
        self.on_b = readonly((~world_b).astype(float))
        self.world_points = readonly(
            np.array([np.zeros(3) if isinstance(e.target, str) else e.target for e in elements]).reshape(E, 3).T
        )
        B = np.zeros((E, U))
        B[np.arange(E), self.ia] -= 1.0
        B[np.arange(E)[~world_b], self.ib[~world_b]] += 1.0
        self.B = readonly(B)  # incidence: -1 at the frame, +1 at the target's frame (E x U)
        self.m_f = readonly(np.array([support_mask(model, model.frames[f].parentJoint) for f in self.frame_ids]))
        self.T = readonly(ancestor_mask(model))
        self.k = readonly(np.array([e.stiffness for e in elements], dtype=float))
        self.c = readonly(np.array([e.damping for e in elements], dtype=float))
        self.l0 = readonly(np.array([e.rest_length for e in elements], dtype=float))
        self.damped = bool(self.c.any())
        self.directed = readonly((self.l0 != 0) | (self.c != 0))  # springs that need the line's direction
        # dof pairs (k, l) where joint(k) strictly supports joint(l): the dead-force term's second mask
        self.T_below = readonly(self.T.T * (1.0 - self.T))

    def _line(self, ev) -> _Line:
        """The geometry at ``ev``, computed once for the force, stiffness and damping of one evaluation
        (kept on the evaluation, which one caller owns: the group is shared with the scene)."""
        return ev.memo(self, lambda: _Line(self, ev, velocity=self.damped and not ev.at_rest))

    @staticmethod
    def _quadratic(line: _Line, Y: np.ndarray) -> np.ndarray:
        """sum_e J_rel_e^T Y_e (nv x nv) for Y (E, 3, nv): one product over all springs.

        (Summing Y per frame first, sum_f C_f^T (sum_e B_ef Y_e), costs 3U nv (E + nv)
        multiplications against 3E nv^2: no cheaper while the U frames are about as many
        as the degrees of freedom.)
        """
        nv = Y.shape[2]
        return line.Jrel.reshape(-1, nv).T @ Y.reshape(-1, nv)

    def add_force(self, ev, Q: np.ndarray) -> None:
        line = self._line(ev)
        Q += np.einsum("ik,ik->k", line.J0, line.wrench_columns(self))

    def add_damping(self, ev, C: np.ndarray) -> None:
        if not self.damped:
            return
        g = self._line(ev).g
        C += g.T @ (self.c[:, None] * g)

    def add_elastic_stiffness(self, ev, K: np.ndarray) -> None:
        line = self._line(ev)
        K += line.g.T @ (self.k[:, None] * line.g)
        if line.any_zero:  # zero-length spring (l0 = 0): its energy k |d|^2 / 2 is isotropic
            K += self._quadratic(line, np.where(line.zero, self.k, 0.0)[:, None, None] * line.Jrel)

    def add_stiffness(self, ev, K: np.ndarray) -> None:
        line = self._line(ev)
        # J_rel^T [k u u^T + (T / l)(I - u u^T)] J_rel; a zero-length spring: k I
        tl = np.where(line.zero, self.k, line.T / line.safe_l) if line.any_zero else line.T / line.l
        rows = (self.k - tl)[:, None] * line.g
        if line.r is not None:  # d(ldot)/dq: the line turns, and the relative velocity changes
            h = np.einsum("ie,ein->en", line.r - line.ldot * line.u, line.Jrel)
            dr = np.einsum("ie,ein->en", line.u, line.rel(self, self._velocity_derivative(ev, line)))
            rows += (self.c / line.safe_l)[:, None] * h + self.c[:, None] * dr
        Y = tl[:, None, None] * line.Jrel
        Y += line.uT[:, :, None] * rows[:, None, :]
        K += self._quadratic(line, Y)
        K += self._dead_force_stiffness(line)

    def _dead_force_stiffness(self, line: _Line) -> np.ndarray:
        """-d(sum_f J_f^T F_f)/dq with the frames' forces F_f held in world axes (nv x nv).

        With J_f's column l = m_fl (v_l + omega_l x p_f), the turning of the twists
        (:func:`.frame_pairs.fixed_wrench_stiffness`) and the motion of the points p_f give

        .. math::  X_{kl} = \\sum_f m_{fk} m_{fl}\\,\\big[\\omega_k\\cdot(F_f\\times v_l)
                   + (\\omega_k\\cdot\\omega_l)(F_f\\cdot p_f) - (\\omega_k\\cdot p_f)(F_f\\cdot\\omega_l)\\big]
                   - T_{kl}\\,(\\xi_k\\times^* W_k)\\cdot\\xi_l.

        On a tree m_fk m_fl = 1 exactly when f lies below the deeper of the two joints,
        so the sums over frames are per-dof sums (like W) taken at k where joint(l)
        supports joint(k) (T_kl = 1) and at l where joint(k) strictly supports joint(l):
        two (nv x nv) products, no sum over frames per pair.  The omega_k x f_k parts of
        the two terms cancel.
        """
        J0, F_f, p_f = line.J0, line.F_f, line.p_f
        W = line.wrench_columns(self)  # (f_k, tau_k): sums over the frames below dof k
        f, tau, v, w = W[:3], W[3:], J0[:3], J0[3:]
        s2 = np.einsum("iu,iu->u", F_f, p_f) @ self.m_f  # sum of F_f . p_f below dof k (nv,)
        S3 = ((p_f[:, None] * F_f[None]).reshape(9, -1) @ self.m_f).reshape(3, 3, -1)  # sum of p_f F_f^T below k
        at_k = s2 * w - np.einsum("jin,jn->in", S3, w) - cross(v, f) - cross(w, tau)  # (3, nv)
        at_l = cross(f, v) + s2 * w - np.einsum("ijn,jn->in", S3, w)
        return self.T * (at_k.T @ w) + self.T_below * (w.T @ at_l)

    def _velocity_derivative(self, ev, line: _Line) -> np.ndarray:
        """d(pdot)/dq at fixed v of each frame's origin (U, 3, nv)."""
        J0 = line.J0
        weights = self.m_f * ev.v  # (U, nv)
        Z = J0 @ weights.T  # (6, U) spatial twists of the bodies
        dZ = cross_motion(J0[:, None, :], (J0[:, None, :] * weights[None]) @ self.T)  # (6, U, nv)
        dp = dZ[:3] - cross(line.p_f[:, :, None], dZ[3:]) + cross(Z[3:, :, None], line.C[:-1].transpose(1, 0, 2))
        return dp.transpose(1, 0, 2)
