"""Point constraints: a frame's origin held at another frame's or at a world point; ground contacts."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
import pinocchio as pin

from ...errors import ConfigurationError, ParameterError
from ..elements.base import check_vector3
from ..numbers import numeric_scalar
from .base import Constraint
from .forces import ConstraintForce, ContactStatus

__all__ = ["PointConstraint", "ground_contacts"]


@dataclass(frozen=True, eq=False)
class PointConstraint(Constraint):
    """Keep the origin of ``frame`` at ``target`` (theory: constraints).

    .. math::  \\Phi = p_a(q) - p_b(q) \\in \\mathbb{R}^3,\\qquad J_c = J_a - J_b

    with J the linear rows of the frame Jacobians in LOCAL_WORLD_ALIGNED axes.
    The multipliers lambda (3,) are the world-axes force on ``frame`` (and
    -lambda on a target frame).  A planar loop's out-of-plane equation is always
    satisfied: such redundant equations are found by a rank-revealing
    factorization, and their forces are then the minimum-norm ones.

    Parameters
    ----------
    frame : str
        The constrained frame; its origin is the constrained point.
    target : str or 3 floats
        Another frame's name (its origin), or a fixed world point [m].
    contact : bool
        A one-sided ground contact: ``target`` must be a world point; the
        equilibrium reports whether the ground must pull or friction exceeds
        ``friction``.  The linearization stays bilateral (stance linearization).
    friction : float, optional
        Friction coefficient mu of a contact; None: only the normal force's sign is checked.
    normal : 3 floats
        The ground's normal, pointing out of the ground (normalized); default +z.
    name : str, optional
        Label in reports; default the frame name (world targets) or ``frame-target``.

    Raises
    ------
    ParameterError
        A target that is neither a frame name nor 3 finite numbers, a contact on
        a frame target, a negative or non-finite friction, friction without
        contact, a zero normal.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    >>> loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0), name="loop")
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", 50.0, rest=0.2)], constraints=[loop])
    >>> loop.kind, loop.size, loop.label
    ('point', 3, 'loop')
    >>> pinlin.linearize(scene, pinlin.find_equilibrium(scene, np.zeros(3)).q).dof_names
    ('coupler_joint',)
    """

    frame: str
    target: str | np.ndarray
    contact: bool = False
    friction: float | None = None
    normal: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))
    name: str | None = None

    kind: ClassVar[str] = "point"
    size: ClassVar[int] = 3

    def __post_init__(self):
        label = f"PointConstraint({self.frame!r})"
        if not isinstance(self.frame, str):
            raise ParameterError(f"{label}.frame", f"expected a frame name, got {self.frame!r}")
        if not isinstance(self.target, str):
            object.__setattr__(self, "target", check_vector3(self.target, f"{label}.target"))
        object.__setattr__(self, "contact", bool(self.contact))
        normal = check_vector3(self.normal, f"{label}.normal")
        size = float(np.linalg.norm(normal))
        if size == 0:
            raise ParameterError(f"{label}.normal", "must not be zero")
        normal = normal / size
        normal.flags.writeable = False
        object.__setattr__(self, "normal", normal)
        if self.contact and isinstance(self.target, str):
            raise ParameterError(f"{label}.target", "a contact needs a fixed world point on the ground, not a frame")
        if self.friction is not None:
            if not self.contact:
                raise ParameterError(f"{label}.friction", "friction applies to contacts only (contact=True)")
            mu = numeric_scalar(self.friction, f"{label}.friction")
            if not (math.isfinite(mu) and mu >= 0):
                raise ParameterError(f"{label}.friction", f"must be a finite number >= 0, got {self.friction!r}")
            object.__setattr__(self, "friction", mu)

    def residual(self, ev) -> np.ndarray:
        p_a = ev.frame_position(ev.robot.frame_id(self.frame))
        if self.target_frame is None:
            return p_a - self.target
        return p_a - ev.frame_position(ev.robot.frame_id(self.target_frame))

    def jacobian(self, ev) -> np.ndarray:
        return self._relative_jacobian(ev)[:3]

    def wrench_terms(self, ev, lam: np.ndarray) -> list[tuple]:
        return self._pair(ev, np.asarray(lam, dtype=float), None)

    def force(self, lam: np.ndarray, copy: bool = True) -> ConstraintForce:
        return ConstraintForce(self.label, self.frame, self.target, np.array(lam, dtype=float) if copy else lam)

    def contact_status(self, lam: np.ndarray) -> ContactStatus:
        """Normal and tangential force of a contact with multipliers ``lam``.

        .. math::  f_n = n\\cdot\\lambda \\ge 0,\\qquad |\\lambda - f_n n| \\le \\mu f_n

        Raises
        ------
        ParameterError
            The constraint is not a contact.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> (foot,) = pinlin.ground_contacts(robot, np.zeros(2), ["tip"], friction=0.5)
        >>> status = foot.contact_status(np.array([0.3, 0.0, 1.0]))
        >>> round(status.friction_needed, 6), status.slips
        (0.3, False)
        """
        if not self.contact:
            raise ParameterError(f"PointConstraint({self.frame!r})", "is not a contact (contact=False)")
        lam = np.asarray(lam, dtype=float)
        fn = float(self.normal @ lam)
        ft = float(np.linalg.norm(lam - fn * self.normal))
        needed = ft / fn if fn > 0 else (0.0 if ft == 0 else math.inf)  # no force at all needs no friction
        slips = self.friction is not None and needed > self.friction
        return ContactStatus(constraint=self.label, normal_force=fn, tangential_force=ft, friction_needed=needed,
                             friction=self.friction, pulls=fn < 0, slips=bool(slips and fn >= 0))


def ground_contacts(
    robot,
    q,
    frames: Sequence[str],
    *,
    friction: float | None = None,
    normal=(0.0, 0.0, 1.0),
) -> list[PointConstraint]:
    """Point contacts that hold ``frames`` where they are at configuration ``q``.

    A convenience for standing robots: each frame's origin at q becomes the world
    point of a ``PointConstraint(frame, point, contact=True, friction=friction,
    normal=normal)`` named after the frame.

    Parameters
    ----------
    robot : Robot
    q : (nq,) array
        Configuration at which the feet touch the ground.
    frames : sequence of str
        The contact frames (feet).
    friction : float, optional
        Friction coefficient of every contact.
    normal : 3 floats
        The ground's normal.

    Raises
    ------
    FrameNotFoundError
        An unknown frame.
    ConfigurationError
        q has the wrong size or is not finite.
    ParameterError
        Bad friction or normal.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> (foot,) = pinlin.ground_contacts(robot, np.zeros(2), ["tip"], friction=0.5)
    >>> foot.contact, foot.friction, foot.target
    (True, 0.5, array([ 0. ,  0. , -1.2]))
    """
    q = np.asarray(q, dtype=float)
    if q.shape != (robot.nq,) or not np.all(np.isfinite(q)):
        raise ConfigurationError(f"q must be {robot.nq} finite numbers (nq), got shape {q.shape}")
    ids = [robot.frame_id(f) for f in frames]
    data = robot.create_data()
    pin.framesForwardKinematics(robot.model, data, pin.normalize(robot.model, q))
    return [
        PointConstraint(f, data.oMf[i].translation.copy(), contact=True, friction=friction, normal=normal, name=f)
        for f, i in zip(frames, ids)
    ]
