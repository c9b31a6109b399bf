"""The ``[sweep]`` table of a scene file: which parameter, which values, and the scene at each value.

Format::

    [sweep]
    parameter = "follower.tip.force"   # see the paths below
    values = { start = 0.0, stop = 30.0, num = 31 }   # or a list [0.0, 1.0, ...]
    # direction = [0.0, 0.0, 1.0]      # a vector parameter is value x direction
    # boundaries = true                # exact values where the verdict changes
    # [sweep.second]                   # a second parameter: a stability map
    # parameter = "spring.joint1.stiffness"
    # values = [1.0, 2.0, 3.0]

Parameter paths name what the scene file sets:

- ``<kind>.<name>.<field>``: the field of the element of that kind (``spring``,
  ``damper``, ``follower``, ``dead``, ``spring_damper``, ``bushing``) on joint or
  frame ``<name>``, for example ``spring.joint1.stiffness``, ``follower.tip.force``;
  ``<kind>[k].<field>`` picks the k-th table of that kind (1-based, as the scene
  file's error messages count them);
- ``prescribed.<joint>``: a prescribed velocity (a spin speed);
- ``gravity``; ``rayleigh.alpha``, ``rayleigh.beta``.

A field that holds a vector or matrix is set to ``value x direction``: the
``direction`` given, else the scene's own value divided by its norm (so the
value is the magnitude: ``follower.tip.force`` scales the scene's force along
its own line).  ``field[i]`` sets one entry instead.
"""

from __future__ import annotations

import dataclasses
import re
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import ParameterError, SceneFileError
from ...model.elements import RayleighDamping
from ...model.scene import Scene
from ...model.scene_file import SceneSpec
from ...studies.grid import MAX_POINTS as GRID_MAX_POINTS
from ..units import coordinate_units

__all__ = ["SweepParameter", "SweepPlan", "sweep_plan", "MAX_POINTS", "ELEMENT_KINDS", "SWEEP_FORMAT"]

#: The format of the ``[sweep]`` table and its parameter paths, as ``pinlin sweep --help`` prints it.
SWEEP_FORMAT = __doc__.split("Format::\n", 1)[1]

#: Most points of one sweep (both parameters together): a modal analysis each, so 10 000 points are
#: minutes for a small scene; more is a typing error more often than a plan.  The API's default cap
#: (:data:`pinlin.studies.MAX_POINTS`), one number for both.
MAX_POINTS = GRID_MAX_POINTS
#: Element kinds a path may name, and the attribute that names the element in the path.
ELEMENT_KINDS = {"spring": "joint", "damper": "joint", "follower": "frame", "dead": "frame",
                 "spring_damper": "frame", "bushing": "frame"}
_KEYS = {"parameter", "values", "direction", "boundaries", "second"}
_PATH = re.compile(r"^(?P<kind>[a-z_]+)(\[(?P<index>\d+)\])?\.(?:(?P<name>[^.\[\]]+)\.)?"
                   r"(?P<field>[a-z_]+)(\[(?P<entry>\d+)\])?$")
#: Units of the fields that do not depend on the joint.
_FIELD_UNITS = {"force": "N", "torque": "N m", "rest_length": "m", "alpha": "1/s", "beta": "s"}


@dataclass(frozen=True)
class SweepParameter:
    """One swept parameter: its path, values [unit], and how it enters the scene.

    Attributes
    ----------
    path : str
        As written in the scene file (or on the command line).
    values : (k,) ndarray
        The values, in the unit ``unit``.
    unit : str
    target : str
        "element", "prescribed", "gravity" or "rayleigh".
    index : int or None
        The element's position in the scene's element list ("element").
    field : str
        The element's field, the prescribed joint, or the Rayleigh coefficient.
    entry : int or None
        One entry of a vector field (``field[i]``).
    direction : ndarray or None
        A vector or matrix field is ``value * direction``.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> parameter = plan.parameters[0]
    >>> parameter.path, parameter.unit, parameter.target, parameter.direction
    ('follower.tip.force', 'N', 'element', array([0., 0., 1.]))
    """

    path: str
    values: np.ndarray
    unit: str
    target: str
    index: int | None
    field: str
    entry: int | None
    direction: np.ndarray | None


