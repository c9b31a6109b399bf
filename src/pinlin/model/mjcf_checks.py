"""What pinlin checks in an MJCF file before Pinocchio's parser reads it.

Pinocchio 4.1's MJCF parser reads numbers it cannot parse as uninitialized memory
(``anchor="nan 0 0"`` or ``"a b c"`` became 0 0 4.6e-310), a ``<connect>`` on a site
that does not exist as a constraint on joint 16 of a 3-joint model (a crash, or a
silently wrong model), a three-number ``relpose`` as NaN, and repeated body names
as a model whose name lookups point at the wrong body.  So every attribute that
pinlin or Pinocchio reads is checked here first, with an
:class:`~pinlin.MjcfError` naming the element and the attribute:

- numbers (:data:`NUMBERS`): finite, and as many as the attribute takes; masses and
  diagonal inertias >= 0; quaternions and joint axes not zero;
- keywords: a joint's and a geom's ``type``, the compiler's ``angle``; ``class`` and
  ``childclass`` name a defined ``<default>`` class;
- names: bodies, joints and sites unique; an ``<equality>`` entry's ``body1``,
  ``body2``, ``site1``, ``site2`` exist; a connect has ``body1`` and ``anchor`` or
  ``site1`` and ``site2``, a weld ``body1`` or both sites; no body constrained to itself;
- the structure Pinocchio 4.1 would drop or get wrong (:mod:`.mjcf`'s docstring);
- the size, first of all (:func:`check_mjcf_size`): Pinocchio 4.1's parser walks the
  tree recursively (30000 nested bodies overflowed its stack) and its memory grows
  with the cube of the body count (250 bodies: 0.6 GB, 400: 2.1 GB, 700: 10.7 GB), so
  more than :data:`MAX_MJCF_BODIES` bodies or elements nested deeper than
  :data:`MAX_MJCF_DEPTH` are a :class:`~pinlin.ModelTooLargeError` before it reads the file.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass

from ..errors import MjcfError, ModelTooLargeError

__all__ = ["NUMBERS", "EqualityEntry", "check_mjcf", "check_mjcf_size", "equality_entries",
           "MAX_MJCF_BODIES", "MAX_MJCF_DEPTH"]

#: Most ``<body>`` elements an MJCF file may have: Pinocchio 4.1's parser needs about
#: 1 GB of memory for 300 (its need grows with the cube of the count).
MAX_MJCF_BODIES = 300
#: Deepest nesting of XML elements in an MJCF file (a body chain of MAX_MJCF_BODIES
#: with its inner elements fits); Pinocchio's parser recurses along it.
MAX_MJCF_DEPTH = 400


def _parser_bytes(bodies: int) -> int:
    """Pinocchio 4.1's MJCF parser's peak memory for a chain of ``bodies`` (measured: 0.95 GB for 300)."""
    return int(3.2e7 * (bodies / 100) ** 3)

_FRAME = {"pos": (3,), "quat": (4,), "euler": (3,), "axisangle": (4,), "xyaxes": (6,), "zaxis": (3,)}
_SOLVER = {"solref": (2,), "solimp": (3, 4, 5)}

#: Element -> numeric attribute -> the numbers of values it may have.
NUMBERS: dict[str, dict[str, tuple[int, ...]]] = {
    "body": dict(_FRAME),
    "inertial": {**_FRAME, "mass": (1,), "diaginertia": (3,), "fullinertia": (6,)},
    "joint": {"pos": (3,), "axis": (3,), "range": (2,), "ref": (1,), "springref": (1,), "stiffness": (1,),
              "damping": (1,), "armature": (1,), "frictionloss": (1,)},
    "site": {**_FRAME, "size": (1, 2, 3), "fromto": (6,)},
    "geom": {**_FRAME, "size": (1, 2, 3), "fromto": (6,), "mass": (1,), "density": (1,)},
    "connect": {"anchor": (3,), **_SOLVER},
    "weld": {"anchor": (3,), "relpose": (7,), "torquescale": (1,), **_SOLVER},
}

_NON_NEGATIVE = {("inertial", "mass"), ("inertial", "diaginertia"), ("geom", "mass"), ("geom", "density")}
_NON_ZERO = {("body", "quat"), ("inertial", "quat"), ("site", "quat"), ("geom", "quat"), ("joint", "axis")}
_KEYWORDS = {
    ("joint", "type"): ("hinge", "slide", "ball", "free"),
    ("compiler", "angle"): ("radian", "degree"),
    ("geom", "type"): ("plane", "hfield", "sphere", "capsule", "ellipsoid", "cylinder", "box", "mesh", "sdf"),
}


def _where(element: ET.Element) -> str:
    name = element.get("name")
    return f"<{element.tag}{f' name={name!r}' if name else ''}>"


def _numbers(element: ET.Element, attribute: str, counts: tuple[int, ...], source: str) -> list[float]:
    text = element.get(attribute)
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        values = None
    if values is None or len(values) not in counts or not all(math.isfinite(v) for v in values):
        expected = " or ".join(str(c) for c in counts)
        raise MjcfError(
            f"{source}: {_where(element)} attribute {attribute}={text!r}: expected {expected} finite number(s)",
            source,
        )
    return values


def _degenerate_axes(values: list[float]) -> bool:
    x = values[:3]
    if len(values) == 4:  # axisangle: the axis, then the angle
        return not any(x)
    y = values[3:]
    cross = (x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0])
    return not any(cross)


def _check_values(element: ET.Element, source: str) -> None:
    for attribute, counts in NUMBERS.get(element.tag, {}).items():
        if element.get(attribute) is None:
            continue
        values = _numbers(element, attribute, counts, source)
        key = (element.tag, attribute)
        if key in _NON_NEGATIVE and min(values) < 0:
            raise MjcfError(f"{source}: {_where(element)} attribute {attribute}={element.get(attribute)!r}: "
                            f"expected numbers >= 0", source)
        if (key in _NON_ZERO or attribute == "zaxis") and not any(values):
            raise MjcfError(f"{source}: {_where(element)} attribute {attribute}={element.get(attribute)!r}: "
                            f"expected a non-zero vector", source)
        if attribute in ("axisangle", "xyaxes") and _degenerate_axes(values):
            raise MjcfError(f"{source}: {_where(element)} attribute {attribute}={element.get(attribute)!r}: "
                            f"expected a non-zero axis (axisangle) or two non-parallel axes (xyaxes)", source)
    for (tag, attribute), allowed in _KEYWORDS.items():
        value = element.get(attribute)
        if element.tag == tag and value is not None and value not in allowed:
            raise MjcfError(f"{source}: {_where(element)} attribute {attribute}={value!r}: expected one of "
                            f"{list(allowed)}", source)


def _check_structure(root: ET.Element, source: str) -> None:
    """Refuse what Pinocchio 4.1's parser would drop or get wrong (:mod:`.mjcf`'s docstring)."""
    if root.find(".//include") is not None:
        raise MjcfError(f"{source}: <include> is not followed by Pinocchio's MJCF parser; inline the included file", source)
    tops = [b.get("name", "?") for wb in root.findall("worldbody") for b in wb.findall("body")]
    if len(tops) > 1:
        raise MjcfError(
            f"{source}: {len(tops)} bodies directly under <worldbody> ({tops}); Pinocchio's MJCF parser keeps only "
            f"the first and drops the others: put them all under one body",
            source,
        )
    for body in root.iter("body"):
        joints = [j.get("name", "?") for j in body if j.tag in ("joint", "freejoint")]
        if len(joints) > 1:
            raise MjcfError(
                f"{source}: body {body.get('name', '?')!r} has {len(joints)} joints {joints}; Pinocchio 4.1 merges "
                f"them into a composite joint whose analytic derivatives are wrong (they disagree with finite "
                f"differences): give each joint its own body (a chain of bodies, the inner ones without mass)",
                source,
            )


def _names(root: ET.Element, source: str) -> tuple[set[str], dict[str, str | None]]:
    """The body names, and site name -> its body's name (None: the world); refuses repeated names."""
    seen: dict[str, set[str]] = {"body": set(), "joint": set(), "site": set()}
    site_body: dict[str, str | None] = {}
    for world in root.findall("worldbody"):
        parents = {child: parent for parent in world.iter() for child in parent}
        for element in world.iter():
            name = element.get("name")
            if element.tag not in seen or name is None:
                continue
            if name in seen[element.tag]:
                raise MjcfError(f"{source}: two <{element.tag}> elements are named {name!r}; a name must be "
                                f"unique (a body subtree repeated?)", source)
            seen[element.tag].add(name)
            if element.tag == "site":
                parent = parents[element]
                site_body[name] = parent.get("name", "?") if parent.tag == "body" else None
    return seen["body"], site_body


