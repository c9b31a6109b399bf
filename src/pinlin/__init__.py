"""pinlin: linearized equations of motion of multibody systems, from a URDF.

URDF -> :class:`Robot` -> :class:`Scene` (elements, gravity, prescribed joints)
-> :func:`find_equilibrium` -> :func:`linearize` -> :class:`LinearizedSystem`
(M, D, G, S, N) -> adjoint, spectral and response analyses.
"""

from .adjoint import (
    AdjugateMatrix,
    CharacteristicPolynomial,
    FlexibilityArray,
    FrequencyResponse,
    Residues,
    adjugate,
    adjugate_eigenvectors,
    characteristic_polynomial,
    check_free_response,
    flexibility,
    frequency_response,
    residues,
)
from .elements import DeadWrench, Element, FollowerWrench, JointDamper, JointSpring, RayleighDamping
from .equilibrium import EquilibriumResult, equilibrium_residual, find_equilibrium
from .errors import (
    AccuracyWarning,
    ComputationError,
    ConfigurationError,
    ConvergenceError,
    EigenvalueNotIsolatedError,
    FrameNotFoundError,
    InputError,
    IntegrationError,
    JointNotFoundError,
    ModelTooLargeError,
    NotAnEigenvalueError,
    NotAnEquilibriumError,
    NotSimpleError,
    ParameterError,
    PinlinError,
    PrescribedJointError,
    SceneFileError,
    SingularMassError,
    TimePeriodicError,
    UrdfError,
)
from .linearize import generalized_force, linearize
from .models import double_pendulum_urdf, pendulum_chain_urdf, rotating_ring_urdf, turntable_urdf
from .response import (
    EnergyBudget,
    ForcedResponse,
    FreeResponse,
    HarmonicResponse,
    Simulation,
    energy_budget,
    forced_response,
    free_response,
    harmonic_response,
    linear_coordinates,
    simulate,
)
from .robot import EXAMPLES, Robot, data_path, load_example, load_urdf, load_urdf_string
from .scene import Scene
from .spectral import JordanChains, Modes, Stability, jordan_chains, modal_analysis
from .sweep import SweepFailure, SweepResult, sweep
from .system import LinearizedSystem

__version__ = "0.1.0"

__all__ = [
    "__version__",
    # loading
    "Robot",
    "load_urdf",
    "load_urdf_string",
    "load_example",
    "EXAMPLES",
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
    # equilibrium and linearization
    "EquilibriumResult",
    "find_equilibrium",
    "equilibrium_residual",
    "linearize",
    "generalized_force",
    "LinearizedSystem",
    # parameter sweeps
    "sweep",
    "SweepResult",
    "SweepFailure",
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
    "AccuracyWarning",
    # responses (SPEC section 6)
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
    # spectrum (SPEC sections 4, 5)
    "modal_analysis",
    "jordan_chains",
    "Modes",
    "Stability",
    "JordanChains",
    # adjoint and flexibility (SPEC section 4)
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
]
