"""Errors of the model stage: URDF and MJCF files, scene files, prescribed joints, constraints."""

from __future__ import annotations

from .base import InputError

__all__ = ["UrdfError", "PrescribedJointError", "SceneFileError", "MjcfError", "ConstraintError", "ConstraintViolationError", "LoopClosureError", "SingularConstraintError", "OverconstrainedError"]


class UrdfError(InputError):
    """A URDF file or string could not be turned into a usable model.

    Attributes
    ----------
    source : str
        The path, or ``"<string>"`` for URDF text.
    """

    def __init__(self, message: str, source: str):
        super().__init__(message)
        self.source = source


class PrescribedJointError(InputError):
    """A joint cannot be given a prescribed velocity (it is not 1-DOF, or unknown)."""


class SceneFileError(InputError):
    """A scene file is missing, unreadable or has a wrong key or value.

    Attributes
    ----------
    path : str
        The scene file.
    key : str or None
        The dotted key at fault, when one is.
    """

    def __init__(self, message: str, path: str, key: str | None = None):
        where = f"{path}: " + (f"[{key}] " if key else "")
        super().__init__(where + message)
        self.path = path
        self.key = key


class MjcfError(InputError):
    """An MJCF file could not be turned into a usable model (theory: constraints); ``source``: its path."""

    def __init__(self, message: str, source: str):
        super().__init__(message)
        self.source = source


class ConstraintError(InputError):
    """The constraints do not allow what was asked (theory: constraints); ``constraints``: the labels concerned."""

    def __init__(self, message: str, constraints=()):
        super().__init__(message)
        self.constraints = tuple(constraints)


class ConstraintViolationError(ConstraintError):
    """A configuration violates the constraints by ``gap`` [m] (largest distance) and ``rotation_gap`` [rad]."""

    def __init__(self, message: str, gap: float, rotation_gap: float = 0.0, constraints=()):
        super().__init__(message, constraints)
        self.gap, self.rotation_gap = float(gap), float(rotation_gap)


class LoopClosureError(ConstraintViolationError):
    """The constraints could not be closed from the start; ``gap`` is what the closest configuration leaves,
    ``history`` ||Phi|| per step."""

    def __init__(self, message: str, gap: float, rotation_gap: float, constraints, history):
        super().__init__(message, gap, rotation_gap, constraints)
        self.history = tuple(history)


class SingularConstraintError(ConstraintError):
    """J_c has rank ``rank`` at q but ``nearby_rank`` at assembled configurations nearby (a toggle or change point)."""

    def __init__(self, message: str, rank: int, nearby_rank: int, constraints=()):
        super().__init__(message, constraints)
        self.rank, self.nearby_rank = int(rank), int(nearby_rank)


class OverconstrainedError(ConstraintError):
    """The constraints leave no motion: ``rank`` J_c equals ``nv``."""

    def __init__(self, message: str, rank: int, nv: int, constraints=()):
        super().__init__(message, constraints)
        self.rank, self.nv = int(rank), int(nv)
