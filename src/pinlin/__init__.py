"""pinlin: linearized equations of motion of multibody systems, from a URDF.

URDF -> :class:`Robot` -> :class:`Scene` (elements, gravity, prescribed joints)
-> :func:`find_equilibrium` -> :func:`linearize` -> :class:`LinearizedSystem`
(M, D, G, S, N) -> adjoint, spectral and response analyses.
"""

from .elements import DeadWrench, Element, FollowerWrench, JointDamper, JointSpring, RayleighDamping
from .equilibrium import EquilibriumResult, equilibrium_residual, find_equilibrium
from .errors import (
    ComputationError,
    ConfigurationError,
    ConvergenceError,
    FrameNotFoundError,
    InputError,
    JointNotFoundError,
    ModelTooLargeError,
    NotAnEquilibriumError,
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
from .robot import EXAMPLES, Robot, data_path, load_example, load_urdf, load_urdf_string
from .scene import Scene
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
    "PrescribedJointError",
    "TimePeriodicError",
    "SceneFileError",
    "ComputationError",
    "ConvergenceError",
    "ModelTooLargeError",
]
