"""The pinlin exception hierarchy.

Every error pinlin raises derives from :class:`PinlinError` and from the closest
built-in exception: :class:`ValueError` for bad input, :class:`RuntimeError` for a
computation that failed, :class:`MemoryError` for a problem too large for this
machine.  Subclasses keep the failing data as attributes so that callers can
react without parsing messages (SPEC section 9).
"""

from __future__ import annotations

from collections.abc import Sequence

__all__ = [
    "PinlinError",
    "InputError",
    "UrdfError",
    "NameNotFoundError",
    "JointNotFoundError",
    "FrameNotFoundError",
    "ParameterError",
    "ConfigurationError",
    "NotAnEquilibriumError",
    "SingularMassError",
    "PrescribedJointError",
    "TimePeriodicError",
    "SceneFileError",
    "ComputationError",
    "ConvergenceError",
    "ModelTooLargeError",
    "MissingDependencyError",
    "IntegrationError",
    "IntegrationBudgetError",
    "AccuracyWarning",
    "NotAnEigenvalueError",
    "NotSimpleError",
    "EigenvalueNotIsolatedError",
    "BracketError",
    "BoundaryNotIsolatedError",
    "SystemFunctionError",
    "MjcfError",
    "ConstraintError",
    "ConstraintViolationError",
    "AssemblyError",
    "SingularConstraintError",
    "OverconstrainedError",
]


class PinlinError(Exception):
    """Base class of every error raised by pinlin."""


class InputError(PinlinError, ValueError):
    """The caller passed something pinlin cannot work with."""


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


