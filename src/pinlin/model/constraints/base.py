"""The constraint interface: what every kinematic constraint of a scene implements (theory: constraints)."""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

import numpy as np

from ...errors import ParameterError
from .forces import ConstraintForce
from .stiffness import CONSTANT_SUBSPACE_JOINTS, dead_wrench_stiffness, stack_wrenches

__all__ = ["Constraint", "constraint_list"]


class Constraint(ABC):
    """A kinematic constraint Phi(q) = 0 between a frame and a target (theory: constraints).

    Subclasses are frozen dataclasses with fields ``frame``, ``target`` and
    ``name``; a :class:`~pinlin.Scene` checks them against its robot.

    Examples
    --------
    >>> loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0))
    >>> isinstance(loop, pinlin.Constraint), loop.label, loop.target_frame
    (True, 'rocker_tip', None)
    """

    #: Short label for reports and scene files.
    kind: ClassVar[str] = "constraint"
    #: Number of scalar equations m.
    size: ClassVar[int] = 0
    frame: str
    target: object
    name: str | None

    @property
    def label(self) -> str:
        """The name, else ``frame`` (a world target) or ``frame-target``."""
        if self.name:
            return self.name
        return f"{self.frame}-{self.target}" if isinstance(self.target, str) else self.frame

    @property
    def target_frame(self) -> str | None:
        """The target's frame name, or None for a fixed world target."""
        return self.target if isinstance(self.target, str) else None

    def check(self, robot) -> None:
        """Raise when the frame or the target frame is not in ``robot`` or moves with unsupported joints.

        Raises
        ------
        FrameNotFoundError
            Unknown frame or target frame (the message lists the valid names).
        ParameterError
            The frame is its own target, or a joint moving a frame has a
            configuration-dependent motion subspace (composite, universal,
            spherical-ZYX, mimic joints), where :func:`dead_wrench_stiffness` does not hold.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> pinlin.PointConstraint("tip", "tip").check(robot)
        Traceback (most recent call last):
        ...
        pinlin.errors.base.ParameterError: PointConstraint('tip').target: a frame cannot be its own target
        """
        label = f"{type(self).__name__}({self.frame!r})"
        frames = [self.frame] if self.target_frame is None else [self.frame, self.target_frame]
        if self.target_frame == self.frame:
            raise ParameterError(f"{label}.target", "a frame cannot be its own target")
        model = robot.model
        for frame in frames:
            fid = robot.frame_id(frame)
            for jid in model.supports[model.frames[fid].parentJoint]:
                joint = model.joints[jid]
                kind = joint.shortname()
                if jid and not ((joint.nv == 1 and "Mimic" not in kind) or kind in CONSTANT_SUBSPACE_JOINTS):
                    raise ParameterError(
                        label,
                        f"joint {model.names[jid]!r} ({kind}) moves frame {frame!r}; constraints support 1-DOF "
                        f"joints and {sorted(CONSTANT_SUBSPACE_JOINTS)} (motion subspace constant in the joint frame)",
                    )

    def _target_placement(self, ev) -> tuple[np.ndarray, np.ndarray, int | None]:
        """World position, rotation and frame id (None for world targets) of the target."""
        if self.target_frame is not None:
            fid = ev.robot.frame_id(self.target_frame)
            return ev.frame_position(fid), ev.frame_rotation(fid), fid
        H = np.asarray(self.target)
        if H.shape == (3,):
            return H, np.eye(3), None
        return H[:3, 3], H[:3, :3], None

    def _relative_jacobian(self, ev) -> np.ndarray:
        """Frame Jacobian minus target Jacobian, LOCAL_WORLD_ALIGNED (6 x nv)."""
        J = ev.world_aligned_jacobian(ev.robot.frame_id(self.frame))
        if self.target_frame is not None:
            J = J - ev.world_aligned_jacobian(ev.robot.frame_id(self.target_frame))
        return J

    def _pair(self, ev, force: np.ndarray, torque: np.ndarray | None) -> list[tuple]:
        """(J, force, torque) on the frame, and the opposite on a target frame."""
        out = [(ev.world_aligned_jacobian(ev.robot.frame_id(self.frame)), force, torque)]
        if self.target_frame is not None:
            J_b = ev.world_aligned_jacobian(ev.robot.frame_id(self.target_frame))
            out.append((J_b, -force, None if torque is None else -torque))
        return out

    def force_stiffness(self, ev, lam: np.ndarray) -> np.ndarray:
        """K_lambda = d(J_c^T lam)/dq at fixed lam (nv x nv), see :func:`dead_wrench_stiffness`.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> hold = pinlin.PointConstraint("tip", (0.0, 0.0, -1.2))   # the tip held at a world point
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [], constraints=[hold]), np.array([0.1, 0.0]), np.zeros(2))
        >>> np.round(hold.force_stiffness(ev, np.array([0.0, 0.0, 5.0])), 6)   # 5 N upwards on the tip
        array([[5.970025, 2.48751 ],
               [2.48751 , 2.48751 ]])
        """
        return dead_wrench_stiffness(*stack_wrenches(self.wrench_terms(ev, lam)), ev.robot.dof_supports)

    @abstractmethod
    def residual(self, ev) -> np.ndarray:
        """Phi(q) (m,): [m] for positions, [rad] for rotations.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> hold = pinlin.PointConstraint("tip", (0.0, 0.0, -1.2))   # the tip held at a world point
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [], constraints=[hold]), np.array([0.1, 0.0]), np.zeros(2))
        >>> np.round(hold.residual(ev), 6)   # tip position minus target, world axes
        array([-0.1198  ,  0.      ,  0.005995])
        """

    @abstractmethod
    def jacobian(self, ev) -> np.ndarray:
        """J_c (m x nv) in velocity form: the frame's velocity relative to the target, world axes.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> hold = pinlin.PointConstraint("tip", (0.0, 0.0, -1.2))   # the tip held at a world point
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [], constraints=[hold]), np.array([0.1, 0.0]), np.zeros(2))
        >>> np.round(hold.jacobian(ev), 6)
        array([[-1.194005, -0.497502],
               [ 0.      ,  0.      ],
               [ 0.1198  ,  0.049917]])
        """

    def closure_jacobian(self, ev) -> np.ndarray:
        """dPhi/dq (m x nv, tangent space), exact also off the manifold (for closing loops).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> hold = pinlin.PointConstraint("tip", (0.0, 0.0, -1.2))   # the tip held at a world point
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [], constraints=[hold]), np.array([0.1, 0.0]), np.zeros(2))
        >>> bool(np.array_equal(hold.closure_jacobian(ev), hold.jacobian(ev)))   # a point: the same
        True
        """
        return self.jacobian(ev)

    @abstractmethod
    def wrench_terms(self, ev, lam: np.ndarray) -> list[tuple]:
        """The world-fixed wrenches J_c^T lam stands for: (J, force, torque) per frame (:func:`dead_wrench_stiffness`).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> hold = pinlin.PointConstraint("tip", (0.0, 0.0, -1.2))   # the tip held at a world point
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [], constraints=[hold]), np.array([0.1, 0.0]), np.zeros(2))
        >>> ((J, force, torque),) = hold.wrench_terms(ev, np.array([0.0, 0.0, 5.0]))
        >>> J.shape, force, torque
        ((6, 2), array([0., 0., 5.]), None)
        """

    @abstractmethod
    def force(self, lam: np.ndarray, copy: bool = True) -> ConstraintForce:
        """The wrench ``lam`` (this constraint's multipliers) as a :class:`ConstraintForce`.

        ``copy=False``: ``lam`` is a float array the caller hands over (a view of its own
        copy of all multipliers), kept without another copy.

        Examples
        --------
        >>> pinlin.PointConstraint("tip", np.zeros(3)).force(np.array([0.0, 0.0, 5.0])).force
        array([0., 0., 5.])
        """

    def gaps(self, phi: np.ndarray) -> tuple[float, float]:
        """Distance [m] and rotation [rad] between the frame and its target for this constraint's Phi.

        Examples
        --------
        >>> pinlin.PointConstraint("tip", np.zeros(3)).gaps(np.array([0.3, 0.0, 0.4]))
        (0.5, 0.0)
        """
        return float(np.linalg.norm(phi[:3])), float(np.linalg.norm(phi[3:])) if len(phi) > 3 else 0.0


