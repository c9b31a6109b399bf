"""Reading the values of a scene file: typed look-ups that name the key at fault (:mod:`.scene_file`).

Every failure is a :class:`~pinlin.SceneFileError` with the file and the dotted key
(``spring[2].stiffness``); numbers are read strictly (TOML strings and booleans are
not numbers, even where numpy would take them).
"""

from __future__ import annotations

import sys

import numpy as np
import pinocchio as pin

from ..errors import SceneFileError

__all__ = ["Reader", "only_numbers", "read_placement", "read_target"]


class Reader:
    """Typed look-ups in the tables of one scene file; failures name the file and the key."""

    def __init__(self, path: str):
        self.path = path

    def fail(self, key: str | None, message: str, exc: BaseException | None = None):
        raise SceneFileError(message, self.path, key) from exc

    def check_keys(self, table: dict, allowed: set, where: str | None) -> None:
        if not isinstance(table, dict):
            self.fail(where, f"expected a table, got {type(table).__name__}")
        unknown = sorted(set(table) - allowed)
        if unknown:
            key = f"{where}.{unknown[0]}" if where else unknown[0]
            self.fail(key, f"unknown key; expected one of {sorted(allowed)}")

    def get(self, table: dict, key: str, where: str, kind, default=None, required=False):
        full = f"{where}.{key}" if where else key
        if key not in table:
            if required:
                self.fail(full, "missing required key")
            return default
        value = table[key]
        if kind is float:
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not abs(value) <= sys.float_info.max:
                self.fail(full, f"expected a finite number, got {value!r:.80}")
            return float(value)
        if kind is bool:
            if not isinstance(value, bool):
                self.fail(full, f"expected true or false, got {value!r}")
            return value
        if kind is str:
            if not isinstance(value, str):
                self.fail(full, f"expected a string, got {value!r}")
            return value
        if kind == "numbers":  # numbers only: numpy would also read "3.0" and true as numbers
            try:
                if not only_numbers(value):
                    raise TypeError
                return np.asarray(value, dtype=float)
            except (TypeError, ValueError, OverflowError):
                self.fail(full, f"expected a number or a (rectangular) list of numbers, got {value!r:.80}")
        return value


def only_numbers(value) -> bool:
    """Whether ``value`` is a number or nested lists of numbers (no strings, booleans or tables)."""
    stack = [value]
    while stack:
        item = stack.pop()
        if isinstance(item, list):
            stack.extend(item)
        elif isinstance(item, bool) or not isinstance(item, (int, float)):
            return False
    return True


def read_placement(r: Reader, value, key: str):
    """A placement from a table { xyz = [m], rpy = [rad] } (URDF's origin convention) or a 4x4 matrix."""
    if isinstance(value, dict):
        r.check_keys(value, {"xyz", "rpy"}, key)
        xyz = r.get(value, "xyz", key, "numbers", np.zeros(3))
        rpy = r.get(value, "rpy", key, "numbers", np.zeros(3))
        for name, arr in (("xyz", xyz), ("rpy", rpy)):
            if arr.shape != (3,) or not np.all(np.isfinite(arr)):
                r.fail(f"{key}.{name}", f"expected 3 finite numbers, got {arr.tolist()}")
        return pin.SE3(pin.rpy.rpyToMatrix(*rpy), xyz)
    if isinstance(value, list):
        try:
            return np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            r.fail(key, f"expected a 4x4 matrix of numbers, got {value!r}")
    r.fail(key, f"expected a table {{ xyz = [...], rpy = [...] }} or a 4x4 matrix, got {value!r}")


def read_target(r: Reader, table: dict, where: str, placement: bool):
    """A frame name, or a world point (3 numbers) / world placement."""
    value = r.get(table, "target", where, None, required=True)
    if isinstance(value, str):
        return value
    if placement:
        return read_placement(r, value, f"{where}.target")
    if not isinstance(value, list):
        r.fail(f"{where}.target", f"expected a frame name or a world point [x, y, z], got {value!r}")
    return r.get(table, "target", where, "numbers")
