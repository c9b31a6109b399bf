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
import importlib.metadata
import os
import tempfile
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import JointNotFoundError, ParameterError, UrdfError
from .inertia import check_inertials
from .memory import check_memory
from .robot import Robot

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

#: Short names of example-robot-data models: (URDF path under ``robots/``,
#: SRDF path or None, floating base by default).
EXAMPLES: dict[str, tuple[str, str | None, bool]] = {
    "double_pendulum": ("double_pendulum_description/urdf/double_pendulum.urdf", None, False),
    "double_pendulum_continuous": (
        "double_pendulum_description/urdf/double_pendulum_continuous.urdf",
        None,
        False,
    ),
    "ur3": ("ur_description/urdf/ur3_robot.urdf", None, False),
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "ur_description/srdf/ur5.srdf", False),
    "ur10": ("ur_description/urdf/ur10_robot.urdf", None, False),
    "panda": ("panda_description/urdf/panda.urdf", "panda_description/srdf/panda.srdf", False),
    "talos_reduced": (
        "talos_data/robots/talos_reduced.urdf",
        "talos_data/srdf/talos.srdf",
        True,
    ),
    "solo12": ("solo_description/robots/solo12.urdf", "solo_description/srdf/solo.srdf", True),
}

_ERD_ROOT = "cmeel.prefix/share/example-robot-data/robots/"


def data_path(name: str) -> Path:
    """Path of a file bundled with pinlin (reference URDFs and scenes).

    Parameters
    ----------
    name : str
        Relative name, for example ``"urdf/double_pendulum.urdf"`` or
        ``"scenes/double_pendulum.toml"``.
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


@contextlib.contextmanager
def captured_stderr() -> Iterator[list[str]]:
    """Capture what the C++ URDF parser prints on file descriptor 2."""
    out: list[str] = []
    try:
        fd = os.dup(2)
    except OSError:  # no usable stderr: nothing to capture
        yield out
        return
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        os.dup2(tmp.fileno(), 2)
        try:
            yield out
        finally:
            os.dup2(fd, 2)
            os.close(fd)
            tmp.seek(0)
            out.append(tmp.read().decode(errors="replace").strip())


def _check_xml(text: str, source: str) -> None:
    """Well-formed XML with a <robot> root, a <link>, and physically valid inertial data."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise UrdfError(f"{source}: malformed XML ({exc})", source) from None
    if root.tag != "robot":
        raise UrdfError(f"{source}: root element is <{root.tag}>, expected <robot>", source)
    if root.find("link") is None:
        raise UrdfError(f"{source}: the URDF has no <link>", source)
    _check_tree(root, source)
    check_inertials(root, source)


def _check_tree(root: ET.Element, source: str) -> None:
    """Unique link and joint names, and at most one parent joint per link: a tree.

    urdfdom accepts a link that is the child of two joints (a loop written as a
    tree); Pinocchio then builds a model with repeated joint names, which a
    name lookup cannot tell apart.  Closed loops are constraints
    (:class:`~pinlin.PointConstraint`, :func:`~pinlin.load_mjcf`).
    """
    for tag in ("link", "joint"):
        seen: set[str] = set()
        for element in root.findall(tag):  # direct children: <transmission> names joints too
            name = element.get("name")
            if name in seen:
                raise UrdfError(f"{source}: two <{tag}> elements are named {name!r}", source)
            seen.add(name)
    parents: dict[str, str] = {}
    for joint in root.findall("joint"):
        child = joint.find("child")
        link = None if child is None else child.get("link")
        if link in parents:
            raise UrdfError(
                f"{source}: link {link!r} is the child of two joints ({parents[link]!r} and "
                f"{joint.get('name')!r}); a URDF is a tree: close loops with constraints "
                f"(pinlin.PointConstraint, or an MJCF <equality>)",
                source,
            )
        if link is not None:
            parents[link] = joint.get("name")


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
            if path is not None:
                model = (
                    pin.buildModelFromUrdf(path, root_joint)
                    if root_joint is not None
                    else pin.buildModelFromUrdf(path)
                )
            else:
                model = (
                    pin.buildModelFromXML(text, root_joint)
                    if root_joint is not None
                    else pin.buildModelFromXML(text)
                )
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
        raise UrdfError(
            f"{source}: the URDF has no movable joint (all joints are fixed); nothing moves",
            source,
        )
    model = reduce_model(model, locked, source)
    check_memory(model.nv, memory_limit, source)
    return Robot(model, source, references if not locked else None)


