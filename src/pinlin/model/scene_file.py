"""Scene files: a robot, its elements and a starting point in TOML.

Format (every table is optional except ``[robot]``)::

    [robot]
    urdf = "double_pendulum.urdf"   # relative to this file, else a bundled URDF of that name
    # example = "ur5"               # or an example-robot-data model (instead of urdf)
    # trust_xacro = true            # expand a .xacro urdf: a xacro is a program, trust only your own
    free_flyer = false
    # locked = ["joint2"]           # joints held fixed; or a table: locked = { joint2 = 0.5 }

    [scene]
    gravity = [0.0, 0.0, -9.81]     # [m/s^2]
    urdf_damping = false            # take <dynamics damping> in as joint dampers

    [prescribed]                    # joint = constant velocity [rad/s or m/s]
    # table = 3.0                   # (a turntable's joint: see the bundled scenes/turntable.toml)
    # pivot = { amplitude = 0.02, omega = 60.0 }  # offset + amplitude sin(omega t + phase) (kapitza.toml)

    [start]
    q = [0.0, 0.0]                  # full configuration (nq); or joints = { joint1 = 0.1 }
    # reference = "half_sitting"    # a named SRDF configuration of an example robot
    equilibrium = true              # run find_equilibrium from q before linearizing
    balancing = false               # hold q with constant actuator forces instead

    [[spring]]                      # one table per spring
    joint = "joint1"
    stiffness = 3.0                 # number, list (diagonal) or matrix
    rest = 0.0

    [[damper]]
    joint = "joint1"
    damping = 0.1

    [rayleigh]
    alpha = 0.0
    beta = 1e-3

    [[follower]]                    # force/torque in the frame's axes
    frame = "tip"
    force = [0.0, 0.0, 4.0]
    torque = [0.0, 0.0, 0.0]

    [[dead]]                        # force/torque in world axes
    frame = "tip"
    force = [1.0, 0.0, 0.0]

    [[spring_damper]]               # spring and dashpot between two points
    frame = "tip"
    target = "base"                 # a frame (its origin) or a world point [x, y, z] [m]
    stiffness = 100.0               # [N/m]
    damping = 1.0                   # [N s/m], default 0
    rest_length = 1.2               # [m], default 0

    [[bushing]]                     # six-axis spring and damper on the relative placement
    frame = "tip"
    target = "base"                 # a frame, or a world placement { xyz = [...], rpy = [...] } or 4x4
    stiffness = [1e4, 1e4, 1e4, 50.0, 50.0, 50.0]   # translations [N/m], rotations [N m/rad]; or 6x6
    damping = [10.0, 10.0, 10.0, 0.1, 0.1, 0.1]     # optional, same form
    offset = { xyz = [0.0, 0.0, -1.2], rpy = [0.0, 0.0, 0.0] }  # optional unloaded placement

    # [[constraint]]                # a closed loop or a contact (theory: constraints)
    # type = "point"                # "point" (keeps the frame's origin at target) or "frame"
    # frame = "rocker_tip"          # (a frame of the bundled four_bar.urdf: see scenes/four_bar.toml)
    # target = [0.7, 0.0, 0.0]      # a frame, a world point [m], or (frame) a world placement
    # name = "loop"                 # label in reports
    # contact = true                # point only: one-sided ground contact, checked and reported
    # friction = 0.8                # its friction coefficient
    # normal = [0.0, 0.0, 1.0]      # the ground's normal
    # Without [[constraint]] tables a scene keeps its robot's own constraints (none for a URDF).

    [sweep]                         # for `pinlin sweep`: root locus, verdicts, exact boundaries
    parameter = "follower.tip.force"  # <kind>.<joint or frame>.<field>, prescribed.<joint>, gravity, ...
    values = { start = 0.0, stop = 30.0, num = 31 }  # or a list; a vector is value x its direction
    # [sweep.second]                # a second parameter: a stability map
    # parameter = "spring.joint1.stiffness"
    # values = [1.0, 2.0, 3.0]

    # [campbell]                    # for `pinlin campbell`: needs a prescribed joint (scenes/rotating_ring.toml)
    # joint = "ring"                # a prescribed joint (default: the scene's only one)
    # speeds = { start = 0.0, stop = 6.0, num = 61 }  # [rad/s or m/s]; or a list

Errors name the file and the key (``spring[2].stiffness``).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ParameterError, PinlinError, SceneFileError
from .elements import (
    Bushing,
    DeadWrench,
    FollowerWrench,
    JointDamper,
    JointSpring,
    LinearSpringDamper,
    RayleighDamping,
)
from .loading import data_path, load_example, load_urdf
from .motions import harmonic_from_table
from .robot import Robot
from .scene import Scene
from .scene_file_constraints import read_constraints
from .scene_file_values import Reader, read_placement, read_target

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["SceneSpec", "load_scene", "default_scene_path", "SCENE_FORMAT"]

SCENE_FORMAT = __doc__.split("Format (every table is optional except ``[robot]``)::")[1].split("Errors name")[0]

_ELEMENT_TABLES = ("spring", "damper", "rayleigh", "follower", "dead", "spring_damper", "bushing")
_TOP = {"robot", "scene", "prescribed", "start", "constraint", "sweep", "campbell", *_ELEMENT_TABLES}
_KEYS = {
    "robot": {"urdf", "example", "free_flyer", "locked", "trust_xacro"},
    "scene": {"gravity", "urdf_damping"},
    "start": {"q", "joints", "reference", "equilibrium", "balancing"},
    "spring": {"joint", "stiffness", "rest"},
    "damper": {"joint", "damping"},
    "rayleigh": {"alpha", "beta"},
    "follower": {"frame", "force", "torque"},
    "dead": {"frame", "force", "torque"},
    "spring_damper": {"frame", "target", "stiffness", "damping", "rest_length"},
    "bushing": {"frame", "target", "stiffness", "damping", "offset"},
    "constraint": {"type", "frame", "target", "name", "contact", "friction", "normal"},
}


@dataclass(frozen=True)
class SceneSpec:
    """A scene read from a file, with where to start and how to treat the start.

    Attributes
    ----------
    scene : Scene
    q0 : (nq,) ndarray
        Starting configuration.
    equilibrium : bool
        Run :func:`~pinlin.find_equilibrium` from q0 before linearizing.
    balancing : bool
        Linearize at q0 held by constant actuator forces.
    path : str
        The file.
    sweep : dict or None
        The ``[sweep]`` table as read, for ``pinlin sweep`` (checked by
        :func:`pinlin.report.sweep.sweep_plan`).
    campbell : dict or None
        The ``[campbell]`` table, for ``pinlin campbell`` (:func:`pinlin.report.campbell.campbell_plan`).

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/double_pendulum.toml"))
    >>> spec.q0, spec.equilibrium, spec.balancing
    (array([0., 0.]), True, False)
    """

    scene: Scene
    q0: np.ndarray
    equilibrium: bool
    balancing: bool
    path: str
    sweep: dict | None = None
    campbell: dict | None = None


def default_scene_path() -> Path:
    """The bundled default scene: the paper's double pendulum with follower load (theory: double pendulum)."""
    return data_path("scenes/double_pendulum.toml")


