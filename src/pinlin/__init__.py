"""pinlin: linearized equations of motion of multibody systems, from a URDF.

The packages follow the data flow:

- :mod:`pinlin.model` -- URDF / MJCF -> :class:`Robot` -> :class:`Scene` (elements,
  constraints, gravity, prescribed joints): descriptions, immutable;
- :mod:`pinlin.linearization` -- :func:`find_equilibrium`, :func:`linearize` ->
  :class:`LinearizedSystem` (M, D, G, S, N), each call in its own Pinocchio workspace;
- :mod:`pinlin.spectral` -- eigenvalues, eigenvectors, Jordan chains, stability;
- :mod:`pinlin.adjoint` -- characteristic polynomial, adjugate, eigenvectors from it;
- :mod:`pinlin.frf` -- H(s), frequency and harmonic responses, residues;
- :mod:`pinlin.response` -- free and forced responses in time, energy budgets;
- :mod:`pinlin.nonlinear` -- the nonlinear reference simulation;
- :mod:`pinlin.periodic` -- time-periodic motions: periodic orbits by shooting, Floquet analysis;
- :mod:`pinlin.studies` -- parameter sweeps (on any executor: threads, processes, Dask,
  Ray) and mode tracking;
- :mod:`pinlin.boundaries` -- eigenvalue sensitivities, exact stability boundaries;
- :mod:`pinlin.interop` -- state-space models for python-control and scipy;
- :mod:`pinlin.cli`, :mod:`pinlin.plot`, :mod:`pinlin.testing` -- around them
  (:mod:`pinlin.plot` also draws and animates mode shapes on the robot).

Conventions (names, units, axis orders, what ``.error`` means per result) are in
``docs/conventions.md``; the user guide, the API reference and the notebooks build
from ``docs/`` with Sphinx (``docs/index.md`` says how).
"""

from . import plot, testing  # noqa: F401 -- pinlin.plot.* and pinlin.testing.check_element after `import pinlin`
from .adjoint import (
    AdjugateMatrix,
    CharacteristicPolynomial,
    adjugate,
    adjugate_eigenvectors,
    characteristic_polynomial,
    check_free_response,
)
from .boundaries import (
    BoundaryFailure,
    CriticalParameter,
    EigenvalueSensitivity,
    StabilityBoundary,
    critical_parameter,
    eigenvalue_sensitivity,
    stability_boundary,
)
from .errors import DEPRECATED_NAMES as _DEPRECATED_NAMES
from .errors import (
    AccuracyWarning,
    BoundaryNotIsolatedError,
    BracketError,
    ComputationError,
    ConfigurationError,
    ConstraintError,
    ConstraintViolationError,
    ConvergenceError,
    EigenvalueNotIsolatedError,
    FrameNotFoundError,
    InputError,
    IntegrationBudgetError,
    IntegrationError,
    JointNotFoundError,
    LoopClosureError,
    MissingDependencyError,
    MjcfError,
    ModelTooLargeError,
    MultibladeNotExactError,
    SamplingError,
    NameNotFoundError,
    NotAnEigenvalueError,
    NotAnEquilibriumError,
    NotSimpleError,
    OrbitLimitError,
    OverconstrainedError,
    ParameterError,
    PeriodicOrbitError,
    PinlinError,
    PrescribedJointError,
    QuasiPeriodicError,
    SceneFileError,
    SingularConstraintError,
    SingularMassError,
    SweepTimeoutError,
    SystemFunctionError,
    TimePeriodicError,
    UrdfError,
)
from .frf import (
    FlexibilityArray,
    FrequencyResponse,
    HarmonicResponse,
    Residues,
    flexibility,
    frequency_response,
    harmonic_response,
    residues,
)
from .interop import StateSpaceModel, state_space
from .linearization.batch import linearize_many
from .linearization.closure import ClosureResult, close_loops
from .linearization.constrained import constraint_stiffness
from .linearization.equilibrium import equilibrium_residual, find_equilibrium
from .linearization.equilibrium_result import EquilibriumResult
from .linearization.linearize import generalized_force, linearize
from .linearization.system import LinearizedSystem
from .model import (
    EXAMPLES,
    ExampleInfo,
    ExampleNotFoundError,
    InertiaWarning,
    Robot,
    Standing,
    data_path,
    examples,
    expand_xacro,
    load_example,
    load_urdf,
    load_urdf_string,
    standing_scene,
)
from .model.constraints import (
    Constraint,
    ConstraintForce,
    ContactStatus,
    FrameConstraint,
    PointConstraint,
    ground_contacts,
)
from .model.elements import (
    Bushing,
    DeadWrench,
    Element,
    FollowerWrench,
    JointDamper,
    JointSpring,
    LinearSpringDamper,
    RayleighDamping,
)
from .model.generators import double_pendulum_urdf, pendulum_chain_urdf, rotating_ring_urdf, turntable_urdf
from .model.mjcf import load_mjcf
from .model.motions import FourierMotion, Harmonic, PeriodicMotion
from .model.scene import Scene
from .nonlinear import Simulation, linear_coordinates, simulate
from .periodic import (
    FloquetAnalysis,
    PeriodicOrbit,
    floquet_analysis,
    floquet_analysis_matrices,
    floquet_from_first_order,
    multiblade_transform,
    multiblade_transform_matrices,
    periodic_orbit,
    scene_period,
    variational_coefficients,
)
from .response import (
    EnergyBudget,
    ForcedResponse,
    FreeResponse,
    energy_budget,
    forced_response,
    free_response,
)
from .results import load
from .spectral import JordanChains, ModeEnergy, Modes, Stability, jordan_chains, modal_analysis
from .studies.floquet_campbell import FloquetCampbell, floquet_campbell
from .studies.sweep import SweepFailure, SweepResult, sweep
from .errors.deprecated import deprecated_names as _deprecated_names
from .version import __version__

