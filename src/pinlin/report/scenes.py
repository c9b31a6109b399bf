"""The scenes the command line analyses without a scene file: ``--example NAME`` (an example robot with
elastic joints) and the bundled scenes of ``pinlin sweep`` and ``pinlin campbell``."""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..model.elements import JointDamper, JointSpring
from ..model.loading import data_path, load_example
from ..model.scene import Scene
from ..model.scene_file import SceneSpec

__all__ = ["example_spec", "default_sweep_scene_path", "default_campbell_scene_path"]


def default_sweep_scene_path():
    """The bundled scene of ``pinlin sweep`` without a file: the double pendulum over its follower 

    Examples
    --------
    >>> pinlin.report.scenes.default_sweep_scene_path().name
    'double_pendulum_flutter.toml'
    """
    return data_path("scenes/double_pendulum_flutter.toml")


def default_campbell_scene_path():
    """The bundled scene of ``pinlin campbell`` without a file: the particle in a rotating ring (theory: rotating r

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
