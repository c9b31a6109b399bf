"""The inputs and outputs of a state-space model, written as short strings (theory: conventions).

Each input or output is one scalar signal.  It is written as a string
``"kind:target[:axis]"`` (or, for coordinates, the coordinate's name or index
alone), and the same string, completed, is its name in the model, in
python-control and in reports:

Inputs (the columns of B)

===========================  ==========================================================  ===============
written                      meaning                                                     unit
===========================  ==========================================================  ===============
``"joint1"``, ``0``,         generalized force on coordinate ``joint1`` (a column of     N or N m
``"force:joint1"``           the identity); named ``"force:joint1"``
``"follower:tip:fz"``        force along the z axis of frame ``tip``, at its origin,     N (fx, fy, fz),
                             turning with the frame (``FollowerWrench``); ``fx, fy, fz,  N m (tx, ty, tz)
                             tx, ty, tz``
``"dead:tip:fx"``            the same in world axes (``DeadWrench``)                     N or N m
``"follower:tip"``           six inputs, ``follower:tip:fx`` ... ``follower:tip:tz``
a ``FollowerWrench`` or      that wrench times the input u (u = 1 is the wrench as       1
``DeadWrench``, or a pair    given); named ``"follower:tip"`` / ``"dead:tip"`` or the
``(name, wrench)``           given name
===========================  ==========================================================  ===============

Outputs (the rows of C)

===========================  ==========================================================  ===============
``"joint1"``, ``0``          coordinate ``joint1``; named ``"joint1"``                   rad or m
``"rate:joint1"``            its rate                                                    rad/s or m/s
``"position:tip:x"``         displacement of the origin of frame ``tip`` along world x   m
``"velocity:tip:z"``         its velocity along world z                                  m/s
``"position:tip"``           three outputs, ``position:tip:x`` ... ``position:tip:z``
===========================  ==========================================================  ===============

The state names are the coordinates (``"joint1"``) followed by their rates
(``"rate:joint1"``).  A coordinate name is matched whole first, so a joint
whose name contains a colon is still found.  Names must be unique.
"""

from __future__ import annotations

import numbers
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..model.elements import DeadWrench, FollowerWrench
from ..model.elements.base import WrenchElement

__all__ = [
    "Signal",
    "WRENCH_AXES",
    "POINT_AXES",
    "INPUT_KINDS",
    "OUTPUT_KINDS",
    "FRAME_KINDS",
    "parse_inputs",
    "parse_outputs",
    "coordinate_inputs",
    "coordinate_outputs",
]

#: Components of a wrench input: force [N] then torque [N m], in frame axes (follower) or world axes (dead).
WRENCH_AXES = ("fx", "fy", "fz", "tx", "ty", "tz")
#: Components of a frame output, in world axes.
POINT_AXES = ("x", "y", "z")
#: Kinds of input: a generalized force on a coordinate, a follower or a dead wrench at a frame.
INPUT_KINDS = ("force", "follower", "dead")
#: Kinds of output: a coordinate, its rate, the position or velocity of a frame origin.
OUTPUT_KINDS = ("coordinate", "rate", "position", "velocity")
#: The kinds that act at a frame and so need the scene's kinematics.
FRAME_KINDS = frozenset({"follower", "dead", "position", "velocity"})

_WRENCH_CLASSES = {"follower": FollowerWrench, "dead": DeadWrench}


@dataclass(frozen=True)
class Signal:
    """One scalar input or output.

    Attributes
    ----------
    name : str
        Its name in the model (``"force:joint1"``, ``"position:tip:x"``, ...).
    kind : str
        One of :data:`INPUT_KINDS` or :data:`OUTPUT_KINDS`.
    target : str
        The coordinate or frame it refers to.
    index : int or None
        The coordinate's index in ``sys.dof_names`` (coordinate kinds), or the
        axis index (frame outputs: 0-2 for x-z).
    wrench : WrenchElement or None
        The wrench an input of kind follower or dead applies for u = 1.

    Examples
    --------
    >>> from pinlin.interop import parse_outputs
    >>> signal = parse_outputs("rate:joint2", ("joint1", "joint2"))[0]
    >>> signal.name, signal.kind, signal.target, signal.index
    ('rate:joint2', 'rate', 'joint2', 1)
    """

    name: str
    kind: str
    target: str
    index: int | None = None
    wrench: WrenchElement | None = None


