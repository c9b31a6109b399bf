"""A rigid multibody: :class:`Robot`, a Pinocchio model without geometry, with name lookups.

Loading from URDF and example-robot-data is in :mod:`.loading`, from MJCF in :mod:`.mjcf`; the memory
guard in front of ``createData`` in :mod:`.memory`.
"""

from __future__ import annotations

import types
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..errors import FrameNotFoundError, JointNotFoundError, ParameterError
from ..numerics.arrays import readonly as _readonly
from .constraints import Constraint
from .memory import check_memory

__all__ = ["Robot", "JointInfo"]

@dataclass(frozen=True)
class JointInfo:
    """Where one joint sits in the configuration and velocity vectors.

    Attributes
    ----------
    name : str
    id : int
        Pinocchio joint index (``model.joints[id]``).
    kind : str
        Pinocchio's short name, for example ``"JointModelRY"``.
    idx_q, nq : int
        Slice ``q[idx_q:idx_q + nq]`` of the configuration.
    idx_v, nv : int
        Slice ``v[idx_v:idx_v + nv]`` of the velocity (tangent space).
    """

    name: str
    id: int
    kind: str
    idx_q: int
    nq: int
    idx_v: int
    nv: int

    @property
    def q_slice(self) -> slice:
        return slice(self.idx_q, self.idx_q + self.nq)

    @property
    def v_slice(self) -> slice:
        return slice(self.idx_v, self.idx_v + self.nv)


