"""The pinlin exception hierarchy (one module per stage: :mod:`.base`, :mod:`.model`, :mod:`.analysis`,
:mod:`.periodic`, :mod:`.periodic_motion`; every deprecation in :mod:`.deprecated`).

Every error pinlin raises derives from :class:`PinlinError` and from the closest
built-in exception: :class:`ValueError` for bad input, :class:`RuntimeError` for a
computation that failed, :class:`MemoryError` for a problem too large for this
machine.  Subclasses keep the failing data as attributes so that callers can
react without parsing messages (theory: conventions).

A class exists because a caller catches it apart from its parent or because it
carries data; the others are merged into their parents:

==============================  ==========================================================================
class                           why it exists
==============================  ==========================================================================
``PinlinError``                 the root: ``except PinlinError`` catches everything pinlin raises
``InputError``                  bad input (``ValueError``): the command line exits with code 2
``ComputationError``            a failed computation (``RuntimeError``): exit code 3
``NameNotFoundError``           ``name``, ``valid``
``JointNotFoundError``          ``name``, ``valid`` (the joint names); a misspelt joint apart from a frame
``FrameNotFoundError``          ``name``, ``valid`` (the frame names)
``ParameterError``              ``parameter``
``ConfigurationError``          caught apart: a scene-file report blames its ``start`` key
``PrescribedJointError``        caught apart: a scene-file report blames its ``prescribed`` key
``ModelTooLargeError``          ``required``, ``available`` (``MemoryError``)
``MissingDependencyError``      caught apart (``ImportError``): which optional extra to install
``AccuracyWarning``             filtered apart (a warning): a result beyond its tolerance
``UrdfError``, ``MjcfError``    ``source``
``SceneFileError``              ``path``, ``key``
``ConstraintError``             ``constraints``; caught apart: a report blames ``constraint``
``ConstraintViolationError``    ``gap``, ``rotation_gap``
``LoopClosureError``            ``history``
``SingularConstraintError``     ``rank``, ``nearby_rank``
``OverconstrainedError``        ``rank``, ``nv``
``NotAnEquilibriumError``       ``residual``, ``relative_residual``
``SingularMassError``           ``joints``
``TimePeriodicError``           ``joint``, ``variation``
``ConvergenceError``            ``history``
``IntegrationError``            ``t_reached``
``IntegrationBudgetError``      ``t_end``, ``steps``, ``elapsed``, ``budget``
``NotAnEigenvalueError``        ``lam``, ``distance``
``NotSimpleError``              ``lam``, ``measure``
``EigenvalueNotIsolatedError``  ``lam``, ``inner``, ``outer``
``BracketError``                ``bracket``, ``verdicts``
``BoundaryNotIsolatedError``    ``interval``
``SystemFunctionError``         ``p``
``SweepTimeoutError``           ``timeout``, ``pending``, ``points``; caught apart (``TimeoutError``)
``MultibladeNotExactError``     ``matrix``, ``variation``, ``tolerance``
``SamplingError``               ``samples``, ``history``, ``tolerance``
``QuasiPeriodicError``          ``periods``
``PeriodicOrbitError``          ``history``, ``period``
``OrbitLimitError``             ``joint``, ``time``, ``value``, ``lower``, ``upper``
==============================  ==========================================================================

Merged (the old name resolves to the parent with a :class:`DeprecationWarning` until 0.5):
``NoPeriodError`` into :class:`InputError` (no data, not caught apart), ``AssemblyError`` (the 0.2
name) into :class:`LoopClosureError`.

Examples
--------
>>> try:
...     raise pinlin.ParameterError("rtol", "must be positive")
... except pinlin.InputError as exc:
...     print(exc.parameter, "|", exc)
rtol | rtol: must be positive
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
    SweepTimeoutError,
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
    warn_user,
)
from .model import (
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
from .deprecated import deprecated_names
from .periodic_motion import OrbitLimitError, PeriodicOrbitError, QuasiPeriodicError

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
    "SweepTimeoutError",
    "MjcfError",
    "ConstraintError",
    "ConstraintViolationError",
    "LoopClosureError",
    "SingularConstraintError",
    "OverconstrainedError",
    "QuasiPeriodicError",
    "MultibladeNotExactError",
    "SamplingError",
    "PeriodicOrbitError",
    "OrbitLimitError",
    "warn_user",
]

#: Old names of merged classes: old name -> (the name to use, the class); removed in 0.5.
DEPRECATED_NAMES = {
    "NoPeriodError": ("pinlin.InputError", lambda: InputError),
    "AssemblyError": ("pinlin.LoopClosureError", lambda: LoopClosureError),
}

__getattr__ = deprecated_names("pinlin.errors", DEPRECATED_NAMES)