def constraint_list(constraints) -> tuple[Constraint, ...]:
    """The ``constraints`` argument of a :class:`~pinlin.Scene` as a tuple: a list of constraints, each
    ``name`` given at most once.

    A single constraint is refused rather than accepted (``constraints=c`` reads
    like a list by mistake; one rule, a list, for one constraint and for many).

    Raises
    ------
    ParameterError
        Named ``constraints``: one constraint instead of a list, something not
        iterable; named ``constraints[i]``: an item that is not a constraint, a
        name an earlier constraint already has.
    """
    if isinstance(constraints, Constraint):
        raise ParameterError("constraints", f"expected a list of constraints, got a single one: "
                             f"write constraints=[{constraints!r}]")
    if isinstance(constraints, (str, bytes)) or not hasattr(constraints, "__iter__"):
        raise ParameterError("constraints", f"expected a list of PointConstraint or FrameConstraint, got {constraints!r}")
    out = tuple(constraints)
    named: dict[str, int] = {}
    for i, constraint in enumerate(out):
        if not isinstance(constraint, Constraint):
            raise ParameterError(f"constraints[{i}]", f"expected a PointConstraint or FrameConstraint, got {constraint!r}")
        if constraint.name and named.setdefault(constraint.name, i) != i:
            raise ParameterError(f"constraints[{i}]", f"the name {constraint.name!r} is already that of "
                                 f"constraints[{named[constraint.name]}]: give each constraint its own name")
    return out
