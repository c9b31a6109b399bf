"""Loading a rigid multibody from a URDF (or example-robot-data) into a :class:`Robot`.

Only Pinocchio's kinematic model is built: no geometry model, no meshes, no
collision data (the linearized equations need inertia and kinematics only).
Joints can be locked away at load time through Pinocchio's reduced model, and
the memory Pinocchio would allocate is estimated before any ``createData``.
Pinocchio's PyPI wheels have no SDF parser: convert SDF to URDF or MJCF.  MJCF
models, with their closed loops (``<connect>``, ``<weld>``), load through
:func:`pinlin.load_mjcf` (:mod:`.mjcf`).
"""

from __future__ import annotations

import contextlib
import os
import warnings
from collections.abc import Collection, Iterator, Mapping, Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import JointNotFoundError, ParameterError, UrdfError
from .examples import discover_examples, example_file, find_example
from .inertia import check_bodies, check_inertia_option
from .memory import check_memory, check_memory_limit
from .parser_output import captured_stderr
from .robot import Robot
from .urdf_text import check_urdf_xml
from .xacro import expand_xacro, is_xacro


def _discovered():
    try:
        return discover_examples()
    except ParameterError:  # example-robot-data missing: load_example says so
        return {}


__all__ = [
    "load_urdf",
    "load_urdf_string",
    "load_example",
    "EXAMPLES",
    "example_urdf_path",
    "data_path",
    "captured_stderr",
    "reduce_model",
]

#: Short names of example-robot-data models: (URDF path under ``robots/``, SRDF path or None,
#: floating base by default), discovered from the installed files (:mod:`.examples`).
EXAMPLES: dict[str, tuple[str, str | None, bool]] = {
    name: (entry.urdf, entry.srdf, entry.free_flyer) for name, entry in _discovered().items()
}


def data_path(name: str) -> Path:
    """Path of a file bundled with pinlin (reference URDFs and scenes).

    Parameters
    ----------
    name : str
        Relative name, for example ``"urdf/double_pendulum.urdf"`` or
        ``"scenes/double_pendulum.toml"``.

    Examples
    --------
    >>> pinlin.data_path("urdf/double_pendulum.urdf").name
    'double_pendulum.urdf'
    """
    root = Path(__file__).parent.parent / "data"
    path = root / name
    if not path.is_file():
        bundled = sorted(str(p.relative_to(root)) for p in root.rglob("*") if p.is_file())
        raise ParameterError("name", f"no bundled file {name!r}; bundled files: {bundled}")
    return path


# ----------------------------------------------------------------------------- memory guard


def _joint_value(model: pin.Model, jid: int, value: object, name: str) -> np.ndarray:
    jm = model.joints[jid]
    arr = np.atleast_1d(np.asarray(value, dtype=float))
    if jm.nq == 2 and jm.nv == 1 and arr.size == 1:  # continuous joint given as an angle
        arr = np.array([np.cos(arr[0]), np.sin(arr[0])])
    if arr.shape != (jm.nq,) or not np.all(np.isfinite(arr)):
        raise ParameterError(
            f"locked[{name!r}]",
            f"expected {jm.nq} finite value(s) for joint {name!r} ({jm.shortname()}), got {value!r}",
        )
    return arr


def reduce_model(model: pin.Model, locked, source: str) -> pin.Model:
    if not locked:
        return model
    if isinstance(locked, str):
        locked = [locked]
    q_ref = pin.neutral(model)
    ids = []
    items = locked.items() if isinstance(locked, Mapping) else ((name, None) for name in locked)
    for name, value in items:
        if not isinstance(name, str) or not model.existJointName(name) or name == "universe":
            valid = [model.names[i] for i in range(1, model.njoints)]
            raise JointNotFoundError(str(name), valid, context=f"locked joints of {source}")
        jid = model.getJointId(name)
        if value is not None:
            jm = model.joints[jid]
            q_ref[jm.idx_q : jm.idx_q + jm.nq] = _joint_value(model, jid, value, name)
        ids.append(jid)
    reduced = pin.buildReducedModel(model, ids, q_ref)
    if reduced.nv == 0:
        raise UrdfError(f"{source}: locking {sorted(locked)} leaves no movable joint", source)
    return reduced


# ----------------------------------------------------------------------------- loading


def _report_parser_messages(messages: list[str], source: str) -> None:
    """What urdfdom printed while building a model that it did build: errors raise, the rest warn.

    urdfdom prints "Error: ..." for elements it could not parse and then goes on
    without them, so the model would silently differ from the file.
    """
    text = "\n".join(m for m in messages if m).strip()
    if not text:
        return
    if "Error" in text:
        raise UrdfError(f"{source}: the URDF parser could not read part of the model: {' '.join(text.split())}", source)
    warnings.warn(f"{source}: the URDF parser says: {' '.join(text.split())}", UserWarning, stacklevel=4)


