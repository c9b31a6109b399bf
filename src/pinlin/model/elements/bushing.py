"""A six-axis linear spring and damper on the relative placement of two frames (theory: elements between frames)."""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass
from typing import ClassVar

import numpy as np
import pinocchio as pin

from ...errors import ParameterError
from ...numerics.arrays import readonly
from .base import Element, ElementGroup, check_psd
from .frame_pairs import (
    FramePairElement,
    ancestor_mask,
    as_placement,
    cross_motion,
    fixed_wrench_stiffness,
    support_mask,
)
from .se3 import LogExpansion, ad_matrix, log_jacobian_derivative, skew

__all__ = ["Bushing", "BushingGroup"]


def _matrix6(value, label: str) -> np.ndarray:
    arr = check_psd(value, label)
    if arr.shape == (6,):
        return np.diag(arr)
    if arr.shape != (6, 6):
        raise ParameterError(
            label, f"expected 6 values (translations, then rotations) or a 6x6 matrix, got shape {arr.shape}"
        )
    return arr


@dataclass(frozen=True, eq=False)
class Bushing(FramePairElement):
    """Six-axis spring and damper between ``frame`` and ``target``, exact for finite rotations.

    With X = O^-1 (oMb^-1 oMa) the placement of the frame (a) relative to its
    unloaded placement on the target (b), the deflection is the SE(3) log

    .. math::  e = \\log_6(X) = (\\rho, \\theta) \\in \\mathbb{R}^6,\\qquad
               \\dot e = J_{log}(X)\\, \\nu,\\quad \\nu = J_r v

    (translation then rotation, in the frame's axes, which are also the unloaded
    frame's since X = exp(e)); nu is the twist of a relative to b in a's axes,
    J_r = J_a - Ad(aMb) J_b (local frame Jacobians).  The force conjugate to e is
    f = -(K_6 e + D_6 edot); the wrench on the frame is J_log^T f (the gradient
    of e^T K_6 e / 2: the bushing stores energy and is conservative without
    damping), its reaction acts on the target, and

    .. math::  Q = J_r^T J_{log}^T f,\\qquad
               C \\mathrel{+}= J_r^T J_{log}^T D_6 J_{log} J_r,\\qquad
               K \\mathrel{+}= J_r^T J_{log}^T K_6 J_{log} J_r + (\\text{terms in } f)

    where the terms in f come from the second-order expansion of log6
    (:mod:`.se3`), the turning of a's axes and the frames' Jacobians
    (:mod:`.frame_pairs`); at e = 0 and v = 0 they vanish and K = J_r^T K_6 J_r.
    At v != 0 (prescribed joints) the q-derivative of edot is included exactly.
    The elastic stiffness (Rayleigh's K_e) is J_r^T J_log^T K_6 J_log J_r.

    Parameters
    ----------
    frame : str
        The frame a.
    target : str, pin.SE3, (4, 4) array or mapping
        The frame b, or a fixed world placement (a mapping ``{"xyz": [m], "rpy": [rad]}``
        reads like URDF's ``<origin>``).
    stiffness : 6 floats or (6, 6) array
        K_6: [N/m] for translations, [N m/rad] for rotations (and mixed units
        off the diagonal); symmetric positive semi-definite.
    damping : 6 floats or (6, 6) array, optional
        D_6 [N s/m, N m s/rad], symmetric psd; default none.
    offset : pin.SE3, (4, 4) array or mapping, optional
        O: the placement of the frame relative to the target at which the bushing
        is unloaded; default the identity.

    Raises
    ------
    ParameterError
        Non-finite values, a stiffness or damping that is not 6 values or a
        symmetric psd 6x6 matrix, a target or offset that is not a placement, or
        ``target == frame``.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> bushing = pinlin.Bushing("link1", "link2", stiffness=np.diag([1e3, 1e3, 1e3, 5.0, 5.0, 5.0]))
    >>> bushing
    Bushing('link1', 'link2', stiffness=diag([1000.0, 1000.0, 1000.0, 5.0, 5.0, 5.0]))
    >>> sys = pinlin.linearize(pinlin.Scene(robot, [bushing], gravity=(0, 0, 0)), np.zeros(2))
    >>> print(f"{sys.S[1, 1]:.6f}")
    45.833333
    """

    frame: str
    target: str | np.ndarray
    _: KW_ONLY
    stiffness: np.ndarray
    damping: np.ndarray | None = None
    offset: np.ndarray | None = None

    kind: ClassVar[str] = "bushing"
    invariance: ClassVar[str] = "unknown"  # between two frames: no proof

    def __post_init__(self):
        label = f"Bushing({self.frame!r})"
        if not isinstance(self.frame, str):
            raise ParameterError(f"{label}.frame", f"expected a frame name, got {self.frame!r}")
        if isinstance(self.target, str):
            if self.target == self.frame:
                raise ParameterError(f"{label}.target", "is the frame itself: there is no relative motion")
        else:
            object.__setattr__(self, "target", self._frozen(as_placement(self.target, f"{label}.target")))
        object.__setattr__(self, "stiffness", self._frozen(_matrix6(self.stiffness, f"{label}.stiffness")))
        damping = np.zeros((6, 6)) if self.damping is None else _matrix6(self.damping, f"{label}.damping")
        object.__setattr__(self, "damping", self._frozen(damping))
        offset = pin.SE3.Identity() if self.offset is None else as_placement(self.offset, f"{label}.offset")
        object.__setattr__(self, "offset", self._frozen(offset))

    def __repr__(self) -> str:
        def matrix(m):
            m = np.asarray(m)
            if not np.any(m - np.diag(np.diag(m))):
                return f"diag({np.round(np.diag(m), 6).tolist()})"
            return "<6x6 matrix>"

        def placement(h):
            M = pin.SE3(np.asarray(h))
            xyz, rpy = np.round(M.translation, 6).tolist(), np.round(pin.rpy.matrixToRpy(M.rotation), 6).tolist()
            return f"SE3(xyz={xyz}, rpy={rpy})"

        target = repr(self.target) if isinstance(self.target, str) else placement(self.target)
        parts = [repr(self.frame), target, f"stiffness={matrix(self.stiffness)}"]
        if np.any(self.damping):
            parts.append(f"damping={matrix(self.damping)}")
        if np.any(self.offset - np.eye(4)):
            parts.append(f"offset={placement(self.offset)}")
        return f"Bushing({', '.join(parts)})"

    @staticmethod
    def _frozen(value) -> np.ndarray:
        return readonly(value.homogeneous if isinstance(value, pin.SE3) else value, dtype=float)

    def deflection(self, ev) -> np.ndarray:
        """e = log6(X) (6,): [m] then [rad], in the frame's axes.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> bushing = pinlin.Bushing("link1", "link2", stiffness=np.eye(6))
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [bushing]), np.array([0.0, 0.2]), np.zeros(2))
        >>> np.round(bushing.deflection(ev), 6) + 0.0
        array([-0.07    ,  0.      ,  0.697665,  0.      , -0.2     ,  0.      ])
        """
        return self._one(ev).state(ev).e[0]

    @classmethod
    def group(cls, elements: tuple[Element, ...], robot) -> ElementGroup:
        return BushingGroup(elements, robot)


