"""What pinlin checks in a URDF's XML before Pinocchio's parser sees it.

- well-formed XML with a ``<robot>`` root and a ``<link>``;
- a tree: unique link and joint names, at most one parent joint per link;
- a size Pinocchio can parse and hold: :func:`check_urdf_size` counts the links and
  the depth of the tree and estimates ``nv`` from the joint types, then refuses a
  model deeper than :data:`MAX_URDF_DEPTH` (urdfdom and Pinocchio walk the tree
  recursively: a 4000-link chain overflows an 8 MiB stack and kills the process) or
  whose ``pin.Data`` would not fit (:func:`~pinlin.model.memory.check_memory` on the
  estimated ``nv``), with :class:`~pinlin.ModelTooLargeError`, before any parsing;
- inertial numbers (:func:`~pinlin.model.inertia.check_inertials`).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from ..errors import ModelTooLargeError, UrdfError
from .inertia import check_inertials
from .memory import check_memory, pinocchio_data_bytes

__all__ = ["check_urdf_xml", "check_urdf_size", "count_links", "MAX_URDF_DEPTH", "MAX_URDF_LINKS", "JOINT_NV"]

#: Deepest chain of links accepted.  Pinocchio 4.1 and urdfdom recurse once per level of
#: the tree; measured on an 8 MiB main-thread stack, a chain of 3000 links parses and one of
#: 4000 crashes the process.  1000 keeps a margin of 3 for smaller thread stacks, and a
#: model that deep would need nv >= 1000, 72 GB for Pinocchio's data
#: (:func:`~pinlin.model.memory.pinocchio_data_bytes`): beyond any memory guard's budget.
MAX_URDF_DEPTH = 1000

#: Most links accepted: 75 times the largest robot of example-robot-data (tiago_dual, 130
#: links).  Counted while streaming through the XML (:func:`count_links`), so a file of
#: 100000 links (55 MB) is refused after reading its first 10001 links, not after
#: building its whole element tree (seconds, and hundreds of MB).
MAX_URDF_LINKS = 10_000

#: Velocity coordinates of each URDF joint type.
JOINT_NV = {"revolute": 1, "continuous": 1, "prismatic": 1, "fixed": 0, "floating": 6, "planar": 3}


def check_urdf_xml(text: str, source: str, *, free_flyer: bool = False,
                   memory_limit: int | None = None) -> dict[str, str]:
    """Check the XML of a URDF before parsing (module docstring).

    Returns
    -------
    dict of str to (str or None)
        Every link with an ``<inertial>`` -> what is physically impossible about its
        own tensor, or None (:func:`~pinlin.model.inertia.check_inertials`).

    Raises
    ------
    UrdfError
        Malformed XML, not a ``<robot>``, no ``<link>``, not a tree, inertial numbers
        that are not finite or a negative mass.
    ModelTooLargeError
        Deeper than :data:`MAX_URDF_DEPTH`, or too many degrees of freedom for memory.
    """
    count_links(text, source)
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise UrdfError(f"{source}: malformed XML ({exc})", source) from None
    if root.tag != "robot":
        raise UrdfError(f"{source}: root element is <{root.tag}>, expected <robot>", source)
    if root.find("link") is None:
        raise UrdfError(f"{source}: the URDF has no <link>", source)
    parents = _check_tree(root, source)
    check_urdf_size(root, parents, source, free_flyer=free_flyer, memory_limit=memory_limit)
    return check_inertials(root, source)


def count_links(text: str, source: str, limit: int = MAX_URDF_LINKS) -> int:
    """The number of ``<link>`` children of the root, counted while streaming; refused past ``limit``.

    Malformed XML stops the count where it is (:func:`check_urdf_xml` then says why).

    Raises
    ------
    ModelTooLargeError
        More than ``limit`` links.
    """
    parser = ET.XMLPullParser(events=("start", "end"))
    depth = count = 0
    for start in range(0, len(text), 1 << 16):
        try:
            parser.feed(text[start:start + (1 << 16)])
            events = list(parser.read_events())
        except ET.ParseError:
            return count
        for event, element in events:
            if event == "start":
                depth += 1
                count += depth == 2 and element.tag == "link"
            else:
                depth -= 1
                element.clear()
        if count > limit:
            raise ModelTooLargeError(
                f"{source}: the URDF has more than {limit} links; pinlin refuses it before building its element tree "
                f"or parsing it (MAX_URDF_LINKS, 75 times the largest robot of example-robot-data)",
                required=pinocchio_data_bytes(count),
                available=pinocchio_data_bytes(limit),
            )
    return count


def _check_tree(root: ET.Element, source: str) -> dict[str, str]:
    """Unique link and joint names, at most one parent joint per link; returns child link -> parent link.

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
    joint_of: dict[str, str] = {}
    parents: dict[str, str] = {}
    for joint in root.findall("joint"):
        child, parent = joint.find("child"), joint.find("parent")
        link = None if child is None else child.get("link")
        if link in joint_of:
            raise UrdfError(
                f"{source}: link {link!r} is the child of two joints ({joint_of[link]!r} and "
                f"{joint.get('name')!r}); a URDF is a tree: close loops with constraints "
                f"(pinlin.PointConstraint, or an MJCF <equality>)",
                source,
            )
        if link is not None:
            joint_of[link] = joint.get("name")
            parents[link] = None if parent is None else parent.get("link")
    return parents


def _depth(parents: dict[str, str]) -> int:
    """Longest chain of links (a loop, refused by the parser later, counts as its length)."""
    depth: dict[str, int] = {}
    for start in parents:
        path, on_path, link = [], set(), start
        while link in parents and link not in depth and link not in on_path:
            path.append(link)
            on_path.add(link)
            link = parents[link]
        base = depth.get(link, 0)
        for k, name in enumerate(reversed(path), start=1):
            depth[name] = base + k
    return max(depth.values(), default=0)


def check_urdf_size(root: ET.Element, parents: dict[str, str], source: str, *, free_flyer: bool = False,
                    memory_limit: int | None = None) -> None:
    """Refuse, before parsing, a URDF too deep for the parser or too large for memory.

    Raises
    ------
    ModelTooLargeError
        The tree is deeper than :data:`MAX_URDF_DEPTH`, or ``pin.Data`` for the
        estimated ``nv`` (:data:`JOINT_NV` summed, plus 6 for a free flyer) would not
        fit (:func:`~pinlin.model.memory.check_memory`).
    """
    depth = _depth(parents)
    nv = sum(JOINT_NV.get(j.get("type", ""), 1) for j in root.findall("joint")) + (6 if free_flyer else 0)
    if depth > MAX_URDF_DEPTH:
        raise ModelTooLargeError(
            f"{source}: the URDF's tree is {depth} links deep ({len(root.findall('link'))} links); "
            f"Pinocchio's parser recurses once per level and overflows the stack near 4000 levels, so pinlin "
            f"accepts at most {MAX_URDF_DEPTH} (nv = {nv} would also need about "
            f"{pinocchio_data_bytes(nv) / 2**30:.3g} GiB for Pinocchio's data)",
            required=pinocchio_data_bytes(nv),
            available=pinocchio_data_bytes(MAX_URDF_DEPTH),
        )
    check_memory(nv, memory_limit, source)