def _build(text: str | None, path: str | None, source: str, free_flyer: bool) -> pin.Model:
    root_joint = pin.JointModelFreeFlyer() if free_flyer else None
    with captured_stderr() as messages:
        try:
            build, source_arg = (pin.buildModelFromUrdf, path) if path is not None else (pin.buildModelFromXML, text)
            model = build(source_arg, root_joint) if root_joint is not None else build(source_arg)
            error = None
        except (ValueError, RuntimeError) as exc:
            error = exc
    if error is not None:
        detail = " ".join(m for m in messages if m) or str(error)
        raise UrdfError(f"{source}: not a valid URDF model ({detail})", source) from None
    _report_parser_messages(messages, source)
    return model


def _finish(
    model: pin.Model,
    source: str,
    locked,
    memory_limit: int | None,
    references: Mapping[str, np.ndarray] | None = None,
) -> Robot:
    if model.nv == 0:
        raise UrdfError(f"{source}: the URDF has no movable joint (all joints are fixed); nothing moves", source)
    model = reduce_model(model, locked, source)
    check_memory(model.nv, memory_limit, source)
    return Robot(model, source, references if not locked else None)


def _load_text(text: str, path: str | None, source: str, free_flyer: bool, memory_limit, inertia: str) -> pin.Model:
    """The checks before parsing, Pinocchio's parser, the checks of the bodies after it."""
    inertia = check_inertia_option(inertia)
    memory_limit = check_memory_limit(memory_limit)
    link_faults = check_urdf_xml(text, source, free_flyer=free_flyer, memory_limit=memory_limit)
    model = _build(text if path is None else None, path, source, free_flyer)
    check_bodies(model, link_faults, source, inertia)
    return model


def load_urdf(
    path: str | os.PathLike,
    *,
    free_flyer: bool = False,
    locked: Sequence[str] | Mapping[str, object] | None = None,
    memory_limit: int | None = None,
    inertia: str = "check",
    xacro_args: Mapping[str, object] | None = None,
    package_dirs: Sequence[str | os.PathLike] | None = None,
    trust_xacro: bool = False,
    xacro_allow: Collection[str] = (),
) -> Robot:
    """Load a URDF (or xacro) file as a :class:`Robot` (kinematics and inertia only).

    Parameters
    ----------
    path : path-like
        The URDF file, or a ``.xacro`` file (expanded with :func:`pinlin.model.xacro.expand_xacro`
        if ``trust_xacro``). Meshes it names are never opened.
    free_flyer : bool
        Mount the root link on a free-flyer joint (floating base, nq = nv + 1).
    locked : sequence of str or mapping, optional
        Joints to remove through Pinocchio's reduced model (a mapping gives their positions).
    memory_limit : int, optional
        Bytes allowed for the peak of Pinocchio's data; default 80 % of the available memory.
    inertia : {"check", "repair"}
        A body (links merged by fixed joints) whose inertia is not physically possible is
        refused (default) or replaced by the nearest valid tensor with an
        :class:`~pinlin.InertiaWarning` (:mod:`pinlin.model.inertia`).
    xacro_args : mapping, optional
        Arguments of a ``.xacro`` file (``$(arg name)``).
    package_dirs : sequence of path-like, optional
        Directories searched first for ``package://`` and ``$(find pkg)`` in a
        ``.xacro`` file, before ``ROS_PACKAGE_PATH`` and ``AMENT_PREFIX_PATH``
        (:func:`pinlin.model.xacro.package_search_path`).
    trust_xacro : bool
        Expand a ``.xacro`` file: a xacro is a program, so only one you trust (default: refused).
        It runs in a child process with time and memory limits (:mod:`pinlin.model.xacro`).
    xacro_allow : collection of str
        What a trusted xacro may also do (``"env"``, ``"optenv"``, ``"load_yaml"``,
        ``"python"``, ``"include"``: :data:`pinlin.model.xacro.XACRO_PERMISSIONS`); default nothing.

    Raises
    ------
    UrdfError
        Missing file, malformed XML, invalid URDF, no movable joint, non-finite or (with
        ``inertia="check"``) impossible inertia, anything the URDF parser or xacro could not read;
        a ``.xacro`` file without ``trust_xacro=True``, or doing what ``xacro_allow`` does not list.
    JointNotFoundError
        A locked joint does not exist.
    ModelTooLargeError
        Too deep for the parser, or Pinocchio's data would not fit in memory (said before parsing).
    ParameterError
        A bad ``inertia``, ``memory_limit``, ``xacro_args``, ``package_dirs`` or ``xacro_allow``.
    MissingDependencyError
        A ``.xacro`` file without the ``xacro`` package (``pip install 'pinlin[xacro]'``).

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> robot
    Robot('double_pendulum', nq=2, nv=2, joints=2, source='.../double_pendulum.urdf')
    >>> robot.dof_names
    ('joint1', 'joint2')
    """
    source = os.fspath(path)
    p = Path(source)
    if not p.is_file():
        raise UrdfError(f"URDF file not found: {source}", source)
    if is_xacro(source):
        text = expand_xacro(p, xacro_args, package_dirs, trust=trust_xacro, allow=xacro_allow)
        model = _load_text(text, None, source, free_flyer, memory_limit, inertia)
        return _finish(model, source, locked, memory_limit)
    if xacro_args is not None:
        raise ParameterError("xacro_args", f"{source} is not a .xacro file; xacro_args apply to .xacro files only")
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise UrdfError(f"cannot read URDF file {source}: {exc}", source) from None
    model = _load_text(text, str(p), source, free_flyer, memory_limit, inertia)
    return _finish(model, source, locked, memory_limit)