def _robot(r: Reader, table: dict, base: Path, trust_xacro: bool) -> Robot:
    r.check_keys(table, _KEYS["robot"], "robot")
    trust_xacro = trust_xacro or bool(r.get(table, "trust_xacro", "robot", bool))
    urdf = r.get(table, "urdf", "robot", str)
    example = r.get(table, "example", "robot", str)
    if (urdf is None) == (example is None):
        r.fail("robot", "give exactly one of 'urdf' (a file) or 'example' (an example-robot-data name)")
    if urdf is not None and not urdf.strip():
        r.fail("robot.urdf", "is empty; expected a URDF file (relative to the scene file) or a bundled URDF's name")
    free_flyer = r.get(table, "free_flyer", "robot", bool)
    locked = table.get("locked")
    if locked is not None and not (
        (isinstance(locked, list) and all(isinstance(x, str) for x in locked)) or isinstance(locked, dict)
    ):
        r.fail("robot.locked", f"expected a list of joint names or a table joint = value, got {locked!r}")
    try:
        if example is not None:
            return load_example(example, free_flyer=free_flyer, locked=locked)
        path = (base / urdf) if not Path(urdf).is_absolute() else Path(urdf)
        if not path.is_file():
            try:
                path = data_path(f"urdf/{urdf}")
            except PinlinError:
                r.fail("robot.urdf", f"URDF file not found: {base / urdf} (nor a bundled URDF of that name)")
        return load_urdf(path, free_flyer=bool(free_flyer), locked=locked, trust_xacro=trust_xacro)
    except SceneFileError:
        raise
    except PinlinError as exc:
        r.fail("robot", str(exc), exc)


