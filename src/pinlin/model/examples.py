"""Every robot example-robot-data ships, by short name.

The table is discovered from the installed package's files (``robots/<package>/
{urdf,robots}/*.urdf``), not kept by hand, so a new release of example-robot-data
brings its new robots.  Short names:

- the file's stem, lower case, ``-`` and ``.`` turned into ``_``, a trailing
  ``_robot`` dropped (``ur5_robot.urdf`` -> ``ur5``, ``b1-z1.urdf`` -> ``b1_z1``);
- a few names fixed by :data:`RENAMED` (two packages ship an ``anymal.urdf``: ANYmal B
  is ``anymal``, ANYmal C ``anymal_c``) and a few aliases in :data:`ALIASES`
  (``talos`` is ``talos_reduced``, as in example-robot-data's own loaders);
- any other clash is resolved by prefixing the package name.

The SRDF of a URDF is ``srdf/<stem>.srdf`` in its package, else without
``_robot``, else the longest SRDF stem that begins the URDF's stem
(``solo12`` -> ``solo.srdf``, ``talos_reduced`` -> ``talos.srdf``).

Free-flyer default (:func:`floating_by_default`): on when the SRDF declares a
floating ``<virtual_joint>``, or the package is a legged robot, a humanoid or a flying
robot (:data:`FLOATING_PACKAGES`), except the arms of :data:`FIXED_FILES`; off for
arms, hands, mobile manipulators (their bases are joints of the URDF or planar
virtual joints) and pendulums.  ``load_example(name, free_flyer=...)`` overrides it.
"""

from __future__ import annotations

import difflib
import functools
import importlib.metadata
import warnings
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import InputError, NameNotFoundError, ParameterError
from .inertia import inertia_fault

__all__ = [
    "ExampleEntry",
    "ExampleInfo",
    "ExampleNotFoundError",
    "ExampleTable",
    "discover_examples",
    "example_file",
    "examples",
    "find_example",
    "floating_by_default",
    "robots_directory",
    "RENAMED",
    "ALIASES",
    "FLOATING_PACKAGES",
    "EXCLUDED",
]

_ERD_ROOT = "cmeel.prefix/share/example-robot-data/robots/"

#: Files whose derived name would clash or read badly: relative path -> short name.
RENAMED = {
    "anymal_b_simple_description/robots/anymal.urdf": "anymal",
    "anymal_b_simple_description/robots/anymal-kinova.urdf": "anymal_kinova",
    "anymal_c_simple_description/urdf/anymal.urdf": "anymal_c",
    "alexander_description/urdf/alexander_v1.lowerBodyOnly.urdf": "alexander",
    "asr_twodof_description/urdf/TwoDofs.urdf": "asr_twodof",
    "g1_description/urdf/g1_29dof_rev_1_0.urdf": "g1",
    "g1_description/urdf/g1_29dof_with_hand_rev_1_0.urdf": "g1_with_hand",
    "hector_description/robots/quadrotor_base.urdf": "hector",
    "borinot_description/urdf/borinot_flying_arm_2.urdf": "borinot",
    "hextilt_description/urdf/hextilt_flying_arm_5.urdf": "hextilt",
    "hyq_description/robots/hyq_no_sensors.urdf": "hyq",
}

#: Files left out, with the reason.
EXCLUDED = {
    "ur_description/urdf/ur3.urdf": "an empty xacro output (no <link>); ur3 is ur3_robot.urdf",
}

#: Second names for a robot: alias -> name.
ALIASES = {"talos": "talos_reduced", "talos_full": "talos_full_v2", "xarm": "xarm7", "so_arm": "so101", "alex": "alex_nub_hands"}

#: Packages of legged robots, humanoids and flying robots: free-flyer on by default.
FLOATING_PACKAGES = frozenset({
    "a1_description", "alexander_description", "anymal_b_simple_description", "anymal_c_simple_description",
    "b1_description", "bolt_description", "borinot_description", "cassie_description", "centauro_description",
    "g1_description", "go1_description", "go2_description", "hector_description", "hextilt_description",
    "human_description", "hyq_description", "icub_description", "iris_description", "laikago_description",
    "quadruped_description", "romeo_description", "simple_humanoid_description", "solo_description", "talos_data",
})  # fmt: skip

#: Files of a floating package that are fixed-base arms.
FIXED_FILES = frozenset({"talos_data/robots/talos_left_arm.urdf"})