@dataclass(frozen=True)
class EqualityEntry:
    """An active ``<connect>`` or ``<weld>``: its kind, label, and the bodies it joins (``None`` is the world)."""

    kind: str
    name: str
    body1: str | None
    body2: str | None


def _ends(item: ET.Element, bodies: set[str], site_body: dict[str, str | None], source: str):
    """(body1, body2) of a connect or weld, its sites resolved to their bodies; None is the world."""
    where = _where(item)
    sites = [item.get("site1"), item.get("site2")]
    if any(s is not None for s in sites):
        if item.get("body1") is not None or item.get("body2") is not None:
            raise MjcfError(f"{source}: {where} gives both bodies and sites; give body1 (and body2) or site1 and site2",
                            source)
        for attribute, site in zip(("site1", "site2"), sites):
            if site is None or site not in site_body:
                raise MjcfError(f"{source}: {where} attribute {attribute}={site!r}: no such site; sites: "
                                f"{sorted(site_body)}", source)
        return site_body[sites[0]], site_body[sites[1]]
    body1, body2 = item.get("body1"), item.get("body2")
    if body1 is None or body1 not in bodies:
        raise MjcfError(f"{source}: {where} attribute body1={body1!r}: no such body; bodies: {sorted(bodies)}", source)
    if body2 is not None and body2 != "world" and body2 not in bodies:
        raise MjcfError(f"{source}: {where} attribute body2={body2!r}: no such body; bodies: {sorted(bodies)}", source)
    if item.tag == "connect" and item.get("anchor") is None:
        raise MjcfError(f"{source}: {where} has no attribute anchor (3 numbers in body1's frame)", source)
    return body1, None if body2 in (None, "world") else body2


