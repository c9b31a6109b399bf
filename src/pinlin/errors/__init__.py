"""The pinlin exception hierarchy (one module per stage: :mod:`.base`, :mod:`.model`, :mod:`.analysis`).

Every error pinlin raises derives from :class:`PinlinError` and from the closest
built-in exception: :class:`ValueError` for bad input, :class:`RuntimeError` for a
computation that failed, :class:`MemoryError` for a problem too large for this
machine.  Subclasses keep the failing data as attributes so that callers can
react without parsing messages (theory: conventions).
"""

from __future__ import annotations

from .analysis import (
    BoundaryNotIsolatedError,
    BracketError,
    ConvergenceError,
    EigenvalueNotIsolatedError,
    IntegrationBudgetError,
    IntegrationError,
    NotAnEigenvalueError,
    NotAnEquilibriumError,
    NotSimpleError,
    SingularMassError,
    SystemFunctionError,
    TimePeriodicError,
)
from .base import (
    AccuracyWarning,
    ComputationError,
    ConfigurationError,
    FrameNotFoundError,
    InputError,
    JointNotFoundError,
    MissingDependencyError,
    ModelTooLargeError,
    NameNotFoundError,
    ParameterError,
    PinlinError,
)
from .model import (
    AssemblyError,
    ConstraintError,
    ConstraintViolationError,
    LoopClosureError,
    MjcfError,
    OverconstrainedError,
    PrescribedJointError,
    SceneFileError,
    SingularConstraintError,
    UrdfError,
)
from .periodic import MultibladeNotExactError, SamplingError
from .periodic_motion import NoPeriodError, OrbitLimitError, PeriodicOrbitError, QuasiPeriodicError

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
    "LoopClosureError",
    "SingularConstraintError",
    "OverconstrainedError",
    "QuasiPeriodicError",
    "MultibladeNotExactError",
    "SamplingError",
    "NoPeriodError",
    "PeriodicOrbitError",
    "OrbitLimitError",
]