class _State:
    """All the bushings of a group at one evaluation, as arrays over the bushings (leading axis B).

    The second-order terms of the log are computed on first use (stiffness only).
    """

    def __init__(self, group: BushingGroup, ev, velocity: bool):
        nb = len(group.elements)
        H = ev.frame_homogeneous(group.frame_ids)
        R_a, p_a = H[group.ia, :3, :3], H[group.ia, :3, 3]
        R_b = np.where(group.world_b[:, None, None], group.target_R, H[group.ib, :3, :3])
        p_b = np.where(group.world_b[:, None], group.target_p, H[group.ib, :3, 3])
        # X = O^-1 oMb^-1 oMa, with O^-1 = (Ro^T, -Ro^T po) stored as (R_oi, p_oi)
        R_ba = np.swapaxes(R_b, 1, 2)
        self.R = group.R_oi @ R_ba @ R_a
        self.p = np.einsum("bij,bj->bi", group.R_oi @ R_ba, p_a - p_b) + group.p_oi
        self.theta = np.array([pin.log3(R) for R in self.R]).reshape(nb, 3)
        R_at = np.swapaxes(R_a, 1, 2)
        self.Ad = np.zeros((nb, 6, 6))  # Ad(aMo) = [[R^T, -R^T [p]x], [0, R^T]]: world twists -> a's axes
        self.Ad[:, :3, :3] = self.Ad[:, 3:, 3:] = R_at
        self.Ad[:, :3, 3:] = -R_at @ skew(p_a)
        # our own J_log (Pinocchio 4.1's Jlog6 loses up to 5e-7 near 1e-3 rad, see tests)
        self._log = LogExpansion(self.R, self.p, self.theta)
        self.J = self._log.J
        rho = np.einsum("bji,bj->bi", self.J[:, :3, :3], self.p)  # W(theta) p, W = A^T
        self.e = np.concatenate([rho, self.theta], axis=1)
        J0 = ev.world_jacobian()
        self.Jr = self.Ad @ (J0 * group.s[:, None, :])  # (B, 6, nv); common supports cancel in s = m_a - m_b
        self.nu = self.Jr @ ev.v if velocity else np.zeros((nb, 6))  # relative twists, a's axes
        self.edot = np.einsum("bij,bj->bi", self.J, self.nu)
        self.f = -np.einsum("bij,bj->bi", group.K6, self.e) - np.einsum("bij,bj->bi", group.D6, self.edot)
        self.w = np.einsum("bji,bj->bi", self.J, self.f)  # wrenches on the frames, in their axes
        self.W = np.einsum("bji,bj->bi", self.Ad, self.w)  # the same as spatial wrenches (world axes, origin)
        self._L: np.ndarray | None = None

    @property
    def L(self) -> np.ndarray:
        """L[b, m, i, j] = d J_log[m, i] / d eta_j (:func:`.se3.log_jacobian_derivative`)."""
        if self._L is None:
            self._L = log_jacobian_derivative(self.J, self._log.E2)
        return self._L

    def projected(self) -> np.ndarray:
        """J_log J_r (B, 6, nv): the rates of the deflections per joint velocity."""
        return self.J @ self.Jr


