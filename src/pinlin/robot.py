"""Loading a rigid multibody from a URDF into a :class:`Robot`.

Only Pinocchio's kinematic model is built: no geometry model, no meshes, no
collision data (the linearized equations need inertia and kinematics only).
Joints can be locked away at load time through Pinocchio's reduced model, and
the memory Pinocchio would allocate is estimated before any ``createData``.
"""

from __future__ import annotations

import contextlib
import importlib.metadata
import os
import tempfile
import xml.etree.ElementTree as ET
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin

from .errors import (
    FrameNotFoundError,
    JointNotFoundError,
    ModelTooLargeError,
    ParameterError,
    UrdfError,
)

__all__ = [
    "Robot",
    "JointInfo",
    "load_urdf",
    "load_urdf_string",
    "load_example",
    "EXAMPLES",
    "example_urdf_path",
    "data_path",
    "pinocchio_data_bytes",
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
    root = Path(__file__).parent / "data"
    path = root / name
    if not path.is_file():
        bundled = sorted(str(p.relative_to(root)) for p in root.rglob("*") if p.is_file())
        raise ParameterError("name", f"no bundled file {name!r}; bundled files: {bundled}")
    return path


# ----------------------------------------------------------------------------- memory guard


def pinocchio_data_bytes(nv: int) -> int:
    """Estimated peak bytes of one ``createData`` for a model with ``nv`` velocities.

    ``pin.Data`` keeps four nv x nv x nv tensors of doubles for the second-order
    derivatives (SPEC section 1): 32 nv^3 bytes.  While ``createData`` builds
    them it transiently holds about twice that (peak resident growth of a
    :class:`~pinlin.Scene` measured at 2.25x, 2.14x and 2.10x of 32 nv^3 for
    nv = 100, 150 and 200), so the estimate is 72 nv^3 plus the quadratic terms
    (Jacobians, mass matrix, derivative matrices) with a generous constant.
    """
    return 72 * nv**3 + 400 * nv**2 + 4_000_000


def _available_memory() -> int | None:
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_AVPHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        return None


def _check_memory(nv: int, memory_limit: int | None, what: str) -> None:
    """Refuse, before allocating, a model whose ``pin.Data`` would not fit.

    ``memory_limit`` in bytes; ``None`` allows 80 % of the memory available now
    for the peak of ``createData`` (the analyses' workspaces are O(n^2), small
    beside it).
    """
    required = pinocchio_data_bytes(nv)
    if memory_limit is None:
        available = _available_memory()
        if available is None:
            return
        limit = int(0.8 * available)
    else:
        limit = int(memory_limit)
    if required > limit:
        raise ModelTooLargeError(
            f"{what}: nv = {nv} needs about {required / 2**30:.2f} GiB while Pinocchio builds its "
            f"data (its second-order derivative tensors keep 32 nv^3 bytes and peak near twice "
            f"that), more than the "
            f"{limit / 2**30:.2f} GiB allowed; lock joints (locked=...) to reduce nv or "
            f"raise memory_limit",
            required=required,
            available=limit,
        )


# ----------------------------------------------------------------------------- Robot


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
    :func:`load_urdf_string` or :func:`load_example`.

    Attributes
    ----------
    model : pinocchio.Model
        The underlying kinematic and inertial model (no geometry).
    source : str
        Where the model came from (a path, ``"<string>"`` or ``"example:NAME"``).
    reference_configurations : dict of str to ndarray
        Named configurations from the SRDF, when one was available.
    """

    def __init__(
        self,
        model: pin.Model,
        source: str = "<model>",
        reference_configurations: Mapping[str, np.ndarray] | None = None,
    ):
        self._model = model
        self.source = source
        self.reference_configurations = {
            k: np.array(v, dtype=float) for k, v in (reference_configurations or {}).items()
        }
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

    def joint(self, name: str) -> JointInfo:
        """Look a joint up by name.

        Raises
        ------
        JointNotFoundError
            If there is no such joint; the message lists the valid names.
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
        """
        try:
            return self._frames[name]
        except (KeyError, TypeError):
            raise FrameNotFoundError(str(name), self.frame_names, context=self.source) from None

    def neutral(self) -> np.ndarray:
        """Pinocchio's neutral configuration (size nq)."""
        return pin.neutral(self._model)

    def create_data(self, model: pin.Model | None = None, memory_limit: int | None = None):
        """``model.createData()`` after checking that it fits in memory.

        Raises
        ------
        ModelTooLargeError
            When the estimate of :func:`pinocchio_data_bytes` exceeds the limit.
        """
        model = self._model if model is None else model
        _check_memory(model.nv, memory_limit, f"model {model.name!r}")
        return model.createData()

    def lock(self, joints: Sequence[str] | Mapping[str, object]) -> Robot:
        """A new robot with the given joints removed (Pinocchio's reduced model).

        Parameters
        ----------
        joints : sequence of str, or mapping of str to value
            Joint names, locked at the neutral configuration; or a mapping from
            joint name to its locked value (a number for 1-DOF joints, else a
            configuration vector of the joint's size nq).
        """
        return Robot(
            _reduce(self._model, joints, self.source),
            self.source,
            self.reference_configurations if not joints else None,
        )

    def __repr__(self) -> str:
        return (
            f"Robot({self.name!r}, nq={self.nq}, nv={self.nv}, "
            f"joints={len(self._joints)}, source={self.source!r})"
        )


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


def _reduce(model: pin.Model, locked, source: str) -> pin.Model:
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
def _captured_stderr() -> Iterator[list[str]]:
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
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise UrdfError(f"{source}: malformed XML ({exc})", source) from None
    if root.tag != "robot":
        raise UrdfError(f"{source}: root element is <{root.tag}>, expected <robot>", source)
    if root.find("link") is None:
        raise UrdfError(f"{source}: the URDF has no <link>", source)


def _build(text: str | None, path: str | None, source: str, free_flyer: bool) -> pin.Model:
    root_joint = pin.JointModelFreeFlyer() if free_flyer else None
    with _captured_stderr() as messages:
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
    model = _reduce(model, locked, source)
    _check_memory(model.nv, memory_limit, source)
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
        Missing file, malformed XML, invalid URDF, no movable joint.
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
    model = _build(None, str(path), source, ff)
    refs: dict[str, np.ndarray] = {}
    if srdf_rel is not None:
        srdf = _erd_file(srdf_rel)
        if srdf.is_file():
            with _captured_stderr():
                try:
                    pin.loadReferenceConfigurations(model, str(srdf), False)
                    refs = {e.key(): np.array(e.data(), dtype=float) for e in model.referenceConfigurations}
                except (ValueError, RuntimeError):
                    refs = {}
    return _finish(model, source, locked, memory_limit, refs)
