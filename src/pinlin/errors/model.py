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

    Examples
    --------
    >>> try:
    ...     raise pinlin.UrdfError("no <robot> element", source="<string>")
    ... except pinlin.InputError as exc:
    ...     print(exc.source)
    <string>
    """

    def __init__(self, message: str, source: str):
        super().__init__(message)
        self.source = source


class PrescribedJointError(InputError):
    """A joint cannot be given a prescribed velocity (it is not 1-DOF, or unknown).

    Examples
    --------
    >>> try:
    ...     raise pinlin.PrescribedJointError("every joint is prescribed: no free degree of freedom is left")
    ... except pinlin.InputError as exc:
    ...     print(exc)
    every joint is prescribed: no free degree of freedom is left
    """


class SceneFileError(InputError):
    """A scene file is missing, unreadable or has a wrong key or value.

    Attributes
    ----------
    path : str
        The scene file.
    key : str or None
        The dotted key at fault, when one is.

    Examples
    --------
    >>> try:
    ...     raise pinlin.SceneFileError("must be positive", "scene.toml", key="spring[1].k")
    ... except pinlin.InputError as exc:
    ...     print((exc.path, exc.key))
    ('scene.toml', 'spring[1].k')
    """

    def __init__(self, message: str, path: str, key: str | None = None):
        where = f"{path}: " + (f"[{key}] " if key else "")
        super().__init__(where + message)
        self.path = path
        self.key = key


class MjcfError(InputError):
    """An MJCF file could not be turned into a usable model (theory: constraints); ``source``: its path.

    Examples
    --------
    >>> try:
    ...     raise pinlin.MjcfError("unsupported joint type 'ball'", source="arm.xml")
    ... except pinlin.InputError as exc:
    ...     print(exc.source)
    arm.xml
    """

    def __init__(self, message: str, source: str):
        super().__init__(message)
        self.source = source


class ConstraintError(InputError):
    """The constraints do not allow what was asked (theory: constraints); ``constraints``: the labels concerned.

    Examples
    --------
    >>> try:
    ...     raise pinlin.ConstraintError("two constraints named 'loop'", constraints=["loop"])
    ... except pinlin.InputError as exc:
    ...     print(exc.constraints)
    ('loop',)
    """

    def __init__(self, message: str, constraints=()):
        super().__init__(message)
        self.constraints = tuple(constraints)


class ConstraintViolationError(ConstraintError):
    """A configuration violates the constraints by ``gap`` [m] (largest distance) and ``rotation_gap`` [rad].

    Examples
    --------
    >>> try:
    ...     raise pinlin.ConstraintViolationError("q is 2 mm off the loop", gap=0.002, constraints=["loop"])
    ... except pinlin.ConstraintError as exc:
    ...     print(exc.gap)
    0.002
    """

    def __init__(self, message: str, gap: float, rotation_gap: float = 0.0, constraints=()):
        super().__init__(message, constraints)
        self.gap, self.rotation_gap = float(gap), float(rotation_gap)


class LoopClosureError(ConstraintViolationError):
    """The constraints could not be closed from the start; ``gap`` is what the closest configuration leaves,
    ``history`` ||Phi|| per step.

    Examples
    --------
    >>> try:
    ...     raise pinlin.LoopClosureError("the loop does not close", 0.3, 0.0, ["loop"], history=[0.5, 0.3])
    ... except pinlin.ConstraintViolationError as exc:
    ...     print(exc.history)
    (0.5, 0.3)
    """

    def __init__(self, message: str, gap: float, rotation_gap: float, constraints, history):
        super().__init__(message, gap, rotation_gap, constraints)
        self.history = tuple(history)


class SingularConstraintError(ConstraintError):
    """J_c has rank ``rank`` at q but ``nearby_rank`` at assembled configurations nearby (a toggle or change point).

    Examples
    --------
    >>> try:
    ...     raise pinlin.SingularConstraintError("a toggle position",
    ...         rank=1, nearby_rank=2, constraints=["loop"])
    ... except pinlin.ConstraintError as exc:
    ...     print((exc.rank, exc.nearby_rank))
    (1, 2)
    """

    def __init__(self, message: str, rank: int, nearby_rank: int, constraints=()):
        super().__init__(message, constraints)
        self.rank, self.nearby_rank = int(rank), int(nearby_rank)


class OverconstrainedError(ConstraintError):
    """The constraints leave no motion: ``rank`` J_c equals ``nv``.

    Examples
    --------
    >>> try:
    ...     raise pinlin.OverconstrainedError("no motion left", rank=2, nv=2)
    ... except pinlin.ConstraintError as exc:
    ...     print((exc.rank, exc.nv))
    (2, 2)
    """

    def __init__(self, message: str, rank: int, nv: int, constraints=()):
        super().__init__(message, constraints)
        self.rank, self.nv = int(rank), int(nv)