def _sum_quadratic(left: np.ndarray, middle: np.ndarray, right: np.ndarray) -> np.ndarray:
    """sum_b left_b^T middle_b right_b (nv x nv) for (B, 6, nv), (B, 6, 6), (B, 6, nv) arrays."""
    mr = middle @ right
    return left.reshape(-1, left.shape[-1]).T @ mr.reshape(-1, mr.shape[-1])


class BushingGroup(ElementGroup):
    """All the bushings of a scene, as arrays over the bushings; one fixed-wrench product for all."""

    def __init__(self, elements: tuple[Bushing, ...], robot):
        super().__init__(elements)
        model = robot.model
        self.symmetric_stiffness = False
        self.fa = [robot.frame_id(e.frame) for e in elements]
        self.fb = [robot.frame_id(e.target) if isinstance(e.target, str) else -1 for e in elements]
        self.frame_ids = tuple(sorted(set(self.fa) | {f for f in self.fb if f >= 0}))
        index = {f: i for i, f in enumerate(self.frame_ids)}
        # positions in frame_ids of each bushing's frames (a world target: any valid index, masked by world_b)
        self.ia = readonly(np.array([index[f] for f in self.fa], dtype=np.intp))
        self.ib = readonly(np.array([index.get(f, 0) for f in self.fb], dtype=np.intp))
        self.world_b = readonly(np.array([f < 0 for f in self.fb], dtype=bool))
        targets = np.array([np.eye(4) if isinstance(e.target, str) else e.target for e in elements]).reshape(-1, 4, 4)
        self.target_R, self.target_p = readonly(targets[:, :3, :3].copy()), readonly(targets[:, :3, 3].copy())
        offsets = np.array([e.offset for e in elements]).reshape(-1, 4, 4)
        self.R_oi = readonly(np.swapaxes(offsets[:, :3, :3], 1, 2).copy())  # O^-1 = (Ro^T, -Ro^T po)
        self.p_oi = readonly(-np.einsum("bij,bj->bi", self.R_oi, offsets[:, :3, 3]))
        nv = model.nv
        self.m_a = readonly(
            np.array([support_mask(model, model.frames[f].parentJoint) for f in self.fa]).reshape(-1, nv)
        )
        m_b = np.array(
            [support_mask(model, model.frames[f].parentJoint) if f >= 0 else np.zeros(nv) for f in self.fb]
        ).reshape(-1, nv)
        self.s = readonly(self.m_a - m_b)
        self.T = readonly(ancestor_mask(model))
        self.K6 = readonly(np.array([e.stiffness for e in elements], dtype=float).reshape(-1, 6, 6))
        self.D6 = readonly(np.array([e.damping for e in elements], dtype=float).reshape(-1, 6, 6))
        self.damped = bool(np.any(self.D6))

    def state(self, ev) -> _State:
        """The bushings at ``ev``, computed once for its force, stiffness and damping (kept on the
        evaluation, which one caller owns: the group is shared with the scene)."""
        return ev.memo(self, lambda: _State(self, ev, velocity=self.damped and not ev.at_rest))

    def add_force(self, ev, Q: np.ndarray) -> None:
        st = self.state(ev)
        Q += np.einsum("bik,bi->k", st.Jr, st.w)

    def add_damping(self, ev, C: np.ndarray) -> None:
        if self.damped:
            B = self.state(ev).projected()
            C += _sum_quadratic(B, self.D6, B)

    def add_elastic_stiffness(self, ev, K: np.ndarray) -> None:
        B = self.state(ev).projected()
        K += _sum_quadratic(B, self.K6, B)

    def add_stiffness(self, ev, K: np.ndarray) -> None:
        st = self.state(ev)
        J0 = ev.world_jacobian()
        Ja = st.Ad @ (J0 * self.m_a[:, None, :])  # body Jacobians of the frames, their axes
        # dw/dq = dJlog^T f + J^T df, df = -K6 de - D6 dedot, de = J Jr dq; W = Ad^T w turns with a's axes
        nb = st.f.shape[0]
        middle = (st.f[:, None, :] @ st.L.reshape(nb, 6, 36)).reshape(nb, 6, 6)  # f_m L[m, i, j]
        middle -= np.swapaxes(st.J, 1, 2) @ self.K6 @ st.J
        dw = middle @ st.Jr
        if self.damped and not ev.at_rest:
            weights = (self.s * ev.v)[:, None, :]  # (B, 1, nv)
            dZ = cross_motion(J0[:, None, :], np.moveaxis((J0[None] * weights) @ self.T, 1, 0))  # (6, B, nv)
            dnu = ad_matrix(st.nu) @ Ja + st.Ad @ np.moveaxis(dZ, 0, 1)
            dedot = np.einsum("bi,bmij->bmj", st.nu, st.L) @ st.Jr + st.J @ dnu
            dw -= np.swapaxes(st.J, 1, 2) @ self.D6 @ dedot
        dw -= _wrench_turn(st.w) @ Ja
        K -= st.Jr.reshape(-1, K.shape[0]).T @ dw.reshape(-1, K.shape[0])
        K -= fixed_wrench_stiffness(J0, self.T, st.W.T @ self.s)


def _wrench_turn(w: np.ndarray) -> np.ndarray:
    """Lambda(w) (..., 6, 6) with ad(x)^T w = Lambda(w) x, for wrenches w = (f, tau) (..., 6)."""
    out = np.zeros(w.shape[:-1] + (6, 6))
    f = skew(w[..., :3])
    out[..., :3, 3:] = f
    out[..., 3:, :3] = f
    out[..., 3:, 3:] = skew(w[..., 3:])
    return out
