"""The scenes the command line analyses without a scene file: ``--example NAME`` (an example robot with
elastic joints) and the bundled scenes of ``pinlin sweep`` and ``pinlin campbell``."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import ParameterError, SceneFileError
from ..model.elements import JointDamper, JointSpring
from ..model.loading import data_path, load_example
from ..model.scene import Scene
from ..model.scene_file import SceneSpec, load_scene

__all__ = ["example_spec", "default_sweep_scene_path", "default_campbell_scene_path", "bundled_scenes", "scene_path",
           "load_scene_argument", "BUNDLED_SCENES"]

#: The folder of the bundled scenes, relative to :func:`pinlin.data_path`; a SCENE argument that is not a file
#: but the name of one of them (``turntable.toml`` or ``turntable``) reads the bundled scene, from any folder.
BUNDLED_SCENES = "scenes"


def default_sweep_scene_path():
    """The bundled scene of ``pinlin sweep`` without a file: the double pendulum over its follower load.

    Examples
    --------
    >>> pinlin.report.scenes.default_sweep_scene_path().name
    'double_pendulum_flutter.toml'
    """
    return data_path("scenes/double_pendulum_flutter.toml")


def default_campbell_scene_path():
    """The bundled scene of ``pinlin campbell`` without a file: the particle in a rotating ring.

    Its critical speed is sqrt(k/m) (theory: rotating ring).

    Examples
    --------
    >>> pinlin.report.scenes.default_campbell_scene_path().name
    'rotating_ring.toml'
    """
    return data_path("scenes/rotating_ring.toml")


def example_spec(name: str, stiffness: float, damping: float = 0.0) -> SceneSpec:
    """An example-robot-data robot with elastic joints, springs unstressed at its reference pose.

    A robot with a free-flyer joint is linearized with balancing forces (it
    has no equilibrium of its own); a fixed-base one at its equilibrium near
    the reference pose.

    Parameters
    ----------
    name : str
        One of :data:`pinlin.EXAMPLES`.
    stiffness : float
        Stiffness of every joint spring [N m/rad or N/m], > 0.
    damping : float
        Damping of every joint [N m s/rad or N s/m], >= 0 (0: no dampers).

    Raises
    ------
    ParameterError
        A stiffness that is not positive, a damping that is negative (named by
        their command-line options).
    InputError
        An unknown example name (see :func:`pinlin.load_example`).

    Examples
    --------
    >>> spec = pinlin.report.scenes.example_spec("ur5", stiffness=1000.0)  # needs example-robot-data
    >>> spec.scene.n, spec.equilibrium, spec.balancing
    (6, True, False)
    >>> pinlin.report.scenes.example_spec("ur5", stiffness=-1.0)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: --stiffness: must be a positive number, got -1.0
    """
    if not (np.isfinite(stiffness) and stiffness > 0):
        raise ParameterError("--stiffness", f"must be a positive number, got {stiffness}")
    if not (np.isfinite(damping) and damping >= 0):
        raise ParameterError("--damping", f"must be a non-negative number, got {damping}")
    robot = load_example(name)
    refs = robot.reference_configurations
    q0 = next(iter(refs.values())).copy() if refs else robot.neutral()
    elements = []
    for jname in robot.joint_names:
        j = robot.joint(jname)
        if j.kind == "JointModelFreeFlyer":
            continue
        rest = q0[j.q_slice]
        elements.append(JointSpring(jname, stiffness, rest=rest if j.nq > 1 else float(rest[0])))
        if damping:
            elements.append(JointDamper(jname, damping))
    scene = Scene(robot, elements)
    floating = any(robot.joint(n).kind == "JointModelFreeFlyer" for n in robot.joint_names)
    return SceneSpec(scene, scene.check_configuration(q0), not floating, floating, f"example:{name}")


def bundled_scenes() -> tuple[str, ...]:
    """The names of the bundled scene files that a command's SCENE argument accepts from any folder.

    Examples
    --------
    >>> "turntable.toml" in pinlin.report.scenes.bundled_scenes()
    True
    """
    root = data_path(f"{BUNDLED_SCENES}/double_pendulum.toml").parent
    return tuple(sorted(p.name for p in root.glob("*.toml")))


def scene_path(text: str | Path) -> Path:
    """The file a SCENE argument names: the path itself where it is a file, else the bundled scene of that name.

    A bare name (no folder) of a bundled scene, with or without ``.toml``, is read from the package wherever
    the command runs; anything else is returned as given, for :func:`~pinlin.model.load_scene` to read or to
    refuse (naming the file).

    Examples
    --------
    >>> pinlin.report.scenes.scene_path("turntable.toml") == pinlin.data_path("scenes/turntable.toml")
    True
    >>> pinlin.report.scenes.scene_path("kapitza").name
    'kapitza.toml'
    """
    path = Path(text)
    if path.is_file() or path.parent != Path("."):
        return path
    name = path.name if path.suffix == ".toml" else f"{path.name}.toml"
    return data_path(f"{BUNDLED_SCENES}/{name}") if name in bundled_scenes() else path


def load_scene_argument(text: str | None, default: Path, *, trust_xacro: bool = False) -> SceneSpec:
    """The scene of a command's SCENE argument (:func:`scene_path`), or its bundled ``default`` without one.

    ``trust_xacro``: the caller trusts a xacro the scene names (see :func:`~pinlin.model.load_scene`).

    Raises
    ------
    SceneFileError
        No such file and no bundled scene of that name (the message lists the bundled scenes), or
        anything :func:`~pinlin.model.load_scene` refuses.

    Examples
    --------
    >>> from pinlin.report.scenes import load_scene_argument
    >>> default = pinlin.data_path("scenes/double_pendulum.toml")
    >>> load_scene_argument("kapitza", default).scene.motions["pivot"]
    Harmonic(...)
    >>> load_scene_argument(None, default).path == str(default)
    True
    """
    if text is None:
        return load_scene(default, trust_xacro=trust_xacro)
    path = scene_path(text)
    if not path.is_file():
        raise SceneFileError(f"scene file not found (bundled scenes, read by name from any folder: "
                             f"{', '.join(bundled_scenes())})", str(path))
    return load_scene(path, trust_xacro=trust_xacro)
