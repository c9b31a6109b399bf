"""The roots of the hierarchy and the errors every stage can raise: bad parameters, names not found, missing
optional dependencies, models too large for this machine; the accuracy warning."""

from __future__ import annotations

import inspect
import warnings
from collections.abc import Sequence
from pathlib import Path

__all__ = ["PinlinError", "InputError", "NameNotFoundError", "JointNotFoundError", "FrameNotFoundError", "ParameterError", "ConfigurationError", "ComputationError", "ModelTooLargeError", "AccuracyWarning", "MissingDependencyError", "warn_user"]


def _rebuild(cls, args, state):
    """Unpickle an error without calling its ``__init__`` (whose signature varies by subclass)."""
    obj = cls.__new__(cls)
    obj.args = args
    obj.__dict__.update(state)
    return obj


class PinlinError(Exception):
    """Base class of every error raised by pinlin.

    Examples
    --------
    >>> try:
    ...     raise pinlin.ParameterError("rtol", "must be positive")
    ... except pinlin.PinlinError as exc:
    ...     print(type(exc).__name__)
    ParameterError
    """

    def __reduce__(self):
        # Subclasses take their data as constructor arguments, so Exception's default
        # pickling (cls(*args)) would fail; rebuild from args and attributes instead, so
        # that errors cross process pools (pinlin.sweep with a ProcessPoolExecutor, Dask).
        return (_rebuild, (type(self), self.args, dict(self.__dict__)))


class InputError(PinlinError, ValueError):
    """The caller passed something pinlin cannot work with.

    Examples
    --------
    >>> try:
    ...     raise pinlin.InputError("q has 3 entries; the robot has nq = 2")
    ... except ValueError as exc:
    ...     print(exc)
    q has 3 entries; the robot has nq = 2
    """


class NameNotFoundError(InputError):
    """A joint or frame name does not exist; the message lists the valid names.

    Attributes
    ----------
    name : str
        The name that was asked for.
    valid : tuple of str
        The names that exist.

    Examples
    --------
    >>> try:
    ...     raise pinlin.NameNotFoundError("knee", ["hip", "ankle"])
    ... except pinlin.InputError as exc:
    ...     print(exc.valid)
    ('hip', 'ankle')
    """

    what = "name"

    def __init__(self, name: str, valid: Sequence[str], context: str = ""):
        self.name = name
        self.valid = tuple(valid)
        shown = ", ".join(repr(v) for v in self.valid[:40])
        if len(self.valid) > 40:
            shown += f", ... ({len(self.valid) - 40} more)"
        where = f" in {context}" if context else ""
        super().__init__(f"unknown {self.what} {name!r}{where}; valid {self.what}s: {shown}")


class JointNotFoundError(NameNotFoundError):
    """A joint name does not exist in the model.

    Examples
    --------
    >>> try:
    ...     raise pinlin.JointNotFoundError("knee", ["joint1", "joint2"])
    ... except pinlin.NameNotFoundError as exc:
    ...     print(exc)
    unknown joint 'knee'; valid joints: 'joint1', 'joint2'
    """

    what = "joint"


class FrameNotFoundError(NameNotFoundError):
    """A frame name does not exist in the model.

    Examples
    --------
    >>> try:
    ...     raise pinlin.FrameNotFoundError("hand", ["base", "tip"], context="double_pendulum.urdf")
    ... except pinlin.NameNotFoundError as exc:
    ...     print(exc)
    unknown frame 'hand' in double_pendulum.urdf; valid frames: 'base', 'tip'
    """

    what = "frame"


class ParameterError(InputError):
    """A numeric parameter is non-finite, of the wrong shape or out of range.

    Attributes
    ----------
    parameter : str
        Name of the offending parameter.

    Examples
    --------
    >>> try:
    ...     raise pinlin.ParameterError("rtol", "must be positive, got -1")
    ... except pinlin.InputError as exc:
    ...     print(exc.parameter)
    rtol
    """

    def __init__(self, parameter: str, message: str):
        super().__init__(f"{parameter}: {message}")
        self.parameter = parameter


class ConfigurationError(InputError):
    """A configuration or velocity vector has the wrong size or is not finite.

    Examples
    --------
    >>> try:
    ...     raise pinlin.ConfigurationError("q must be 2 finite numbers (nq), got shape (3,)")
    ... except pinlin.InputError as exc:
    ...     print(exc)
    q must be 2 finite numbers (nq), got shape (3,)
    """


class ComputationError(PinlinError, RuntimeError):
    """A computation failed (did not converge, lost all accuracy).

    Examples
    --------
    >>> try:
    ...     raise pinlin.ComputationError("the eigenvalues overflow")
    ... except RuntimeError as exc:
    ...     print(exc)
    the eigenvalues overflow
    """


class ModelTooLargeError(PinlinError, MemoryError):
    """The model would need more memory than this machine can give.

    Attributes
    ----------
    required : int
        Estimated bytes needed.
    available : int
        Bytes pinlin allows itself to use.

    Examples
    --------
    >>> try:
    ...     raise pinlin.ModelTooLargeError("needs 64 GB", required=64 * 2**30, available=8 * 2**30)
    ... except MemoryError as exc:
    ...     print(exc.required // exc.available)
    8
    """

    def __init__(self, message: str, required: int, available: int):
        super().__init__(message)
        self.required = required
        self.available = available


class AccuracyWarning(UserWarning):
    """A result was computed but its own error figure exceeds the requested tolerance.

    The result is still returned, with the error figure attached; the warning
    says which figure and by how much (never silently inaccurate).

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn("defect 1e-06 above rtol 1e-09", pinlin.AccuracyWarning)
    >>> issubclass(caught[0].category, UserWarning), str(caught[0].message)
    (True, 'defect 1e-06 above rtol 1e-09')
    """


class MissingDependencyError(PinlinError, ImportError):
    """An optional dependency (matplotlib for plots, ...) is not installed; the message says which extra to install.

    Examples
    --------
    >>> try:
    ...     raise pinlin.MissingDependencyError("plots need matplotlib: pip install pinlin[plot]")
    ... except ImportError as exc:
    ...     print(exc)
    plots need matplotlib: pip install pinlin[plot]
    """


#: The installed package: warnings are attributed to the first frame outside it.
PACKAGE_DIR = str(Path(__file__).resolve().parent.parent)


def warn_user(message: str, category: type[Warning] = UserWarning) -> None:
    """Warn at the caller's line: the first frame outside pinlin, however many pinlin frames lie between
    (decorators, helpers), as ``warnings.warn(..., skip_file_prefixes=...)`` does from Python 3.12.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_user("the result is rough", AccuracyWarning)
    >>> caught[0].category.__name__, caught[0].filename.startswith("<doctest")  # this line, not pinlin's
    ('AccuracyWarning', True)
    """
    frame, level = inspect.currentframe(), 1
    while frame is not None and str(Path(frame.f_code.co_filename).resolve()).startswith(PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    del frame
    warnings.warn(message, category, stacklevel=level)
