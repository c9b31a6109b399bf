"""A scene: a robot, its force elements, its kinematic constraints, gravity and prescribed joint velocities."""

from __future__ import annotations

import math
import types
from collections.abc import Iterable, Mapping

import numpy as np
import pinocchio as pin

from ..errors import ConfigurationError, ParameterError, PrescribedJointError
from .constraints import Constraint, PointConstraint
from .constraints.base import constraint_list
from .elements import Element, JointDamper, WrenchElement
from .elements.base import check_vector3
from .elements.invariance import invariance_kind
from .motions import common_period, split_prescribed
from .robot import Robot

__all__ = ["Scene", "ANGLE_LIMIT", "UNIT_NORM_MIN"]

#: Largest revolute angle [rad] accepted: beyond 2 pi / eps consecutive doubles are over a turn apart.
ANGLE_LIMIT = 2.0 * math.pi / float(np.finfo(float).eps)
#: Smallest unit quaternion or (cos, sin) pair :meth:`Scene.check_configuration` normalizes: one this
#: short is unset (typed zeros), not a rotation, and normalizing it would amplify its rounding over 1e8.
UNIT_NORM_MIN = 1e-8
#: Up to _SMALL_NQ entries q is checked as Python floats (cheaper than numpy calls for few); a norm
#: of q up to _HALF_LIMIT puts every entry within ANGLE_LIMIT (half: far above the norm's rounding).
_SMALL_NQ, _HALF_LIMIT, _F64 = 64, 0.5 * ANGLE_LIMIT, np.dtype(np.float64)
#: Joint kinds whose configuration ends with a unit vector (quaternion, or (cos, sin)), and its size.
_UNIT_BLOCKS = {"FreeFlyer": 4, "Spherical": 4, "RUBX": 2, "RUBY": 2, "RUBZ": 2, "RevoluteUnboundedUnaligned": 2, "Planar": 2}