class Robot:
    """A rigid multibody: a Pinocchio model with name lookups.

    The model is never modified by pinlin; analyses copy it when they need to
    change it (gravity, for instance).  Build one with :func:`load_urdf`,
    :func:`load_urdf_string`, :func:`load_example` or :func:`load_mjcf`.

    Attributes
    ----------
    model : pinocchio.Model
        The underlying kinematic and inertial model (no geometry).
    source : str
        Where the model came from (a path, ``"<string>"`` or ``"example:NAME"``).
    reference_configurations : dict of str to ndarray
        Named configurations from the SRDF, when one was available.
    constraints : tuple of Constraint
        Kinematic constraints that come with the model (an MJCF file's
        ``<equality>`` connects and welds, :func:`pinlin.load_mjcf`); empty for
        URDF robots.  A :class:`~pinlin.Scene` includes them unless its
        ``constraints=`` says otherwise (theory: constraints).

    Raises
    ------
    ParameterError
        A constraint is not a :class:`~pinlin.Constraint`.
    FrameNotFoundError
        A constraint names a frame the model lacks.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> robot.nq, robot.nv, robot.joint_names
    (2, 2, ('joint1', 'joint2'))
    """

    def __init__(
        self,
        model: pin.Model,
        source: str = "<model>",
        reference_configurations: Mapping[str, np.ndarray] | None = None,
        constraints: Sequence[Constraint] = (),
    ):
        self._model = model
        self.source = source
        self.reference_configurations = types.MappingProxyType(
            {k: _readonly(v) for k, v in (reference_configurations or {}).items()}
        )
        self._joints: dict[str, JointInfo] = {}
        for jid in range(1, model.njoints):
            jm = model.joints[jid]
            self._joints[model.names[jid]] = JointInfo(
                name=model.names[jid],
                id=jid,
                kind=jm.shortname(),
                idx_q=jm.idx_q,
                nq=jm.nq,
                idx_v=jm.idx_v,
                nv=jm.nv,
            )
        self._frames = {}
        for fid, frame in enumerate(model.frames):
            self._frames.setdefault(frame.name, fid)
        dof_joint = np.zeros(model.nv, dtype=int)
        for j in self._joints.values():
            dof_joint[j.v_slice] = j.id
        # Pinocchio numbers joints parent before child: along one chain, a smaller id supports a larger one
        self._dof_supports = dof_joint[None, :] <= dof_joint[:, None]
        self._dof_supports.flags.writeable = False
        self.constraints: tuple[Constraint, ...] = tuple(constraints)
        for i, constraint in enumerate(self.constraints):
            if not isinstance(constraint, Constraint):
                raise ParameterError(f"constraints[{i}]", f"expected a PointConstraint or FrameConstraint, got {constraint!r}")
            constraint.check(self)
        self._frozen = True

    def __setattr__(self, name, value):
        if getattr(self, "_frozen", False):
            raise AttributeError(f"Robot is immutable (threads share it): cannot set {name!r}")
        object.__setattr__(self, name, value)

    @property
    def model(self) -> pin.Model:
        return self._model

    @property
    def name(self) -> str:
        return self._model.name

    @property
    def nq(self) -> int:
        return self._model.nq

    @property
    def nv(self) -> int:
        return self._model.nv

    @property
    def joint_names(self) -> tuple[str, ...]:
        """Names of the movable joints, in model order (the universe excluded)."""
        return tuple(self._joints)

    @property
    def frame_names(self) -> tuple[str, ...]:
        return tuple(self._frames)

    @property
    def dof_names(self) -> tuple[str, ...]:
        """One name per velocity coordinate: the joint name, with ``[k]`` for multi-DOF joints."""
        names: list[str] = []
        for j in self._joints.values():
            names.extend([j.name] if j.nv == 1 else [f"{j.name}[{k}]" for k in range(j.nv)])
        return tuple(names)

    @property
    def dof_supports(self) -> np.ndarray:
        """(nv, nv) bool, read-only: [i, j] when the joint of degree of freedom j comes no later than that of i.

        Pinocchio numbers joints parent before child, so for two degrees of freedom
        that move one frame (they lie on one chain) this says that j's joint
        supports i's, or is it; the derivative of frame Jacobians needs no more
        (:func:`pinlin.model.constraints.dead_wrench_stiffness`).
        """
        return self._dof_supports

    def joint(self, name: str) -> JointInfo:
        """Look a joint up by name.

        Raises
        ------
        JointNotFoundError
            If there is no such joint; the message lists the valid names.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> robot.joint("joint2")
        JointInfo(name='joint2', id=2, kind='JointModelRY', idx_q=1, nq=1, idx_v=1, nv=1)
        """
        try:
            return self._joints[name]
        except KeyError:
            raise JointNotFoundError(name, self.joint_names, context=self.source) from None
        except TypeError:
            raise JointNotFoundError(str(name), self.joint_names, context=self.source) from None

    def frame_id(self, name: str) -> int:
        """Pinocchio frame index of a frame (link, joint or fixed frame) by name.

        Raises
        ------
        FrameNotFoundError
            If there is no such frame; the message lists the valid names.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> robot.model.frames[robot.frame_id("tip")].name
        'tip'
        """
        try:
            return self._frames[name]
        except (KeyError, TypeError):
            raise FrameNotFoundError(str(name), self.frame_names, context=self.source) from None

    def neutral(self) -> np.ndarray:
        """Pinocchio's neutral configuration (size nq).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> robot.neutral()
        array([0., 0.])
        """
        return pin.neutral(self._model)

    def check_memory(self, memory_limit: int | None = None) -> None:
        """Refuse now a model whose Pinocchio data would not fit (see :mod:`.memory`).

        Raises
        ------
        ModelTooLargeError
            When the estimate exceeds the limit.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> robot.check_memory()  # a two-link model fits: nothing happens
        """
        check_memory(self._model.nv, memory_limit, f"model {self._model.name!r}")

    def create_data(self, model: pin.Model | None = None, memory_limit: int | None = None):
        """``model.createData()`` after checking that it fits in memory.

        Raises
        ------
        ModelTooLargeError
            When the estimate of :func:`pinocchio_data_bytes` exceeds the limit.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> data = robot.create_data()
        >>> len(data.oMi)
        3
        """
        model = self._model if model is None else model
        check_memory(model.nv, memory_limit, f"model {model.name!r}")
        return model.createData()

    def __repr__(self) -> str:
        loops = f", constraints={len(self.constraints)}" if self.constraints else ""
        return (
            f"Robot({self.name!r}, nq={self.nq}, nv={self.nv}, "
            f"joints={len(self._joints)}{loops}, source={self.source!r})"
        )