def load_urdf(
    path: str | os.PathLike,
    *,
    free_flyer: bool = False,
    locked: Sequence[str] | Mapping[str, object] | None = None,
    memory_limit: int | None = None,
) -> Robot:
    """Load a URDF file as a :class:`Robot` (kinematics and inertia only).

    Parameters
    ----------
    path : path-like
        The URDF file.  Meshes it names are never opened.
    free_flyer : bool
        Mount the root link on a free-flyer joint (floating base, nq = nv + 1).
    locked : sequence of str or mapping, optional
        Joints to remove through Pinocchio's reduced model, see :meth:`Robot.lock`.
    memory_limit : int, optional
        Bytes allowed for the peak of Pinocchio's data; default 80 % of the
        available memory.

    Raises
    ------
    UrdfError
        Missing file, malformed XML, invalid URDF, no movable joint, a link whose
        inertial data is not finite or not physically possible (see
        :mod:`pinlin.model.inertia`), anything the URDF parser could not read.
    JointNotFoundError
        A locked joint does not exist.
    ModelTooLargeError
        Pinocchio's data would not fit in memory.
    """
    source = os.fspath(path)
    p = Path(source)
    if not p.is_file():
        raise UrdfError(f"URDF file not found: {source}", source)
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise UrdfError(f"cannot read URDF file {source}: {exc}", source) from None
    _check_xml(text, source)
    model = _build(None, str(p), source, free_flyer)
    return _finish(model, source, locked, memory_limit)


def load_urdf_string(
    text: str,
    *,
    free_flyer: bool = False,
    locked: Sequence[str] | Mapping[str, object] | None = None,
    memory_limit: int | None = None,
) -> Robot:
    """Load URDF text as a :class:`Robot`; same options as :func:`load_urdf`."""
    source = "<string>"
    if not isinstance(text, str):
        raise UrdfError(f"URDF text must be a str, got {type(text).__name__}", source)
    _check_xml(text, source)
    model = _build(text, None, source, free_flyer)
    return _finish(model, source, locked, memory_limit)


def example_urdf_path(name: str) -> Path:
    """Path of an example-robot-data URDF by short name (see :data:`EXAMPLES`).

    example-robot-data ships its URDFs as data files of the wheel, located through
    the package metadata (SPEC section 1).
    """
    if name not in EXAMPLES:
        raise ParameterError("name", f"unknown example {name!r}; known examples: {sorted(EXAMPLES)}")
    return _erd_file(EXAMPLES[name][0])


def _erd_file(relative: str) -> Path:
    try:
        dist = importlib.metadata.distribution("example-robot-data")
    except importlib.metadata.PackageNotFoundError:
        raise ParameterError(
            "name", "example-robot-data is not installed (pip install example-robot-data)"
        ) from None
    return Path(str(dist.locate_file(_ERD_ROOT + relative)))


def load_example(
    name: str,
    *,
    free_flyer: bool | None = None,
    locked: Sequence[str] | Mapping[str, object] | None = None,
    memory_limit: int | None = None,
) -> Robot:
    """Load an example-robot-data model by short name, without meshes.

    Parameters
    ----------
    name : str
        One of :data:`EXAMPLES`: ``double_pendulum``, ``ur5``, ``panda``,
        ``talos_reduced``, ``solo12``, ...
    free_flyer : bool, optional
        Default: True for legged robots (talos_reduced, solo12), else False.
    locked, memory_limit
        As in :func:`load_urdf`.

    The SRDF's named configurations (``half_sitting``, ``standing``, ...) are kept
    in :attr:`Robot.reference_configurations` when the SRDF exists.
    """
    path = example_urdf_path(name)
    urdf_rel, srdf_rel, floating = EXAMPLES[name]
    ff = floating if free_flyer is None else bool(free_flyer)
    source = f"example:{name}"
    if not path.is_file():
        raise UrdfError(f"example-robot-data file missing: {path}", source)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise UrdfError(f"cannot read URDF file {path}: {exc}", source) from None
    _check_xml(text, source)
    model = _build(None, str(path), source, ff)
    refs = _reference_configurations(model, srdf_rel, source)
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