class Scene:
    """What acts on a robot: elements, constraints, gravity, prescribed joint velocities (theory: elements, constraints).

    An immutable description: it owns a copy of the robot's model (with the scene's
    gravity) and no Pinocchio ``Data``, so any number of threads may share it.  The
    coordinates of the linearized equations are the free degrees of freedom: every
    velocity coordinate except those of prescribed joints.

    Parameters
    ----------
    robot : Robot
    elements : iterable of Element
        Springs, dampers, Rayleigh damping, follower and dead wrenches.
    gravity : 3 floats
        Gravity vector [m/s^2] in world axes; zero is allowed.
    prescribed : mapping of str to float or Motion, optional
        Joint name -> constant velocity [rad/s or m/s] of a 1-DOF joint (a turntable, a
        rotor) or a periodic motion (:class:`~pinlin.Harmonic`, :class:`~pinlin.FourierMotion`,
        :class:`~pinlin.PeriodicMotion`; theory: Floquet), kept in ``prescribed`` and
        ``motions`` (their common period ``motion_period``, their velocity at t = 0 in
        ``v0``).  Refused together with constraints, whose steady motion needs J_c-dot terms.
    constraints : iterable of Constraint, optional
        Closed loops and contacts (:class:`~pinlin.PointConstraint`,
        :class:`~pinlin.FrameConstraint`), each ``name`` at most once.  Default: the
        robot's own (``robot.constraints``, from an MJCF file); a list given here replaces them.
    urdf_damping : bool
        Add the URDF's ``<dynamics damping>`` as joint dampers (Pinocchio's dynamics ignore it).
    memory_limit : int, optional
        Bytes allowed for Pinocchio's data, see :func:`pinlin.load_urdf`.

    Raises
    ------
    ParameterError
        An element is not an :class:`Element`, gravity is not 3 finite numbers,
        a prescribed velocity is not finite.
    JointNotFoundError, FrameNotFoundError
        An element or prescribed velocity names something the robot lacks.
    PrescribedJointError
        A prescribed joint is not 1-DOF, every joint is prescribed, or constraints too.
    QuasiPeriodicError
        Periodic motions without a common period (:func:`pinlin.model.motions.common_period`).

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 2.0)])
    >>> scene
    Scene('double_pendulum', n=2, 1 spring, gravity=[0.0, 0.0, -9.81])
    >>> pinlin.linearize(scene, scene.neutral()).S.shape
    (2, 2)
    """

    def __init__(
        self,
        robot: Robot,
        elements: Iterable[Element] = (),
        *,
        gravity=(0.0, 0.0, -9.81),
        prescribed: Mapping[str, float] | None = None,
        urdf_damping: bool = False,
        memory_limit: int | None = None,
        constraints: Iterable[Constraint] | None = None,
    ):
        if not isinstance(robot, Robot):
            raise ParameterError("robot", f"expected a pinlin.Robot, got {type(robot).__name__}")
        self.robot = robot
        elements = tuple(elements)
        for i, element in enumerate(elements):
            if not isinstance(element, Element):
                raise ParameterError(
                    f"elements[{i}]", f"expected a pinlin element (JointSpring, ...), got {element!r}"
                )
            element.check(robot)
            invariance_kind(element)  # a misspelt declaration is refused now, not at the first linearize
        self._user_elements = elements
        self.urdf_damping = bool(urdf_damping)
        if self.urdf_damping:
            elements = elements + self._urdf_dampers(robot)
        self.elements: tuple[Element, ...] = elements
        self.gravity = check_vector3(gravity, "gravity")
        self.gravity.flags.writeable = False
        self._has_gravity = bool(np.any(self.gravity != 0))

        pres, motions = split_prescribed(robot, prescribed)
        self.prescribed = types.MappingProxyType(pres)
        self.motions = types.MappingProxyType(motions)
        self.motion_period = common_period({name: m.period for name, m in motions.items()})
        self.memory_limit = memory_limit
        self._user_constraints = None if constraints is None else constraint_list(constraints)
        self.constraints = self._check_constraints(robot, self._user_constraints)
        mask = np.ones(robot.nv, dtype=bool)
        self.v0 = np.zeros(robot.nv)
        for name, omega in pres.items():
            j = robot.joint(name)
            mask[j.idx_v] = False
            self.v0[j.idx_v] = omega
        for name, motion in motions.items():  # the velocity at t = 0
            j = robot.joint(name)
            mask[j.idx_v] = False
            self.v0[j.idx_v] = motion.v(0.0)
        if not mask.any():
            raise PrescribedJointError("every joint is prescribed: no free degree of freedom is left")
        self.v0.flags.writeable = False
        self.free_dofs = np.flatnonzero(mask)
        self.prescribed_dofs = np.flatnonzero(~mask)
        self.free_dofs.flags.writeable = False
        self.prescribed_dofs.flags.writeable = False
        all_names = robot.dof_names
        self.dof_names = tuple(all_names[i] for i in self.free_dofs)

        self.model = pin.Model(robot.model)
        self.model.gravity = pin.Motion(self.gravity, np.zeros(3))
        robot.check_memory(memory_limit)  # refuse a model whose workspace would not fit, now
        self._compile()
        self._compile_constraints()
        self._compile_configuration()
        self._frozen = True

    def __setattr__(self, name, value):
        if getattr(self, "_frozen", False):
            raise AttributeError(f"Scene is immutable (threads share it): cannot set {name!r}; use replace()")
        object.__setattr__(self, name, value)

    def _compile(self) -> None:
        """Group the elements by class for evaluation; build the body-fixed wrenches' (followers')
        part of Pinocchio's ``fext`` once (only world-fixed wrenches are re-expressed at each q)."""
        by_class: dict[type, list[Element]] = {}
        for element in self.elements:
            if not element.is_wrench:
                by_class.setdefault(type(element), []).append(element)
        self.groups = tuple(cls.group(tuple(els), self.robot) for cls, els in by_class.items())
        wrenches = self.wrenches
        self.varying_wrenches = tuple(w for w in wrenches if not w.body_fixed)
        self.constant_fext = None
        if wrenches:
            fext = pin.StdVec_Force()
            for _ in range(self.model.njoints):
                fext.append(pin.Force.Zero())
            for w in wrenches:
                if w.body_fixed:
                    jid, f = w.joint_wrench(None, self.model, self.robot)
                    fext[jid] = fext[jid] + f
            self.constant_fext = fext

    def _compile_constraints(self) -> None:
        """Row layout of the stacked constraint equations (scene order), for vectorized checks.

        ``constraint_rows`` (a slice per constraint), ``position_rows`` / ``rotation_rows`` (k x 3),
        the contacts' ``contact_index``, ``contact_rows``, ``contact_normals``, ``contact_friction``
        (inf when unchecked); ``world_points`` (frame ids, targets) when every constraint holds a
        frame's origin at a world point.
        """
        rows, position, rotation, contacts = [], [], [], []
        start = 0
        for i, c in enumerate(self.constraints):
            rows.append(slice(start, start + c.size))
            position.append(range(start, start + 3))
            if c.size == 6:
                rotation.append(range(start + 3, start + 6))
            if getattr(c, "contact", False):
                contacts.append(i)
            start += c.size
        self.constraint_rows = tuple(rows)
        self.position_rows = np.array(position, dtype=int).reshape(-1, 3)
        self.rotation_rows = np.array(rotation, dtype=int).reshape(-1, 3)
        self.contact_index = tuple(contacts)
        self.contact_rows = self.position_rows[contacts] if contacts else np.zeros((0, 3), dtype=int)
        self.contact_normals = np.array([self.constraints[i].normal for i in contacts]).reshape(-1, 3)
        friction = [self.constraints[i].friction for i in contacts]
        self.contact_friction = np.array([np.inf if mu is None else mu for mu in friction], dtype=float)
        # the common case, points held at world points (contacts, pins to the ground), is evaluated as one group
        self.world_points = None
        if self.constraints and all(isinstance(c, PointConstraint) and c.target_frame is None for c in self.constraints):
            self.world_points = (
                tuple(self.robot.frame_id(c.frame) for c in self.constraints),
                np.array([c.target for c in self.constraints]),
            )

    def _compile_configuration(self) -> None:
        """Bounds and unit blocks of q, for :meth:`check_configuration` (one vectorized pass per call).

        ``q_limit`` (nq,), read-only: :data:`ANGLE_LIMIT` on revolute angles, the largest double elsewhere
        (one comparison also catches inf and NaN); ``unit_blocks``: (joint name, slice of q) of each
        quaternion and (cos, sin) pair, None when there is none (also read by ``linearize_many``).
        """
        limit = np.full(self.robot.nq, np.finfo(float).max)
        blocks: list[tuple[str, slice]] = []
        for name in self.robot.joint_names:
            j = self.robot.joint(name)
            kind = j.kind.removeprefix("JointModel")
            if j.nq == 1 and (kind in ("RX", "RY", "RZ") or kind == "RevoluteUnaligned"):
                limit[j.idx_q] = ANGLE_LIMIT
            elif kind in _UNIT_BLOCKS:  # the unit vector ends the joint's configuration
                end = j.idx_q + j.nq
                blocks.append((name, slice(end - _UNIT_BLOCKS[kind], end)))
        limit.flags.writeable = False
        self.q_limit = limit
        self._q_shape = (self.robot.nq,)
        self._q_small = self.robot.nq <= _SMALL_NQ
        self.unit_blocks = tuple(blocks) or None

    def _check_constraints(self, robot: Robot, given: tuple | None) -> tuple[Constraint, ...]:
        constraints = robot.constraints if given is None else given
        for i, constraint in enumerate(constraints):
            if not isinstance(constraint, Constraint):
                raise ParameterError(
                    f"constraints[{i}]", f"expected a PointConstraint or FrameConstraint, got {constraint!r}"
                )
            constraint.check(robot)
        if constraints and (self.prescribed or self.motions):
            raise PrescribedJointError(
                f"a scene with constraints cannot have prescribed joint velocities or motions "
                f"({sorted(self.prescribed) + sorted(self.motions)}): "
                f"the steady motion of a constrained system needs the J_c-dot terms, which pinlin does not "
                f"linearize; remove the prescribed velocities or the constraints"
            )
        return tuple(constraints)

    @staticmethod
    def _urdf_dampers(robot: Robot) -> tuple[Element, ...]:
        dampers = []
        for j in (robot.joint(n) for n in robot.joint_names):
            c = np.asarray(robot.model.damping[j.v_slice], dtype=float)
            if np.any(c != 0):
                dampers.append(JointDamper(j.name, c if j.nv > 1 else float(c[0])))
        return tuple(dampers)

    # ------------------------------------------------------------------ structure

    @property
    def n(self) -> int:
        """Number of free velocity coordinates (the linearized size without constraints)."""
        return len(self.free_dofs)

    @property
    def wrenches(self) -> tuple[WrenchElement, ...]:
        return tuple(e for e in self.elements if isinstance(e, WrenchElement))

    @property
    def needs(self) -> frozenset[str]:
        """What the scene's elements read beyond the dynamics (see :meth:`Element.needs`)."""
        out: frozenset[str] = frozenset()
        for element in self.elements:
            out = out | element.needs()
        return out

    @property
    def constraint_size(self) -> int:
        """Number of scalar constraint equations m (3 per point, 6 per frame constraint)."""
        return sum(c.size for c in self.constraints)

    @property
    def has_gravity(self) -> bool:
        """True when gravity is not zero (decided once: the scene is immutable)."""
        return self._has_gravity

    def replace(self, **changes) -> Scene:
        """A new scene with some constructor arguments changed (for sweeps).

        Examples
        --------
        >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
        >>> scene.replace(gravity=(0.0, 0.0, 0.0))
        Scene('double_pendulum', n=2, no elements, gravity=[0.0, 0.0, 0.0])
        """
        args = dict(
            robot=self.robot,
            elements=self._user_elements,
            gravity=self.gravity,
            prescribed={**self.prescribed, **self.motions},
            urdf_damping=self.urdf_damping,
            memory_limit=self.memory_limit,
            constraints=self._user_constraints,
        )
        unknown = set(changes) - set(args)
        if unknown:
            raise ParameterError("replace", f"unknown scene arguments {sorted(unknown)}; valid: {sorted(args)}")
        args.update(changes)
        robot = args.pop("robot")
        elements = args.pop("elements")
        return Scene(robot, elements, **args)

    def neutral(self) -> np.ndarray:
        """Pinocchio's neutral configuration of the robot (nq,).

        Examples
        --------
        >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
        >>> scene.neutral()
        array([0., 0.])
        """
        return self.robot.neutral()

    def check_configuration(self, q, label: str = "q") -> np.ndarray:
        """A finite configuration of size nq, normalized on its manifold (a copy).

        Quaternions and (cos, sin) pairs are normalized (``pin.normalize``); those shorter than
        :data:`UNIT_NORM_MIN`, and revolute angles beyond :data:`ANGLE_LIMIT`, are refused.

        Raises
        ------
        ConfigurationError
            Wrong size, complex or non-finite entries, an angle or a unit vector out of bounds.

        Examples
        --------
        >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
        >>> scene.check_configuration([0.1, 0.2])
        array([0.1, 0.2])
        """
        if type(q) is np.ndarray and q.dtype is _F64:  # the common case; pin.normalize below copies too
            q = q.copy() if self.unit_blocks is None else q  # the result may be frozen read-only
        else:  # numpy would drop an imaginary part with a warning
            try:
                complex_entries = np.iscomplexobj(q)
                q = np.array(q, dtype=float) if not complex_entries else q
            except (TypeError, ValueError):  # strings, a ragged nested list
                raise ConfigurationError(f"{label} must be an array of numbers, got {q!r:.80}") from None
            if complex_entries:
                raise ConfigurationError(f"{label} must be real, got complex entries: {q!r:.80}")
            if q.ndim == 0:
                q = q.reshape(1)
        if q.shape != self._q_shape:
            raise ConfigurationError(
                f"{label} has shape {q.shape}; robot {self.robot.name!r} needs a full Pinocchio "
                f"configuration of size nq = {self.robot.nq} (prescribed joints included)"
            )
        # |q_i| <= ||q|| (rounding is monotone; NaN, inf: no norm): one norm, else each entry vs its limit
        values = q.tolist() if self._q_small else None
        within = math.hypot(*values) <= _HALF_LIMIT if values is not None else np.dot(q, q) <= _HALF_LIMIT**2
        if not within and not (np.abs(q) <= self.q_limit).all():
            self._refuse_configuration(q, label)
        if self.unit_blocks is None:  # a vector space: nothing to normalize
            return q
        for name, block in self.unit_blocks:
            unit = values[block] if values is not None else q[block].tolist()
            length = math.hypot(*unit)
            if not length >= UNIT_NORM_MIN:  # False for NaN
                raise ConfigurationError(
                    f"{label}[{block.start}:{block.stop}] = {unit} of joint {name!r} is not a rotation: "
                    f"its length {length:.3g} is below {UNIT_NORM_MIN:g} (a unit quaternion or "
                    f"(cos, sin) pair is expected; pinlin does not take a zero one as the identity)"
                )
        return pin.normalize(self.model, q)  # a fresh array

    def _refuse_configuration(self, q: np.ndarray, label: str) -> None:
        bad = np.flatnonzero(~np.isfinite(q))
        if bad.size:
            raise ConfigurationError(f"{label} has non-finite entries at {bad.tolist()}: {q}")
        k = int(np.flatnonzero(np.abs(q) > self.q_limit)[0])
        joint = next(n for n in self.robot.joint_names if self.robot.joint(n).idx_q == k)
        raise ConfigurationError(  # only revolute angles have a limit below the largest double
            f"{label}[{k}] = {q[k]:.6g} rad on revolute joint {joint!r} is beyond {ANGLE_LIMIT:.3g} rad: "
            f"doubles that large are more than a turn apart, so the angle does not say where the joint is; "
            f"give the angle modulo 2 pi"
        )

    def __repr__(self) -> str:
        kinds: dict[str, int] = {}
        for e in self.elements:
            kinds[e.kind] = kinds.get(e.kind, 0) + 1
        parts = ", ".join(f"{v} {k}" for k, v in kinds.items()) or "no elements"
        given = {**self.prescribed, **self.motions}
        pres = f", prescribed={given}" if given else ""
        loops = f", {len(self.constraints)} constraints (m = {self.constraint_size})" if self.constraints else ""
        return f"Scene({self.robot.name!r}, n={self.n}, {parts}{loops}, gravity={self.gravity.tolist()}{pres})"