def _is_named_wrench(item) -> bool:
    return isinstance(item, tuple) and len(item) == 2 and isinstance(item[1], WrenchElement)


def _items(spec, label: str) -> list:
    """One signal or a list of them, as a list."""
    single = isinstance(spec, (str, numbers.Integral, WrenchElement)) or _is_named_wrench(spec)
    items = [spec] if single else spec
    if not isinstance(items, (Sequence, np.ndarray)) or len(items) == 0:
        raise ParameterError(label, f"expected a signal or a non-empty list of signals, got {spec!r}")
    return list(items)


def _coordinate(item, dof_names: tuple[str, ...], label: str) -> int:
    if isinstance(item, numbers.Integral) and not isinstance(item, (bool, np.bool_)):
        if not 0 <= int(item) < len(dof_names):
            raise ParameterError(
                label, f"coordinate index {item} out of range for n = {len(dof_names)} coordinates"
            )
        return int(item)
    if item not in dof_names:
        raise ParameterError(label, f"unknown coordinate {item!r}; valid coordinates: {list(dof_names)}")
    return dof_names.index(item)


def _split(item: str, kinds: tuple[str, ...], dof_names: tuple[str, ...], label: str) -> list[str]:
    """``"kind:target[:axis]"`` as its parts, after checking the kind."""
    parts = item.split(":")
    if len(parts) < 2 or parts[0] not in kinds:
        raise ParameterError(
            label,
            f"{item!r} is neither a coordinate ({list(dof_names)}) nor 'kind:target[:axis]' "
            f"with kind in {list(kinds)}",
        )
    if parts[0] in FRAME_KINDS and len(parts) > 3:
        raise ParameterError(label, f"{item!r}: expected 'kind:frame' or 'kind:frame:axis'")
    if not parts[1]:
        raise ParameterError(label, f"{item!r}: the target name is empty")
    return parts


def _axes(item: str, parts: list[str], axes: tuple[str, ...], label: str) -> list[int]:
    if len(parts) == 2:
        return list(range(len(axes)))
    if parts[2] not in axes:
        raise ParameterError(label, f"{item!r}: unknown axis {parts[2]!r}; valid axes: {list(axes)}")
    return [axes.index(parts[2])]


def _wrench_item(item, label: str) -> Signal:
    name = None
    if isinstance(item, tuple):
        if len(item) != 2 or not isinstance(item[0], str) or not isinstance(item[1], WrenchElement):
            raise ParameterError(label, f"expected a pair (name, FollowerWrench or DeadWrench), got {item!r}")
        name, item = item
    kind = item.kind
    if kind not in _WRENCH_CLASSES:
        raise ParameterError(label, f"expected a FollowerWrench or DeadWrench, got {item!r}")
    return Signal(name or f"{kind}:{item.frame}", kind, item.frame, wrench=item)