class NameNotFoundError(InputError):
    """A joint or frame name does not exist; the message lists the valid names.

    Attributes
    ----------
    name : str
        The name that was asked for.
    valid : tuple of str
        The names that exist.
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
    """A joint name does not exist in the model."""

    what = "joint"


class FrameNotFoundError(NameNotFoundError):
    """A frame name does not exist in the model."""

    what = "frame"


class ParameterError(InputError):
    """A numeric parameter is non-finite, of the wrong shape or out of range.

    Attributes
    ----------
    parameter : str
        Name of the offending parameter.
    """

    def __init__(self, parameter: str, message: str):
        super().__init__(f"{parameter}: {message}")
        self.parameter = parameter


class ConfigurationError(InputError):
    """A configuration or velocity vector has the wrong size or is not finite."""


class NotAnEquilibriumError(InputError):
    """``linearize`` was asked to work at a point that is not an equilibrium.

    Attributes
    ----------
    residual : float
        Norm of the generalized-force residual [N or N m].
    relative_residual : float
        The residual divided by the size of the forces that should balance.
    """

    def __init__(self, message: str, residual: float, relative_residual: float):
        super().__init__(message)
        self.residual = residual
        self.relative_residual = relative_residual


class SingularMassError(InputError):
    """The mass matrix is singular or indefinite.

    Attributes
    ----------
    joints : tuple of str
        Joints whose motion carries no inertia.
    """

    def __init__(self, message: str, joints: Sequence[str]):
        super().__init__(message)
        self.joints = tuple(joints)


class PrescribedJointError(InputError):
    """A joint cannot be given a prescribed velocity (it is not 1-DOF, or unknown)."""


class TimePeriodicError(InputError):
    """The linearized equations depend on the angle of a prescribed joint.

    Then they are time-periodic, not constant-coefficient, and pinlin's analysis
    (built on a constant dynamic stiffness) does not apply.

    Attributes
    ----------
    joint : str
        The prescribed joint whose angle changes the equations.
    variation : float
        Largest relative change of M, C, K or the residual over the tested angles.
    """

    def __init__(self, message: str, joint: str, variation: float):
        super().__init__(message)
        self.joint = joint
        self.variation = variation


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


class ComputationError(PinlinError, RuntimeError):
    """A computation failed (did not converge, lost all accuracy)."""


class ConvergenceError(ComputationError):
    """An iteration did not converge.

    Attributes
    ----------
    history : tuple of float
        The residual norm at each iteration.
    """

    def __init__(self, message: str, history: Sequence[float]):
        super().__init__(message)
        self.history = tuple(history)


class ModelTooLargeError(PinlinError, MemoryError):
    """The model would need more memory than this machine can give.

    Attributes
    ----------
    required : int
        Estimated bytes needed.
    available : int
        Bytes pinlin allows itself to use.
    """

    def __init__(self, message: str, required: int, available: int):
        super().__init__(message)
        self.required = required
        self.available = available


class IntegrationError(ComputationError):
    """A time integration (the nonlinear reference simulation) failed.

    Attributes
    ----------
    t_reached : float
        The time [s] up to which the solution is valid.
    """

    def __init__(self, message: str, t_reached: float):
        super().__init__(message)
        self.t_reached = float(t_reached)


class IntegrationBudgetError(IntegrationError):
    """A time integration stopped at its budget of steps or wall time, or would clearly exceed it.

    Attributes: ``t_reached`` [s] (the solution is valid up to it), ``t_end`` [s] (asked for),
    ``steps`` (taken), ``elapsed`` [s] (spent), ``budget`` (``"max_steps"`` or ``"max_time"``).
    """

    def __init__(self, message: str, t_reached: float, t_end: float, steps: int, elapsed: float, budget: str):
        super().__init__(message, t_reached)
        self.t_end, self.steps, self.elapsed, self.budget = float(t_end), int(steps), float(elapsed), budget


class AccuracyWarning(UserWarning):
    """A result was computed but its own error figure exceeds the requested tolerance.

    The result is still returned, with the error figure attached; the warning
    says which figure and by how much (STYLE: never silently inaccurate).
    """


class NotAnEigenvalueError(InputError):
    """A point given as an eigenvalue (a root of det L) is not one, to the stated tolerance.

    Attributes
    ----------
    lam : complex
        The point [1/s].
    distance : float
        How far it is from being a root, in the measure the message names
        (relative smallest singular value of L, or relative distance to the
        nearest eigenvalue).
    """

    def __init__(self, message: str, lam: complex, distance: float):
        super().__init__(message)
        self.lam = complex(lam)
        self.distance = float(distance)


class NotSimpleError(InputError):
    """A method needs a simple root or a simple dynamic stiffness, and this one is not.

    Attributes
    ----------
    lam : complex or None
        The offending eigenvalue [1/s], when there is one.
    measure : float
        The quantity that failed the test (named in the message).
    """

    def __init__(self, message: str, lam: complex | None = None, measure: float = float("nan")):
        super().__init__(message)
        self.lam = None if lam is None else complex(lam)
        self.measure = float(measure)


class EigenvalueNotIsolatedError(ComputationError):
    """No contour around an eigenvalue separates it from the rest of the spectrum.

    Attributes
    ----------
    lam : complex
        The eigenvalue [1/s].
    inner : float
        Radius [1/s] of the cluster taken as the eigenvalue itself.
    outer : float
        Radius [1/s] at which the next eigenvalue was found.
    """

    def __init__(self, message: str, lam: complex, inner: float, outer: float):
        super().__init__(message)
        self.lam = complex(lam)
        self.inner = float(inner)
        self.outer = float(outer)


class MissingDependencyError(PinlinError, ImportError):
    """An optional dependency (matplotlib for plots, ...) is not installed; the message says which extra to install."""


class BracketError(InputError):
    """A bracket cannot hold a stability boundary (SPEC 12): its ends have the same verdict class, one is
    "undecided", or they are not two distinct finite numbers; ``bracket``, ``verdicts`` (the kinds at its ends)."""

    def __init__(self, message: str, bracket, verdicts=()):
        super().__init__(message)
        self.bracket, self.verdicts = tuple(bracket), tuple(verdicts)


class BoundaryNotIsolatedError(InputError):
    """The verdict changes, but not at an isolated parameter value (SPEC 12): it stays "undecided" over an
    interval far wider than rounding; ``interval``: where."""

    def __init__(self, message: str, interval):
        super().__init__(message)
        self.interval = tuple(float(x) for x in interval)


class SystemFunctionError(InputError):
    """A user's ``func(p) -> LinearizedSystem`` raised (chained as ``__cause__``), returned something else, or
    systems of different sizes (SPEC 12); ``p``: the parameter value."""

    def __init__(self, message: str, p: float):
        super().__init__(message)
        self.p = float(p)


class MjcfError(InputError):
    """An MJCF file could not be turned into a usable model (SPEC section 10); ``source``: its path."""

    def __init__(self, message: str, source: str):
        super().__init__(message)
        self.source = source


class ConstraintError(InputError):
    """The constraints do not allow what was asked (SPEC section 10); ``constraints``: the labels concerned."""

    def __init__(self, message: str, constraints=()):
        super().__init__(message)
        self.constraints = tuple(constraints)


class ConstraintViolationError(ConstraintError):
    """A configuration violates the constraints by ``gap`` [m] (largest distance) and ``rotation_gap`` [rad]."""

    def __init__(self, message: str, gap: float, rotation_gap: float = 0.0, constraints=()):
        super().__init__(message, constraints)
        self.gap, self.rotation_gap = float(gap), float(rotation_gap)


class AssemblyError(ConstraintViolationError):
    """Assembly could not close the constraints; ``gap`` is what the closest configuration leaves, ``history`` ||Phi||."""

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
