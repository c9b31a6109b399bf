"""Loading an MJCF (MuJoCo) model with its closed loops into a :class:`Robot` (theory: constraints).

Pinocchio's ``buildModelAndConstraintsFromMJCF`` builds the kinematic tree and
turns the ``<equality>`` entries into constraint models: ``<connect>`` into a
``PointAnchorConstraintModel``, ``<weld>`` into a ``FrameAnchorConstraintModel``,
each with a placement on two joints (the world for a missing ``body2``).
:func:`load_mjcf` adds an operational frame at each of these placements
(``<name>_1`` on body1's side, ``<name>_2`` on body2's) and returns a Robot whose
``constraints`` are the matching :class:`~pinlin.PointConstraint` (connect) and
:class:`~pinlin.FrameConstraint` (weld), world targets as fixed points or
placements.  No geometry is built and no mesh is opened.

What pinlin refuses rather than get wrong (Pinocchio 4.1's MJCF parser):

- several bodies directly under ``<worldbody>``: the parser keeps only the first
  one and drops the others silently; put them under one body;
- a body with several joints: the parser merges them into a composite joint,
  whose analytic derivatives in Pinocchio 4.1 disagree with finite differences
  (checked: 10 % errors in dtau/dq); give each joint its own body;
- ``<include>``: not followed by the parser;
- more than :data:`~.mjcf_checks.MAX_MJCF_BODIES` bodies or nesting deeper than
  :data:`~.mjcf_checks.MAX_MJCF_DEPTH` (a :class:`~pinlin.ModelTooLargeError`): the
  parser recurses along the tree and its memory grows with the cube of the body count.

Other ``<equality>`` kinds (joint, tendon, flex couplings) are not constraints
pinlin models: they are left out with a warning; inactive entries
(``active="false"``) are left out as MuJoCo starts them disabled.  Pinocchio's
PyPI wheel has no SDF parser: convert SDF models to URDF or MJCF.
"""

from __future__ import annotations

import os
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import MjcfError
from .constraints import Constraint, FrameConstraint, PointConstraint
from .inertia import check_bodies, check_inertia_option
from .loading import reduce_model
from .parser_output import captured_stderr
from .memory import check_memory
from .mjcf_checks import EqualityEntry, check_mjcf, equality_entries
from .robot import Robot

__all__ = ["load_mjcf", "MJCF_CONSTRAINTS"]

#: The ``<equality>`` kinds that become pinlin constraints.
MJCF_CONSTRAINTS = {"connect": PointConstraint, "weld": FrameConstraint}