def parse_inputs(spec, dof_names: tuple[str, ...], label: str = "inputs") -> list[Signal]:
    """The input signals written in ``spec`` (see the module docstring); None: a force on every coordinate.

    Raises
    ------
    ParameterError
        An unknown coordinate, kind or axis, an empty list, or a name used twice.

    Examples
    --------
    >>> from pinlin.interop import parse_inputs
    >>> signals = parse_inputs(["joint1", "dead:tip:fz"], ("joint1", "joint2"))
    >>> [s.name for s in signals], signals[1].wrench.force
    (['force:joint1', 'dead:tip:fz'], array([0., 0., 1.]))
    """
    if spec is None:
        return coordinate_inputs(dof_names)
    out: list[Signal] = []
    for item in _items(spec, label):
        if isinstance(item, (WrenchElement, tuple)):
            out.append(_wrench_item(item, label))
        elif isinstance(item, numbers.Integral) or (isinstance(item, str) and item in dof_names):
            k = _coordinate(item, dof_names, label)
            out.append(Signal(f"force:{dof_names[k]}", "force", dof_names[k], k))
        elif isinstance(item, str):
            parts = _split(item, INPUT_KINDS, dof_names, label)
            if parts[0] == "force":
                k = _coordinate(":".join(parts[1:]), dof_names, label)
                out.append(Signal(f"force:{dof_names[k]}", "force", dof_names[k], k))
                continue
            frame = parts[1]
            for a in _axes(item, parts, WRENCH_AXES, label):
                e = np.eye(6)[a]
                wrench = _WRENCH_CLASSES[parts[0]](frame, force=e[:3], torque=e[3:])
                out.append(Signal(f"{parts[0]}:{frame}:{WRENCH_AXES[a]}", parts[0], frame, a, wrench))
        else:
            raise ParameterError(
                label, f"expected a coordinate, a 'kind:frame:axis' string or a wrench, got {item!r}"
            )
    return _unique(out, label)


def parse_outputs(spec, dof_names: tuple[str, ...], label: str = "outputs") -> list[Signal]:
    """The output signals written in ``spec`` (see the module docstring); None: every coordinate.

    Raises
    ------
    ParameterError
        An unknown coordinate, kind or axis, an empty list, or a name used twice.

    Examples
    --------
    >>> from pinlin.interop import parse_outputs
    >>> [s.name for s in parse_outputs(["joint2", "position:tip"], ("joint1", "joint2"))]
    ['joint2', 'position:tip:x', 'position:tip:y', 'position:tip:z']
    """
    if spec is None:
        return coordinate_outputs(dof_names)
    out: list[Signal] = []
    for item in _items(spec, label):
        if isinstance(item, numbers.Integral) or (isinstance(item, str) and item in dof_names):
            k = _coordinate(item, dof_names, label)
            out.append(Signal(dof_names[k], "coordinate", dof_names[k], k))
        elif isinstance(item, str):
            parts = _split(item, OUTPUT_KINDS, dof_names, label)
            if parts[0] in ("coordinate", "rate"):
                k = _coordinate(":".join(parts[1:]), dof_names, label)
                name = dof_names[k] if parts[0] == "coordinate" else f"rate:{dof_names[k]}"
                out.append(Signal(name, parts[0], dof_names[k], k))
                continue
            for a in _axes(item, parts, POINT_AXES, label):
                out.append(Signal(f"{parts[0]}:{parts[1]}:{POINT_AXES[a]}", parts[0], parts[1], a))
        else:
            raise ParameterError(
                label, f"expected a coordinate or a 'kind:frame[:axis]' string, got {item!r}"
            )
    return _unique(out, label)


def coordinate_inputs(dof_names: tuple[str, ...]) -> list[Signal]:
    """A generalized force on every coordinate, in ``dof_names`` order.

    Examples
    --------
    >>> from pinlin.interop.signal_names import coordinate_inputs
    >>> [s.name for s in coordinate_inputs(("joint1", "joint2"))]
    ['force:joint1', 'force:joint2']
    """
    return [Signal(f"force:{name}", "force", name, k) for k, name in enumerate(dof_names)]


def coordinate_outputs(dof_names: tuple[str, ...]) -> list[Signal]:
    """Every coordinate, in ``dof_names`` order.

    Examples
    --------
    >>> from pinlin.interop.signal_names import coordinate_outputs
    >>> [(s.name, s.kind) for s in coordinate_outputs(("joint1", "joint2"))]
    [('joint1', 'coordinate'), ('joint2', 'coordinate')]
    """
    return [Signal(name, "coordinate", name, k) for k, name in enumerate(dof_names)]


def _unique(signals: list[Signal], label: str) -> list[Signal]:
    seen: set[str] = set()
    for s in signals:
        if s.name in seen:
            hint = " (name wrenches with pairs (name, wrench))" if s.wrench is not None else ""
            raise ParameterError(label, f"signal {s.name!r} appears twice{hint}")
        seen.add(s.name)
    return signals