@dataclass(frozen=True)
class SweepPlan:
    """The swept parameters (one, or two for a stability map) of a scene spec.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> len(plan.parameters), plan.boundaries
    (1, True)
    """

    spec: SceneSpec
    parameters: tuple[SweepParameter, ...]
    boundaries: bool

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(p.values.size for p in self.parameters)

    def scene_at(self, values: Sequence[float]) -> Scene:
        """The scene with each parameter at its value.

        Raises
        ------
        PinlinError
            Whatever the scene or an element refuses at these values (a negative
            stiffness, a prescribed joint of several degrees of freedom, ...).
        """
        scene = self.spec.scene
        elements = list(scene._user_elements)  # the scene's own list, without the URDF dampers it adds
        changes: dict[str, Any] = {}
        for p, value in zip(self.parameters, values):
            if p.target == "element":
                element = elements[p.index]
                elements[p.index] = dataclasses.replace(element, **{p.field: _set(getattr(element, p.field), p, value)})
            elif p.target == "prescribed":
                changes["prescribed"] = {**changes.get("prescribed", dict(scene.prescribed)), p.field: float(value)}
            elif p.target == "gravity":
                changes["gravity"] = _set(changes.get("gravity", scene.gravity), p, value)
            else:
                elements = _with_rayleigh(elements, p.field, float(value))
        return scene.replace(elements=elements, **changes)


def _set(current, p: SweepParameter, value: float):
    """The field's new value: ``value``, one entry of a copy, or ``value * direction``."""
    if p.entry is not None:
        out = np.array(current, dtype=float)
        out.flat[p.entry] = value
        return out
    return float(value) if p.direction is None else value * p.direction


def _with_rayleigh(elements: list, coefficient: str, value: float) -> list:
    for i, element in enumerate(elements):
        if isinstance(element, RayleighDamping):
            return [*elements[:i], dataclasses.replace(element, **{coefficient: value}), *elements[i + 1:]]
    return [*elements, RayleighDamping(**{coefficient: value})]


