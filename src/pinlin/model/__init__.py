"""What is being linearized: robots, scenes and their elements (the first stage of the data flow).

One concept per module:

- :mod:`.motions` -- periodic prescribed motions (:class:`Harmonic`, :class:`FourierMotion`,
  :class:`PeriodicMotion`) and their common period;
- :mod:`.robot` -- :class:`Robot` (a Pinocchio model without geometry), URDF and
  example-robot-data loading, the memory guard in front of every ``createData``;
- :mod:`.generators` -- URDF text of the reference models (pendulum chains, the
  paper's double pendulum, turntable, rotating ring);
- :mod:`.elements` -- force elements: a base class and one file per kind;
- :mod:`.scene` -- :class:`Scene`, an immutable description (robot, elements,
  gravity, prescribed joints) that holds no Pinocchio workspace;
- :mod:`.scene_file` -- scenes from TOML files;
- :mod:`.constraints` -- kinematic constraints (closed loops, contacts): point and frame constraints;
- :mod:`.mjcf` -- MJCF (MuJoCo) models with their ``<connect>`` and ``<weld>`` loops;
- :mod:`.loading` -- URDF files, strings and example robots; :mod:`.urdf_text` the checks
  of the XML before parsing (tree, size, depth), :mod:`.inertia` the physical validity
  of links and bodies, :mod:`.xacro` xacro files and ROS package paths;
- :mod:`.examples` -- every robot of example-robot-data by short name (:func:`examples`);
- :mod:`.standing` -- legged robots standing on the ground (:func:`standing_scene`).
"""

from .constraints import (
    Constraint,
    ConstraintForce,
    ContactStatus,
    FrameConstraint,
    PointConstraint,
    ground_contacts,
)
from .elements import (
    Bushing,
    DeadWrench,
    Element,
    FollowerWrench,
    JointDamper,
    JointSpring,
    LinearSpringDamper,
    RayleighDamping,
    WrenchElement,
)
from .examples import ExampleInfo, ExampleNotFoundError, examples
from .generators import double_pendulum_urdf, pendulum_chain_urdf, rotating_ring_urdf, turntable_urdf
from .inertia import InertiaWarning
from .loading import EXAMPLES, data_path, load_example, load_urdf, load_urdf_string
from .mjcf import load_mjcf
from .motions import FourierMotion, Harmonic, Motion, PeriodicMotion, common_period
from .robot import Robot
from .scene import Scene
from .scene_file import SceneSpec, load_scene
from .standing import Standing, standing_scene
from .xacro import expand_xacro

__all__ = [
    "Harmonic",
    "FourierMotion",
    "PeriodicMotion",
    "Motion",
    "common_period",
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
    "Element",
    "WrenchElement",
    "JointSpring",
    "JointDamper",
    "RayleighDamping",
    "FollowerWrench",
    "DeadWrench",
    "LinearSpringDamper",
    "Bushing",
    "Scene",
    "SceneSpec",
    "load_scene",
    "Constraint",
    "PointConstraint",
    "FrameConstraint",
    "ConstraintForce",
    "ContactStatus",
    "ground_contacts",
    "load_mjcf",
    "examples",
    "ExampleInfo",
    "ExampleNotFoundError",
    "InertiaWarning",
    "expand_xacro",
    "Standing",
    "standing_scene",
]