def load_urdf_string(
    text: str,
    *,
    free_flyer: bool = False,
    locked: Sequence[str] | Mapping[str, object] | None = None,
    memory_limit: int | None = None,
    inertia: str = "check",
) -> Robot:
    """Load URDF text as a :class:`Robot`; same options as :func:`load_urdf`.

    Examples
    --------
    >>> robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf(m1=1.0, l1=0.5))
    >>> robot.nv, robot.joint_names
    (2, ('joint1', 'joint2'))
    """
    source = "<string>"
    if not isinstance(text, str):
        raise UrdfError(f"URDF text must be a str, got {type(text).__name__}", source)
    model = _load_text(text, None, source, free_flyer, memory_limit, inertia)
    return _finish(model, source, locked, memory_limit)


def example_urdf_path(name: str) -> Path:
    """Path of an example-robot-data URDF by short name (see :func:`pinlin.examples`).

    Raises
    ------
    ExampleNotFoundError
        Unknown name (a :class:`~pinlin.ParameterError`); the message lists close matches.
    """
    return _erd_file(find_example(name).urdf)


def _erd_file(relative: str) -> Path:
    return example_file(relative)


def load_example(
    name: str,
    *,
    free_flyer: bool | None = None,
    locked: Sequence[str] | Mapping[str, object] | None = None,
    memory_limit: int | None = None,
    inertia: str = "check",
) -> Robot:
    """Load an example-robot-data model by short name, without meshes.

    Parameters
    ----------
    name : str
        One of :func:`pinlin.examples` (every robot of the installed
        example-robot-data): ``double_pendulum``, ``ur5``, ``panda``, ``go1``,
        ``anymal``, ``talos``, ``tiago``, ...
    free_flyer : bool, optional
        Default: on for legged robots, humanoids and flying robots
        (:func:`pinlin.model.examples.floating_by_default`), else off.
    locked, memory_limit, inertia
        As in :func:`load_urdf`.

    Returns
    -------
    Robot
        With the SRDF's named configurations (``half_sitting``, ``standing``, ...) in
        ``reference_configurations`` when the SRDF exists.

    Raises
    ------
    ExampleNotFoundError
        Unknown name; the message lists close matches (a :class:`~pinlin.ParameterError`).
    UrdfError, ModelTooLargeError, JointNotFoundError
        As in :func:`load_urdf`.

    Examples
    --------
    >>> robot = pinlin.load_example("ur5")
    >>> robot
    Robot('ur5', nq=6, nv=6, joints=6, source='example:ur5')
    """
    entry = find_example(name)
    path = _erd_file(entry.urdf)
    ff = entry.free_flyer if free_flyer is None else bool(free_flyer)
    source = f"example:{name}"
    if not path.is_file():
        raise UrdfError(f"example-robot-data file missing: {path}", source)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise UrdfError(f"cannot read URDF file {path}: {exc}", source) from None
    model = _load_text(text, str(path), source, ff, memory_limit, inertia)
    refs = _reference_configurations(model, entry.srdf, source)
    return _finish(model, source, locked, memory_limit, refs)


def _reference_configurations(model: pin.Model, srdf_rel: str | None, source: str) -> dict[str, np.ndarray]:
    """The SRDF's named configurations; a missing or unreadable SRDF is said with a warning, never dropped."""
    if srdf_rel is None:
        return {}
    srdf = _erd_file(srdf_rel)
    if not srdf.is_file():
        warnings.warn(
            f"{source}: the SRDF {srdf} is missing; the robot has no named reference configurations",
            UserWarning,
            stacklevel=3,
        )
        return {}
    with captured_stderr() as messages:
        try:
            pin.loadReferenceConfigurations(model, str(srdf), False)
            error = None
        except (ValueError, RuntimeError) as exc:
            error = exc
    if error is not None:
        detail = " ".join(m for m in messages if m) or str(error)
        warnings.warn(
            f"{source}: could not read the reference configurations of {srdf} ({detail}); "
            f"the robot has none",
            UserWarning,
            stacklevel=3,
        )
        return {}
    return {e.key(): np.array(e.data(), dtype=float) for e in model.referenceConfigurations}
