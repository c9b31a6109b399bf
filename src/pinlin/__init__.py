"""pinlin: linearized equations of motion of multibody systems, from a URDF.

The packages follow the data flow:

- :mod:`pinlin.model` -- URDF -> :class:`Robot` -> :class:`Scene` (elements, gravity,
  prescribed joints): descriptions, immutable;
- :mod:`pinlin.linearization` -- :func:`find_equilibrium`, :func:`linearize` ->
  :class:`LinearizedSystem` (M, D, G, S, N), each call in its own Pinocchio workspace;
- :mod:`pinlin.spectral` -- eigenvalues, eigenvectors, Jordan chains, stability;
- :mod:`pinlin.adjoint` -- characteristic polynomial, adjugate, eigenvectors from it;
- :mod:`pinlin.frf` -- H(s), frequency and harmonic responses, residues;
- :mod:`pinlin.response` -- free and forced responses in time, energy budgets;
- :mod:`pinlin.nonlinear` -- the nonlinear reference simulation;
- :mod:`pinlin.studies` -- parameter sweeps and mode tracking;
- :mod:`pinlin.cli`, :mod:`pinlin.plot`, :mod:`pinlin.testing` -- around them.

Conventions (names, units, axis orders, what ``.error`` means per result) are in
``docs/conventions.md``.
"""

from . import _compat
from .adjoint import (
    AdjugateMatrix,
    CharacteristicPolynomial,
    adjugate,
    adjugate_eigenvectors,
    characteristic_polynomial,
    check_free_response,
)
from .model.elements import DeadWrench, Element, FollowerWrench, JointDamper, JointSpring, RayleighDamping
from .linearization.equilibrium import EquilibriumResult, equilibrium_residual, find_equilibrium
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
from .linearization.linearize import generalized_force, linearize
from .model.generators import double_pendulum_urdf, pendulum_chain_urdf, rotating_ring_urdf, turntable_urdf
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
from .nonlinear import Simulation, linear_coordinates, simulate
from .response import EnergyBudget, ForcedResponse, FreeResponse, energy_budget, forced_response, free_response
from .model import EXAMPLES, Robot, data_path, load_example, load_urdf, load_urdf_string
from .model.scene import Scene
from .spectral import JordanChains, Modes, Stability, jordan_chains, modal_analysis
from .studies.sweep import SweepFailure, SweepResult, sweep
from .linearization.system import LinearizedSystem

__version__ = "0.2.0"

_compat.install()

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