__all__ = [
    "__version__",
    # results a user can keep
    "load",
    # loading
    "Robot",
    "load_urdf",
    "load_urdf_string",
    "load_example",
    "EXAMPLES",
    "examples",
    "ExampleInfo",
    "ExampleNotFoundError",
    "InertiaWarning",
    "expand_xacro",
    "Standing",
    "standing_scene",
    "data_path",
    "pendulum_chain_urdf",
    "double_pendulum_urdf",
    "turntable_urdf",
    "rotating_ring_urdf",
    # scene
    "Scene",
    "Element",
    "JointSpring",
    "JointDamper",
    "RayleighDamping",
    "FollowerWrench",
    "DeadWrench",
    "LinearSpringDamper",
    "Bushing",
    # equilibrium and linearization
    "EquilibriumResult",
    "find_equilibrium",
    "equilibrium_residual",
    "linearize",
    "linearize_many",
    "generalized_force",
    "LinearizedSystem",
    # constraints: closed loops and contacts (theory: constraints)
    "Constraint",
    "PointConstraint",
    "FrameConstraint",
    "ConstraintForce",
    "ContactStatus",
    "ground_contacts",
    "load_mjcf",
    "close_loops",
    "ClosureResult",
    "constraint_stiffness",
    "ConstraintError",
    "ConstraintViolationError",
    "LoopClosureError",
    "SingularConstraintError",
    "OverconstrainedError",
    "MjcfError",
    # parameter sweeps
    "sweep",
    "SweepResult",
    "SweepFailure",
    "SweepTimeoutError",
    # sensitivities and stability boundaries (theory: boundaries)
    "eigenvalue_sensitivity",
    "EigenvalueSensitivity",
    "critical_parameter",
    "CriticalParameter",
    "stability_boundary",
    "StabilityBoundary",
    "BoundaryFailure",
    "BracketError",
    "BoundaryNotIsolatedError",
    "SystemFunctionError",
    # errors
    "PinlinError",
    "InputError",
    "UrdfError",
    "JointNotFoundError",
    "FrameNotFoundError",
    "ParameterError",
    "ConfigurationError",
    "NotAnEquilibriumError",
    "SingularMassError",
    "NotAnEigenvalueError",
    "NotSimpleError",
    "EigenvalueNotIsolatedError",
    "PrescribedJointError",
    "TimePeriodicError",
    "SceneFileError",
    "ComputationError",
    "ConvergenceError",
    "ModelTooLargeError",
    "IntegrationError",
    "IntegrationBudgetError",
    "MissingDependencyError",
    "NameNotFoundError",
    "AccuracyWarning",
    # responses (theory: responses)
    "free_response",
    "FreeResponse",
    "harmonic_response",
    "HarmonicResponse",
    "simulate",
    "Simulation",
    "linear_coordinates",
    "forced_response",
    "ForcedResponse",
    "energy_budget",
    "EnergyBudget",
    # spectrum (theory: spectrum, stability)
    "modal_analysis",
    "jordan_chains",
    "Modes",
    "ModeEnergy",
    "Stability",
    "JordanChains",
    # adjoint and flexibility (theory: spectrum)
    "characteristic_polynomial",
    "CharacteristicPolynomial",
    "adjugate",
    "AdjugateMatrix",
    "adjugate_eigenvectors",
    "check_free_response",
    "flexibility",
    "FlexibilityArray",
    "residues",
    "Residues",
    "frequency_response",
    "FrequencyResponse",
    # other tools' forms: python-control, scipy.signal
    "state_space",
    "StateSpaceModel",
    # time-periodic motions (theory: Floquet)
    "Harmonic",
    "FourierMotion",
    "PeriodicMotion",
    "scene_period",
    "periodic_orbit",
    "PeriodicOrbit",
    "variational_coefficients",
    "floquet_analysis",
    "floquet_analysis_matrices",
    "floquet_from_first_order",
    "multiblade_transform",
    "floquet_campbell",
    "FloquetCampbell",
    "multiblade_transform_matrices",
    "FloquetAnalysis",
    "QuasiPeriodicError",
    "MultibladeNotExactError",
    "SamplingError",
    "PeriodicOrbitError",
    "OrbitLimitError",
]

# The old names of merged error classes resolve with a DeprecationWarning, as in pinlin.errors.
__getattr__ = _deprecated_names("pinlin", _DEPRECATED_NAMES)