def equality_entries(root: ET.Element, source: str) -> tuple[list[EqualityEntry], list[str]]:
    """The active connects and welds in file order, and the tags of the other ``<equality>`` entries.

    Raises
    ------
    MjcfError
        A missing or unknown body or site, both given, a connect without anchor, a
        body constrained to itself.
    """
    bodies, site_body = _names(root, source)
    out, others = [], []
    counts = {"connect": 0, "weld": 0}
    for eq in root.findall("equality"):
        for item in eq:
            if item.tag not in counts:
                others.append(item.tag)
                continue
            counts[item.tag] += 1
            body1, body2 = _ends(item, bodies, site_body, source)
            if body1 == body2:
                raise MjcfError(
                    f"{source}: {_where(item)} constrains body {body1 or 'world'!r} to itself: a constraint joins "
                    f"two different bodies", source)
            if item.get("active", "true").strip().lower() == "false":
                continue
            out.append(EqualityEntry(item.tag, item.get("name") or f"{item.tag}{counts[item.tag]}", body1, body2))
    return out, others


def _check_classes(root: ET.Element, source: str) -> None:
    """Every ``class`` and ``childclass`` names a ``<default class=...>`` (Pinocchio 4.1 raised IndexError)."""
    defined = {"main"} | {d.get("class") for d in root.iter("default") if d.get("class") is not None}
    for element in root.iter():
        if element.tag == "default":
            continue
        for attribute in ("class", "childclass"):
            value = element.get(attribute)
            if value is not None and value not in defined:
                raise MjcfError(f"{source}: {_where(element)} attribute {attribute}={value!r}: no such default "
                                f"class; classes: {sorted(defined)}", source)


def check_mjcf_size(root: ET.Element, source: str) -> None:
    """Refuse a file too large or too deep for Pinocchio's parser (module docstring), walking it without recursion.

    Raises
    ------
    ModelTooLargeError
        More than :data:`MAX_MJCF_BODIES` bodies, or elements nested deeper than :data:`MAX_MJCF_DEPTH`.

    Examples
    --------
    >>> import xml.etree.ElementTree as ET
    >>> from pinlin.model.mjcf_checks import check_mjcf_size
    >>> root = ET.fromstring("<mujoco><worldbody>" + "<body>" * 301 + "</body>" * 301 + "</worldbody></mujoco>")
    >>> try:
    ...     check_mjcf_size(root, "deep.xml")
    ... except pinlin.ModelTooLargeError as exc:
    ...     print(str(exc)[:45])
    deep.xml: 301 bodies; pinlin accepts at most
    """
    bodies, stack = 0, [(root, 1)]
    while stack:
        element, depth = stack.pop()
        if depth > MAX_MJCF_DEPTH:
            raise ModelTooLargeError(
                f"{source}: elements nested more than {MAX_MJCF_DEPTH} deep (MAX_MJCF_DEPTH); Pinocchio's MJCF parser "
                f"recurses along the nesting and would crash or run out of memory",
                required=_parser_bytes(depth), available=_parser_bytes(MAX_MJCF_BODIES))
        bodies += element.tag == "body"
        stack.extend((child, depth + 1) for child in element)
    if bodies > MAX_MJCF_BODIES:
        raise ModelTooLargeError(
            f"{source}: {bodies} bodies; pinlin accepts at most {MAX_MJCF_BODIES} (MAX_MJCF_BODIES): the memory "
            f"Pinocchio's MJCF parser needs grows with the cube of the body count (about 1 GB for 300, "
            f"11 GB for 700)", required=_parser_bytes(bodies), available=_parser_bytes(MAX_MJCF_BODIES))


def check_mjcf(root: ET.Element, source: str) -> None:
    """The size, every attribute pinlin or Pinocchio reads, and the structure (module docstring).

    Raises
    ------
    ModelTooLargeError
        Too many bodies or too deep (:func:`check_mjcf_size`).
    MjcfError
        Naming the element and the attribute at fault.
    """
    check_mjcf_size(root, source)
    _check_structure(root, source)
    _check_classes(root, source)
    for element in root.iter():
        _check_values(element, source)