class _Planner:
    """Reads one parameter's table, failing with the scene file and the key (or the command-line option)."""

    def __init__(self, spec: SceneSpec, where: str, options: bool = False):
        self.spec, self.where, self.options = spec, where, options

    def fail(self, key: str, message: str):
        if self.options:  # the table came from --parameter and --values
            raise ParameterError("--values" if key.startswith("values") else "--parameter", message)
        raise SceneFileError(message, self.spec.path, f"{self.where}.{key}" if key else self.where)

    def values(self, table: Mapping) -> np.ndarray:
        raw = table.get("values")
        if isinstance(raw, Mapping):
            unknown = sorted(set(raw) - {"start", "stop", "num"})
            if unknown or not all(k in raw for k in ("start", "stop", "num")):
                self.fail("values", "expected a list of numbers or a table { start = ..., stop = ..., num = ... }")
            num = raw["num"]
            if isinstance(num, bool) or not isinstance(num, int) or not 2 <= num <= MAX_POINTS:
                self.fail("values.num", f"expected an integer in [2, {MAX_POINTS}], got {num!r}")
            raw = np.linspace(self.number(raw["start"], "values.start"), self.number(raw["stop"], "values.stop"), num)
        elif not (isinstance(raw, list) and raw):
            self.fail("values", f"expected a non-empty list of numbers or {{ start, stop, num }}, got {raw!r:.80}")
        values = np.array([self.number(v, f"values[{i}]") for i, v in enumerate(raw)])
        if values.size > MAX_POINTS:
            self.fail("values", f"{values.size} values; at most {MAX_POINTS}")
        if values.size > 1 and not (np.all(np.diff(values) > 0) or np.all(np.diff(values) < 0)):
            self.fail("values", "must be strictly increasing or strictly decreasing (a path through the parameter)")
        return values

    def number(self, value, key: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not abs(value) <= sys.float_info.max:
            self.fail(key, f"expected a finite number, got {value!r:.80}")
        return float(value)

    def parameter(self, table) -> SweepParameter:
        if not isinstance(table, Mapping):
            self.fail("", f"expected a table, got {table!r:.80}")
        unknown = sorted(set(table) - _KEYS)
        if unknown:
            self.fail(unknown[0], f"unknown key; expected one of {sorted(_KEYS)}")
        path = table.get("parameter")
        if not isinstance(path, str):
            self.fail("parameter", f"expected a parameter path such as 'follower.tip.force', got {path!r:.80}")
        values = self.values(table)
        return self.resolve(path, values, table.get("direction"))

    def resolve(self, path: str, values: np.ndarray, direction) -> SweepParameter:
        scene = self.spec.scene
        if path in ("gravity", "scene.gravity") or path.startswith(("gravity[", "scene.gravity[")):
            entry = self.entry(path, 3)
            return SweepParameter(path, values, "m/s^2", "gravity", None, "gravity", entry,
                                  None if entry is not None else self.direction(scene.gravity, direction, path))
        if path in ("rayleigh.alpha", "rayleigh.beta"):
            field = path.split(".")[1]
            return SweepParameter(path, values, _FIELD_UNITS[field], "rayleigh", None, field, None, None)
        if path.startswith("prescribed."):
            joint = path.split(".", 1)[1]
            unit = f"{self.joint_unit(joint, 'parameter')}/s"
            return SweepParameter(path, values, unit, "prescribed", None, joint, None, None)
        match = _PATH.match(path)
        if not match or match["kind"] not in ELEMENT_KINDS or (match["index"] is None) == (match["name"] is None):
            self.fail("parameter", f"unknown parameter path {path!r}; expected <kind>.<joint or frame>.<field> "
                      f"(kinds {sorted(ELEMENT_KINDS)}), <kind>[k].<field>, prescribed.<joint>, gravity, "
                      f"rayleigh.alpha or rayleigh.beta")
        return self.element(path, match, values, direction)

    def element(self, path: str, match, values, direction) -> SweepParameter:
        kind, naming = match["kind"], ELEMENT_KINDS[match["kind"]]
        elements = [(i, e) for i, e in enumerate(self.spec.scene._user_elements) if e.kind == kind]
        if match["index"] is not None:
            k = int(match["index"])
            if not 1 <= k <= len(elements):
                self.fail("parameter", f"{path!r}: the scene has {len(elements)} {kind} element(s)")
            found = [elements[k - 1]]
        else:
            found = [(i, e) for i, e in elements if getattr(e, naming) == match["name"]]
            names = sorted({getattr(e, naming) for _, e in elements})
            if not found:
                self.fail("parameter", f"{path!r}: no {kind} on {naming} {match['name']!r}; the scene's: {names}")
            if len(found) > 1:
                self.fail("parameter", f"{path!r}: {len(found)} {kind} elements on {match['name']!r}; "
                          f"name one as {kind}[k].{match['field']}")
        index, element = found[0]
        field = match["field"]
        fields = [f.name for f in dataclasses.fields(element) if f.name != naming and f.name != "target"]
        if field not in fields:
            self.fail("parameter", f"{path!r}: a {kind} has no field {field!r}; expected one of {fields}")
        current = getattr(element, field)
        entry = self.entry(path, np.size(current)) if match["entry"] is not None else None
        vector = current is not None and np.ndim(current) > 0 and entry is None
        return SweepParameter(path, values, self.unit(element, field), "element", index, field, entry,
                              self.direction(current, direction, path) if vector else None)

    def entry(self, path: str, size: int) -> int | None:
        found = re.search(r"\[(\d+)\]$", path)
        if found is None:
            return None
        entry = int(found.group(1))
        if entry >= size:
            self.fail("parameter", f"{path!r}: entry {entry} of a field with {size} entries (0-based)")
        return entry

    def direction(self, current, given, path: str) -> np.ndarray:
        current = np.asarray(current, dtype=float)
        if given is None:
            norm = float(np.linalg.norm(current))
            if norm == 0:
                self.fail("direction", f"{path!r} is zero in the scene: give its direction")
            return current / norm
        try:
            if not isinstance(given, list) or any(isinstance(x, (bool, str)) for x in given):
                raise TypeError  # numpy would read "1" and true as numbers
            out = np.array(given, dtype=float)
        except (TypeError, ValueError, OverflowError):
            self.fail("direction", f"expected a list of numbers, got {given!r:.80}")
        if out.shape != current.shape or not np.all(np.isfinite(out)) or not np.any(out):
            self.fail("direction", f"expected {current.shape} finite numbers, not all zero, got {given!r:.80}")
        return out

    def joint_unit(self, joint: str, key: str) -> str:
        robot = self.spec.scene.robot
        if joint not in robot.joint_names:
            self.fail(key, f"unknown joint {joint!r}; the robot's: {list(robot.joint_names)}")
        return coordinate_units(robot, [robot.joint(joint).idx_v])[0]

    def unit(self, element, field: str) -> str:
        if field in _FIELD_UNITS:
            return _FIELD_UNITS[field]
        if element.kind == "spring_damper":
            return {"stiffness": "N/m", "damping": "N s/m"}.get(field, "")
        if element.kind not in ("spring", "damper"):
            return ""  # a bushing's entries mix N/m and N m/rad: its docstring says which is which
        angle = self.joint_unit(element.joint, "parameter") == "rad"
        return {"stiffness": "N m/rad" if angle else "N/m", "damping": "N m s/rad" if angle else "N s/m",
                "rest": "rad" if angle else "m"}.get(field, "")


def sweep_plan(spec: SceneSpec, table, *, options: bool = False) -> SweepPlan:
    """The sweep of a scene spec from its ``[sweep]`` table (format in the module docstring).

    Parameters
    ----------
    spec : SceneSpec
    table : mapping or None
        The ``[sweep]`` table (``spec.sweep``), or one made of command-line options.
    options : bool
        ``table`` came from the options ``--parameter`` and ``--values``: errors name them.

    Raises
    ------
    SceneFileError
        No table, an unknown key, a path that names nothing in the scene, values
        that are not finite numbers, not monotonic or too many (:data:`MAX_POINTS`),
        a bad direction; the message names the file and the key (``sweep.values``).
    ParameterError
        The same, for a table made of options (``options=True``), named by the option.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> plan.parameters[0].values
    array([ 0., 10., 20., 30.])
    """
    if table is None:
        raise SceneFileError("no [sweep] table: give one in the scene file, or --parameter and --values",
                             spec.path, "sweep")
    first = _Planner(spec, "sweep", options).parameter(table)
    parameters = [first]
    second = table.get("second")
    if second is not None:
        if isinstance(second, Mapping) and {"second", "boundaries"} & set(second):
            raise SceneFileError("'second' and 'boundaries' belong to [sweep] itself", spec.path, "sweep.second")
        parameters.append(_Planner(spec, "sweep.second").parameter(second))
        if parameters[1].path == first.path:
            raise SceneFileError("the two parameters are the same", spec.path, "sweep.second.parameter")
    if np.prod([p.values.size for p in parameters]) > MAX_POINTS:
        raise SceneFileError(f"{' x '.join(str(p.values.size) for p in parameters)} points; at most {MAX_POINTS}",
                             spec.path, "sweep")
    boundaries = table.get("boundaries", True)
    if not isinstance(boundaries, bool):
        raise SceneFileError(f"expected true or false, got {boundaries!r:.80}", spec.path, "sweep.boundaries")
    return SweepPlan(spec, tuple(parameters), boundaries)