def _elements(r: Reader, doc: dict, robot: Robot) -> list:
    elements = []
    makers = {
        "spring": lambda t, w: JointSpring(
            r.get(t, "joint", w, str, required=True),
            r.get(t, "stiffness", w, "numbers", required=True),
            r.get(t, "rest", w, "numbers"),
        ),
        "damper": lambda t, w: JointDamper(
            r.get(t, "joint", w, str, required=True), r.get(t, "damping", w, "numbers", required=True)
        ),
        "follower": lambda t, w: FollowerWrench(
            r.get(t, "frame", w, str, required=True),
            r.get(t, "force", w, "numbers", np.zeros(3)),
            r.get(t, "torque", w, "numbers", np.zeros(3)),
        ),
        "dead": lambda t, w: DeadWrench(
            r.get(t, "frame", w, str, required=True),
            r.get(t, "force", w, "numbers", np.zeros(3)),
            r.get(t, "torque", w, "numbers", np.zeros(3)),
        ),
        "spring_damper": lambda t, w: LinearSpringDamper(
            r.get(t, "frame", w, str, required=True),
            read_target(r, t, w, placement=False),
            stiffness=r.get(t, "stiffness", w, float, required=True),
            damping=r.get(t, "damping", w, float, 0.0),
            rest_length=r.get(t, "rest_length", w, float, 0.0),
        ),
        "bushing": lambda t, w: Bushing(
            r.get(t, "frame", w, str, required=True),
            read_target(r, t, w, placement=True),
            stiffness=r.get(t, "stiffness", w, "numbers", required=True),
            damping=r.get(t, "damping", w, "numbers"),
            offset=None if "offset" not in t else read_placement(r, t["offset"], f"{w}.offset"),
        ),
    }
    for kind, make in makers.items():
        tables = doc.get(kind, [])
        if not isinstance(tables, list):
            r.fail(kind, f"use [[{kind}]] (an array of tables), one per {kind}")
        for i, table in enumerate(tables, start=1):
            where = f"{kind}[{i}]"
            r.check_keys(table, _KEYS[kind], where)
            try:
                element = make(table, where)
                element.check(robot)
            except SceneFileError:
                raise
            except PinlinError as exc:
                r.fail(where, str(exc), exc)
            elements.append(element)
    if "rayleigh" in doc:
        t = doc["rayleigh"]
        r.check_keys(t, _KEYS["rayleigh"], "rayleigh")
        try:
            elements.append(
                RayleighDamping(r.get(t, "alpha", "rayleigh", float, 0.0), r.get(t, "beta", "rayleigh", float, 0.0))
            )
        except SceneFileError:
            raise
        except PinlinError as exc:
            r.fail("rayleigh", str(exc), exc)
    return elements


def _start(r: Reader, table: dict, scene: Scene) -> tuple[np.ndarray, bool, bool]:
    r.check_keys(table, _KEYS["start"], "start")
    robot = scene.robot
    q = robot.neutral()
    given = [k for k in ("q", "joints", "reference") if k in table]
    if len(given) > 1:
        r.fail("start", f"give at most one of q, joints, reference; got {given}")
    if "q" in table:
        q = r.get(table, "q", "start", "numbers")
        if q.shape != (robot.nq,):
            r.fail("start.q", f"expected {robot.nq} numbers (the full configuration, nq), got shape {q.shape}")
    elif "joints" in table:
        joints = table["joints"]
        if not isinstance(joints, dict):
            r.fail("start.joints", "expected a table joint = value")
        for name in joints:
            try:
                j = robot.joint(name)
            except PinlinError as exc:
                r.fail(f"start.joints.{name}", str(exc), exc)
            arr = np.atleast_1d(r.get(joints, name, "start.joints", "numbers"))
            if j.nq == 2 and j.nv == 1 and arr.size == 1:
                arr = np.array([np.cos(arr[0]), np.sin(arr[0])])
            if arr.shape != (j.nq,):
                r.fail(f"start.joints.{name}", f"joint {name!r} needs {j.nq} value(s), got {arr.size}")
            q[j.q_slice] = arr
    elif "reference" in table:
        name = r.get(table, "reference", "start", str)
        if name not in robot.reference_configurations:
            r.fail(
                "start.reference",
                f"unknown reference configuration {name!r}; available: {sorted(robot.reference_configurations)}",
            )
        q = robot.reference_configurations[name].copy()
    try:
        q = scene.check_configuration(q, "start.q")
    except PinlinError as exc:
        r.fail("start", str(exc), exc)
    equilibrium = r.get(table, "equilibrium", "start", bool, True)
    balancing = r.get(table, "balancing", "start", bool, False)
    if equilibrium and balancing:
        r.fail("start", "equilibrium = true and balancing = true exclude each other")
    return q, equilibrium, balancing