def _read(path: Path, source: str) -> ET.Element:
    if not path.is_file():
        raise MjcfError(f"MJCF file not found: {source}", source)
    try:
        root = ET.fromstring(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise MjcfError(f"cannot read MJCF file {source}: {exc}", source) from None
    except ET.ParseError as exc:
        raise MjcfError(f"{source}: malformed XML ({exc})", source) from None
    if root.tag != "mujoco":
        raise MjcfError(f"{source}: root element is <{root.tag}>, expected <mujoco>", source)
    return root


def _equalities(root: ET.Element, source: str) -> list[EqualityEntry]:
    """The active connects and welds (:func:`.mjcf_checks.equality_entries`); other kinds are said, left out."""
    entries, others = equality_entries(root, source)
    for tag in others:
        warnings.warn(
            f"{source}: <equality><{tag}> is not a constraint pinlin models (only <connect> and <weld>); it is left out",
            UserWarning,
            stacklevel=3,
        )
    return entries


def _body_joint(model: pin.Model, body: str | None) -> int:
    if body is None or body == "world":
        return 0
    fid = model.getFrameId(body, pin.FrameType.BODY)
    return model.frames[fid].parentJoint if fid < len(model.frames) else -1


def _frame_name(model: pin.Model, wanted: str) -> str:
    name, k = wanted, 1
    while model.existFrame(name):
        k += 1
        name = f"{wanted}_{k}"
    return name


def _constraints(model: pin.Model, points, frames, entries, source: str) -> list[Constraint]:
    """Match Pinocchio's constraint models to the file's entries, add their frames, build pinlin constraints."""
    pool = {"connect": list(points), "weld": list(frames)}
    out: list[Constraint] = []
    for entry in entries:
        kind, name, body1, body2 = entry.kind, entry.name, entry.body1, entry.body2
        j1, j2 = _body_joint(model, body1), _body_joint(model, body2)
        if j1 == j2:
            raise MjcfError(
                f"{source}: <{kind} name={name!r}> joins bodies {body1 or 'world'!r} and {body2 or 'world'!r}, which "
                f"move together (no joint between them): the constraint would hold a body to itself", source)
        match = next((c for c in pool[kind] if (c.joint1_id, c.joint2_id) == (j1, j2)), None)
        if match is None:
            raise MjcfError(
                f"{source}: Pinocchio built no constraint for <{kind} name={name!r} body1={body1!r} body2={body2!r}>",
                source,
            )
        pool[kind].remove(match)
        placements = np.concatenate([match.joint1_placement.homogeneous.ravel(), match.joint2_placement.homogeneous.ravel()])
        if not np.all(np.isfinite(placements)):  # never reached after check_mjcf; kept so nothing uninitialized passes
            raise MjcfError(f"{source}: Pinocchio built <{kind} name={name!r}> with non-finite placements", source)
        fid = model.addFrame(
            pin.Frame(_frame_name(model, f"{name}_1"), match.joint1_id, match.joint1_placement, pin.FrameType.OP_FRAME)
        )
        frame = model.frames[fid].name
        if match.joint2_id == 0:
            M2 = match.joint2_placement
            target = M2.translation.copy() if kind == "connect" else M2.homogeneous.copy()
        else:
            fid2 = model.addFrame(
                pin.Frame(_frame_name(model, f"{name}_2"), match.joint2_id, match.joint2_placement, pin.FrameType.OP_FRAME)
            )
            target = model.frames[fid2].name
        out.append(MJCF_CONSTRAINTS[kind](frame, target, name=name))
    return out


def load_mjcf(
    path: str | os.PathLike,
    *,
    free_flyer: bool = False,
    locked: Sequence[str] | Mapping[str, object] | None = None,
    memory_limit: int | None = None,
    inertia: str = "check",
) -> Robot:
    """Load an MJCF file as a :class:`Robot` whose ``constraints`` are its ``<connect>`` and ``<weld>``.

    Parameters
    ----------
    path : path-like
        The MJCF file.  Meshes it names are never opened.  The constraints must be
        satisfied in the file's own configuration (q = 0), as MuJoCo requires:
        that is where Pinocchio places each connect's and weld's second anchor.
    free_flyer : bool
        Mount the root body on a free-flyer joint.
    locked : sequence of str or mapping, optional
        Joints to remove through Pinocchio's reduced model (as in :func:`pinlin.load_urdf`).
    memory_limit : int, optional
        Bytes allowed for the peak of Pinocchio's data.
    inertia : {"check", "repair"}
        As in :func:`pinlin.load_urdf`: each body of the model (bodies without a
        joint merged into their parent's) must be physically possible, or is
        repaired to the nearest valid tensor with an :class:`~pinlin.InertiaWarning`.

    Returns
    -------
    Robot
        ``robot.constraints``: one :class:`~pinlin.PointConstraint` per ``<connect>``
        and one :class:`~pinlin.FrameConstraint` per ``<weld>``, named after the
        entry's ``name`` (else ``connect1``, ``weld1``, ...), between added frames
        ``<name>_1`` and ``<name>_2`` or a fixed world target.

    Raises
    ------
    MjcfError
        Missing file, malformed XML, a model Pinocchio cannot parse or would
        parse wrongly (see the module docstring), an attribute that is not what
        it must be (:mod:`.mjcf_checks`: the message names element and attribute),
        no movable joint, a body whose inertia is impossible (``inertia="check"``).
    JointNotFoundError
        A locked joint does not exist.
    ModelTooLargeError
        More bodies or deeper nesting than Pinocchio's parser handles (:data:`.mjcf_checks.MAX_MJCF_BODIES`,
        :data:`.mjcf_checks.MAX_MJCF_DEPTH`, checked before it reads the file), or Pinocchio's data would
        not fit in memory.
    ParameterError
        ``inertia`` is not "check" or "repair".

    Examples
    --------
    >>> robot = pinlin.load_mjcf(pinlin.data_path("mjcf/four_bar.xml"))
    >>> robot.nv, len(robot.constraints)
    (3, 1)
    """
    source = os.fspath(path)
    check_inertia_option(inertia)
    root = _read(Path(source), source)
    check_mjcf(root, source)
    entries = _equalities(root, source)
    with captured_stderr() as messages:
        try:
            if free_flyer:
                model, points, frames = pin.buildModelAndConstraintsFromMJCF(source, pin.JointModelFreeFlyer())
            else:
                model, points, frames = pin.buildModelAndConstraintsFromMJCF(source)
            error = None
        except (ValueError, RuntimeError, IndexError, KeyError) as exc:  # C++ out_of_range arrives as IndexError
            error = exc
    if error is not None:
        detail = " ".join(m for m in messages if m) or f"{type(error).__name__}: {error}"
        raise MjcfError(f"{source}: not a valid MJCF model for Pinocchio ({detail})", source) from None
    said = " ".join(" ".join(m for m in messages if m).split())
    if said:  # what the parser printed while building a model it did build: never dropped
        warnings.warn(f"{source}: the MJCF parser says: {said}", UserWarning, stacklevel=2)
    if model.nv == 0:
        raise MjcfError(f"{source}: the MJCF model has no movable joint; nothing moves", source)
    with_inertial = {b.get("name"): None for b in root.iter("body") if b.find("inertial") is not None}
    check_bodies(model, with_inertial, source, inertia, error=MjcfError)
    constraints = _constraints(model, points, frames, entries, source)
    model = reduce_model(model, locked, source)
    check_memory(model.nv, memory_limit, source)
    return Robot(model, source, constraints=constraints)