class ExampleNotFoundError(NameNotFoundError, ParameterError):
    """No example robot has this name; the message lists close matches and every name.

    A :class:`~pinlin.NameNotFoundError` and a :class:`~pinlin.ParameterError`
    (``parameter = "name"``), as unknown examples were before.

    Attributes
    ----------
    name : str
    valid : tuple of str
        Every known name.
    close : tuple of str
        The close matches (:func:`difflib.get_close_matches`).

    Examples
    --------
    >>> try:
    ...     pinlin.load_example("ur55")
    ... except pinlin.ExampleNotFoundError as exc:
    ...     print(exc.name)
    ur55
    """

    what = "example"

    def __init__(self, name: str, valid, close):
        self.name, self.valid, self.close = str(name), tuple(valid), tuple(close)
        self.parameter = "name"
        hint = f"did you mean {', '.join(repr(c) for c in self.close)}? " if self.close else ""
        InputError.__init__(self, f"unknown example {self.name!r}; {hint}known examples: {list(self.valid)}")


@dataclass(frozen=True)
class ExampleEntry:
    """Where an example's files are (relative to example-robot-data's ``robots/``) and its free-flyer default."""

    name: str
    urdf: str
    srdf: str | None
    free_flyer: bool


@dataclass(frozen=True)
class ExampleInfo:
    """One row of :func:`examples`.

    Attributes
    ----------
    name : str
        The short name for :func:`pinlin.load_example`.
    file : str
        The URDF, relative to example-robot-data's ``robots/`` directory.
    nv : int
        Velocity coordinates with the default free flyer.
    references : tuple of str
        Named configurations of the SRDF (``standing``, ``half_sitting``, ...).
    free_flyer : bool
        The free-flyer default.
    inertia : str
        ``"check"`` when every body is physically valid, ``"repair"`` when some body
        is not and the robot loads only with ``inertia="repair"``.
    massless : tuple of str
        Joints that move no mass and no inertia (gripper fingers without inertial
        data): the mass matrix is singular until they are locked
        (``load_example(name, locked=row.massless)``).

    Examples
    --------
    >>> info = next(r for r in pinlin.examples() if r.name == "ur5")
    >>> info.name, info.nv
    ('ur5', 6)
    """

    name: str
    file: str
    nv: int
    references: tuple[str, ...]
    free_flyer: bool
    inertia: str
    massless: tuple[str, ...] = ()

    def __repr__(self) -> str:
        refs = ",".join(self.references) or "-"
        massless = f" massless={len(self.massless)}" if self.massless else ""
        return (f"{self.name:<26} nv={self.nv:<4} free_flyer={str(self.free_flyer):<5} refs={refs:<24} "
                f"inertia={self.inertia:<6} {self.file}{massless}")


class ExampleTable(tuple):
    """The rows of :func:`examples`, a tuple of :class:`ExampleInfo` that prints one row a line.

    Indexed by position (a row, or a slice: a table) or by name (the row of that robot); ``name in table``
    asks for a name.

    Raises
    ------
    ExampleNotFoundError
        Indexed by a name that no row has (a ``ValueError``, as every bad input; it lists the close names).

    Examples
    --------
    >>> table = pinlin.examples()
    >>> table["ur5"].nv, "ur5" in table, table[0] == table[table[0].name]
    (6, True, True)
    """

    def __getitem__(self, key):
        if isinstance(key, str):
            for row in self:
                if row.name == key:
                    return row
            names = self.names()
            raise ExampleNotFoundError(key, names, difflib.get_close_matches(key, names, n=4, cutoff=0.6))
        item = super().__getitem__(key)
        return ExampleTable(item) if isinstance(key, slice) else item

    def __contains__(self, item) -> bool:
        return item in self.names() if isinstance(item, str) else super().__contains__(item)

    def __repr__(self) -> str:
        return f"{len(self)} example robots:\n" + "\n".join(repr(row) for row in self)

    def names(self) -> tuple[str, ...]:
        """The robots' names, in the table's order.

        Examples
        --------
        >>> "panda" in pinlin.examples().names()
        True
        """
        return tuple(row.name for row in self)


def robots_directory() -> Path:
    """example-robot-data's ``robots/`` directory.

    Raises
    ------
    ParameterError
        example-robot-data is not installed.
    """
    try:
        dist = importlib.metadata.distribution("example-robot-data")
    except importlib.metadata.PackageNotFoundError:
        raise ParameterError("name", "example-robot-data is not installed (pip install example-robot-data)") from None
    return Path(str(dist.locate_file(_ERD_ROOT)))


def example_file(relative: str) -> Path:
    """A file of example-robot-data by its path under ``robots/``."""
    return robots_directory() / relative


def _short_name(relative: str) -> str:
    if relative in RENAMED:
        return RENAMED[relative]
    name = Path(relative).stem.lower().replace("-", "_").replace(".", "_")
    return name.removesuffix("_robot")


def _srdf_of(package: Path, stem: str) -> str | None:
    srdfs = {p.stem: p for p in sorted((package / "srdf").glob("*.srdf"))}
    for candidate in (stem, stem.removesuffix("_robot")):
        if candidate in srdfs:
            return str(srdfs[candidate].relative_to(package.parent))
    prefixes = [s for s in srdfs if stem.startswith(s)]
    return str(srdfs[max(prefixes, key=len)].relative_to(package.parent)) if prefixes else None