def load_scene(path, *, trust_xacro: bool = False) -> SceneSpec:
    """Read a scene file (format in :data:`SCENE_FORMAT`).

    Parameters
    ----------
    path : path-like
        The TOML file.
    trust_xacro : bool
        Expand a ``.xacro`` robot file (as its own ``[robot] trust_xacro = true`` does): a
        xacro is a program, so only one you trust (:func:`pinlin.load_urdf`); default refused.

    Raises
    ------
    SceneFileError
        Missing or unreadable file, invalid TOML, unknown or wrongly typed key,
        or anything the robot, elements or start refuse; the message names the key.
    ParameterError
        ``trust_xacro`` is not a boolean.

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/double_pendulum.toml"))
    >>> spec.scene
    Scene('double_pendulum', n=2, 2 spring, 1 follower, gravity=[0.0, 0.0, -9.81])
    """
    path = Path(path)
    r = Reader(str(path))
    if not path.is_file():
        r.fail(None, "scene file not found")
    try:
        doc = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        r.fail(None, f"cannot read: {exc}", exc)
    except tomllib.TOMLDecodeError as exc:
        r.fail(None, f"invalid TOML: {exc}", exc)
    except RecursionError as exc:  # tomllib parses nested arrays and tables recursively
        r.fail(None, "invalid TOML: arrays or tables nested too deeply to read", exc)
    r.check_keys(doc, _TOP, None)
    if "robot" not in doc:
        r.fail("robot", "missing the [robot] table")
    if not isinstance(trust_xacro, bool):
        raise ParameterError("trust_xacro", f"expected True or False, got {trust_xacro!r}")
    robot = _robot(r, doc["robot"], path.parent, trust_xacro)
    elements = _elements(r, doc, robot)
    constraints = read_constraints(r, doc, robot, _KEYS["constraint"])
    scene_table = doc.get("scene", {})
    r.check_keys(scene_table, _KEYS["scene"], "scene")
    gravity = r.get(scene_table, "gravity", "scene", "numbers", np.array([0.0, 0.0, -9.81]))
    urdf_damping = r.get(scene_table, "urdf_damping", "scene", bool, False)
    prescribed = doc.get("prescribed", {})
    if not isinstance(prescribed, dict):
        r.fail("prescribed", "expected a table joint = velocity")
    for name in prescribed:
        try:  # a table is a harmonic motion (theory: Floquet), a number a constant velocity
            if isinstance(prescribed[name], dict):
                prescribed[name] = harmonic_from_table(prescribed[name])
            else:
                r.get(prescribed, name, "prescribed", float)
            robot.joint(name)
        except SceneFileError:
            raise
        except PinlinError as exc:
            r.fail(f"prescribed.{name}", str(exc), exc)
    try:
        scene = Scene(
            robot, elements, gravity=gravity, prescribed=prescribed, urdf_damping=urdf_damping, constraints=constraints
        )
    except PinlinError as exc:
        key = "prescribed" if prescribed and "prescribed" in str(exc) else "scene"
        r.fail(key, str(exc), exc)
    q0, equilibrium, balancing = _start(r, doc.get("start", {}), scene)
    return SceneSpec(scene, q0, equilibrium, balancing, str(path), doc.get("sweep"), doc.get("campbell"))
