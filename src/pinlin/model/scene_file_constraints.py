"""Reading a scene file's ``[[constraint]]`` tables (:mod:`.scene_file`): point and frame constraints, contacts."""

from __future__ import annotations

import numpy as np

from ..errors import PinlinError, SceneFileError
from .constraints import FrameConstraint, PointConstraint
from .scene_file_values import Reader, read_target

__all__ = ["read_constraints"]


def read_constraints(r: Reader, doc: dict, robot, keys) -> list | None:
    """The ``[[constraint]]`` tables, or None when there are none (the robot's own constraints stay); ``keys``
    are the keys a constraint table may have."""
    tables = doc.get("constraint")
    if tables is None:
        return None
    if not isinstance(tables, list):
        r.fail("constraint", "use [[constraint]] (an array of tables), one per constraint")
    out = []
    for i, t in enumerate(tables, start=1):
        where = f"constraint[{i}]"
        r.check_keys(t, keys, where)
        kind = r.get(t, "type", where, str, "point")
        if kind not in ("point", "frame"):
            r.fail(f"{where}.type", f"expected 'point' or 'frame', got {kind!r}")
        if kind == "frame" and any(k in t for k in ("contact", "friction", "normal")):
            r.fail(where, "contact, friction and normal apply to point constraints only")
        try:
            frame = r.get(t, "frame", where, str, required=True)
            goal = read_target(r, t, where, placement=kind == "frame")
            name = r.get(t, "name", where, str)
            if kind == "frame":
                constraint = FrameConstraint(frame, goal, name=name)
            else:
                constraint = PointConstraint(
                    frame,
                    goal,
                    contact=r.get(t, "contact", where, bool, False),
                    friction=r.get(t, "friction", where, float),
                    normal=r.get(t, "normal", where, "numbers", np.array([0.0, 0.0, 1.0])),
                    name=name,
                )
            constraint.check(robot)
        except SceneFileError:
            raise
        except PinlinError as exc:
            r.fail(where, str(exc), exc)
        out.append(constraint)
    return out
