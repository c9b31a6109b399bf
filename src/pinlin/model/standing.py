"""Legged robots standing on the ground: a scene ready for ``find_equilibrium`` and ``linearize``.

:func:`standing_scene` takes a floating-base robot, a nominal pose (the SRDF's
``standing`` configuration where there is one), lowers or raises the base so that
the lowest foot touches the ground plane, holds every actuated joint at the pose
with a spring (and a damper, a PD servo's linear model), and puts a
:func:`~pinlin.ground_contacts` point contact under each foot where it stands.
The contacts are bilateral in the linearization, as in every standing
linearization; the equilibrium reports whether the ground would have to pull or
friction exceed ``friction`` (:attr:`~pinlin.EquilibriumResult.contacts`).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..errors import ConfigurationError, ParameterError
from ..numerics.arrays import readonly
from .constraints import ground_contacts
from .elements import JointDamper, JointSpring
from .robot import Robot
from .scene import Scene

__all__ = ["Standing", "standing_scene", "STANDING_POSES"]

#: SRDF configurations tried, in order, for the nominal pose when ``q`` is not given.
STANDING_POSES = ("standing", "straight_standing", "half_sitting")


@dataclass(frozen=True)
class Standing:
    """A standing robot: what :func:`pinlin.find_equilibrium` and :func:`pinlin.linearize` need.

    Attributes
    ----------
    scene : Scene
        Joint springs (and dampers) at the pose, ground contacts under the feet, gravity.
    q0 : (nq,) ndarray
        The nominal pose with the feet on the ground: the start of ``find_equilibrium``.
    feet : tuple of str
        The contact frames, in the order of ``scene.constraints``.
    pose : str
        Where the pose came from: an SRDF configuration's name, or ``"given"``.
    weight : float
        The robot's weight ``g * total mass`` [N], what the contacts carry at equilibrium.

    Examples
    --------
    >>> robot = pinlin.load_example("a1")
    >>> standing = pinlin.standing_scene(robot, ["FL_foot", "FR_foot", "RL_foot", "RR_foot"], stiffness=100.0)
    >>> standing.pose, standing.feet, standing.q0.shape
    ('standing', ('FL_foot', 'FR_foot', 'RL_foot', 'RR_foot'), (19,))
    """

    scene: Scene
    q0: np.ndarray
    feet: tuple[str, ...]
    pose: str
    weight: float

    def __repr__(self) -> str:
        return (f"Standing({self.scene.robot.name!r}, feet={list(self.feet)}, pose={self.pose!r}, "
                f"weight={self.weight:.6g} N)")


def _gain(value, name: str, joints: Sequence[str], allow_zero: bool) -> dict[str, float]:
    items = value.items() if isinstance(value, Mapping) else ((j, value) for j in joints)
    out = {}
    for joint, gain in items:
        ok = isinstance(gain, numbers.Real) and not isinstance(gain, bool) and math.isfinite(gain)
        if not ok or gain < 0 or (gain == 0 and not allow_zero):
            bound = ">= 0" if allow_zero else "> 0"
            raise ParameterError(f"{name}[{joint!r}]" if isinstance(value, Mapping) else name,
                                 f"expected a finite number {bound}, got {gain!r}")
        out[joint] = float(gain)
    missing = [j for j in joints if j not in out]
    if missing:
        raise ParameterError(name, f"no value for joints {missing}")
    return out


def _pose(robot: Robot, q) -> tuple[np.ndarray, str]:
    if q is not None:
        q = np.asarray(q, dtype=float)
        if q.shape != (robot.nq,) or not np.all(np.isfinite(q)):
            raise ConfigurationError(f"q must be {robot.nq} finite numbers (nq), got shape {q.shape}")
        return pin.normalize(robot.model, q), "given"
    for name in STANDING_POSES:
        if name in robot.reference_configurations:
            return np.array(robot.reference_configurations[name]), name
    return robot.neutral(), "neutral"


def _on_the_ground(robot: Robot, q: np.ndarray, feet: Sequence[str], normal: np.ndarray) -> np.ndarray:
    """q with the base moved along the normal so that the lowest foot is on the plane n . x = 0."""
    ids = [robot.frame_id(f) for f in feet]
    data = robot.create_data()
    pin.framesForwardKinematics(robot.model, data, q)
    height = min(float(normal @ data.oMf[i].translation) for i in ids)
    q = q.copy()
    q[0:3] -= height * normal
    return q


def standing_scene(
    robot: Robot,
    feet: Sequence[str],
    *,
    stiffness: float | Mapping[str, float],
    damping: float | Mapping[str, float] = 0.0,
    q=None,
    friction: float | None = None,
    gravity=(0.0, 0.0, -9.81),
) -> Standing:
    """A floating-base robot standing on its ``feet``, held at a pose by joint springs.

    Parameters
    ----------
    robot : Robot
        With a free-flyer root joint (``load_example("go1")`` has one by default).
    feet : sequence of str
        Contact frames (``["FL_foot", "FR_foot", "RL_foot", "RR_foot"]`` for go1).
    stiffness : float or mapping of joint name to float
        Joint spring stiffness [N m/rad or N/m], > 0, for every joint but the root.
    damping : float or mapping, optional
        Joint damping [N m s/rad or N s/m], >= 0; 0 adds no damper.
    q : (nq,) array, optional
        Nominal pose; default the SRDF's first of :data:`STANDING_POSES`, else neutral.
        The springs rest there; the base is then moved along the ground normal so the
        lowest foot touches the ground plane through the origin.
    friction : float, optional
        Friction coefficient of every contact (for :attr:`EquilibriumResult.contacts`).
    gravity : 3 floats
        [m/s^2]; the ground normal is ``-gravity / |gravity|``.

    Returns
    -------
    Standing
        ``.scene`` and ``.q0`` for ``find_equilibrium(standing.scene, standing.q0)``.

    Raises
    ------
    ParameterError
        The root joint is not a free flyer, no feet, bad gains, zero or non-finite gravity.
    FrameNotFoundError
        An unknown foot.
    ConfigurationError
        ``q`` of the wrong size or not finite.

    Examples
    --------
    >>> robot = pinlin.load_example("a1")
    >>> standing = pinlin.standing_scene(robot, ["FL_foot", "FR_foot", "RL_foot", "RR_foot"], stiffness=100.0)
    >>> print(f"{standing.weight:.3f}")
    134.799
    """
    if robot.nv == 0 or robot.joint(robot.joint_names[0]).kind != "JointModelFreeFlyer":
        raise ParameterError("robot", f"{robot.name!r} has no free-flyer root joint: load it with free_flyer=True")
    feet = tuple(feet) if not isinstance(feet, str) else (feet,)
    if not feet:
        raise ParameterError("feet", "expected at least one contact frame")
    g = np.asarray(gravity, dtype=float)
    if g.shape != (3,) or not np.all(np.isfinite(g)) or not np.linalg.norm(g) > 0:
        raise ParameterError("gravity", f"expected 3 finite numbers, not all zero, got {gravity!r}")
    normal = -g / np.linalg.norm(g)
    joints = [j for j in robot.joint_names[1:]]
    k = _gain(stiffness, "stiffness", joints, allow_zero=False)
    c = _gain(damping, "damping", joints, allow_zero=True)
    q0, pose = _pose(robot, q)
    q0 = _on_the_ground(robot, q0, feet, normal)
    elements = [JointSpring(j, k[j], rest=q0[robot.joint(j).q_slice]) for j in joints]
    elements += [JointDamper(j, c[j]) for j in joints if c[j] > 0]
    contacts = ground_contacts(robot, q0, feet, friction=friction, normal=normal)
    scene = Scene(robot, elements, gravity=g, constraints=contacts)
    weight = float(np.linalg.norm(g)) * sum(inertia.mass for inertia in robot.model.inertias)
    return Standing(scene, readonly(q0), feet, pose, weight)