def floating_by_default(relative: str, srdf: Path | None) -> bool:
    """The free-flyer default of a URDF (module docstring)."""
    if relative in FIXED_FILES:
        return False
    if srdf is not None and srdf.is_file():
        try:
            root = ET.parse(srdf).getroot()
        except ET.ParseError:
            root = None
        if root is not None and any(v.get("type") == "floating" for v in root.iter("virtual_joint")):
            return True
    return relative.split("/")[0] in FLOATING_PACKAGES


@functools.lru_cache(maxsize=4)
def _discover(root: Path) -> dict[str, ExampleEntry]:
    found: dict[str, list[str]] = {}
    for path in sorted(root.glob("*/*/*.urdf")):
        relative = str(path.relative_to(root))
        if relative not in EXCLUDED:
            found.setdefault(_short_name(relative), []).append(relative)
    out: dict[str, ExampleEntry] = {}
    for name, files in found.items():
        for relative in files:
            unique = name if len(files) == 1 else f"{relative.split('/')[0].removesuffix('_description')}_{name}"
            srdf = _srdf_of(root / relative.split("/")[0], Path(relative).stem)
            ff = floating_by_default(relative, None if srdf is None else root / srdf)
            out[unique] = ExampleEntry(unique, relative, srdf, ff)
    for alias, target in ALIASES.items():
        if target in out and alias not in out:
            out[alias] = ExampleEntry(alias, out[target].urdf, out[target].srdf, out[target].free_flyer)
    return dict(sorted(out.items()))


def discover_examples() -> dict[str, ExampleEntry]:
    """Short name -> :class:`ExampleEntry` for every URDF of the installed example-robot-data."""
    return dict(_discover(robots_directory()))


def find_example(name: str) -> ExampleEntry:
    """The entry of ``name``.

    Raises
    ------
    ExampleNotFoundError
        Unknown name; the message lists close matches (difflib) and every name.
    """
    table = discover_examples()
    if not isinstance(name, str) or name not in table:
        close = difflib.get_close_matches(str(name), list(table), n=4, cutoff=0.6)
        raise ExampleNotFoundError(name, table, close)
    return table[name]


def _references(srdf: Path | None) -> tuple[str, ...]:
    if srdf is None or not srdf.is_file():
        return ()
    try:
        root = ET.parse(srdf).getroot()
    except ET.ParseError:
        return ()
    return tuple(dict.fromkeys(g.get("name", "?") for g in root.iter("group_state")))


def _row(entry: ExampleEntry, root: Path) -> ExampleInfo:
    path = str(root / entry.urdf)
    model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if entry.free_flyer else pin.buildModelFromUrdf(path)
    faulty = any(inertia_fault(np.linalg.eigvalsh(model.inertias[j].inertia)) is not None
                 for j in range(1, model.njoints))
    refs = _references(None if entry.srdf is None else root / entry.srdf)
    return ExampleInfo(entry.name, entry.urdf, model.nv, refs, entry.free_flyer, "repair" if faulty else "check",
                       _massless_joints(model))


def _massless_joints(model: pin.Model) -> tuple[str, ...]:
    """Joints whose whole subtree has zero mass and zero inertia."""
    def empty(j: int) -> bool:
        inertia = model.inertias[j]
        return inertia.mass == 0 and not np.any(np.asarray(inertia.inertia))
    return tuple(model.names[j] for j in range(1, model.njoints) if all(empty(k) for k in model.subtrees[j]))


def examples() -> ExampleTable:
    """The table of every example robot: name, file, nv, SRDF reference poses, free-flyer default, inertia.

    Builds each model once with Pinocchio (no meshes; about a second for the whole
    set).  A robot that Pinocchio cannot build, or that has no movable joint even
    with its default free flyer, is left out with a ``UserWarning`` naming it.

    Examples
    --------
    >>> table = pinlin.examples()
    >>> row = next(r for r in table if r.name == "ur5")
    >>> row.nv, row.free_flyer
    (6, False)
    """
    root = robots_directory()
    rows = []
    for entry in discover_examples().values():
        try:
            row = _row(entry, root)
        except (ValueError, RuntimeError) as exc:
            warnings.warn(f"example {entry.name!r} ({entry.urdf}) left out: Pinocchio cannot build it ({exc})",
                          UserWarning, stacklevel=2)
            continue
        if row.nv == 0:
            warnings.warn(f"example {entry.name!r} ({entry.urdf}) left out: it has no movable joint", UserWarning,
                          stacklevel=2)
            continue
        rows.append(row)
    return ExampleTable(rows)
