"""Force elements of a scene: springs, dampers, Rayleigh damping, wrenches."""

from .base import Element, Evaluation, WrenchElement
from .joint_damper import JointDamper
from .joint_spring import JointSpring
from .rayleigh import RayleighDamping
from .wrenches import DeadWrench, FollowerWrench

__all__ = [
    "Element",
    "WrenchElement",
    "Evaluation",
    "JointSpring",
    "JointDamper",
    "RayleighDamping",
    "FollowerWrench",
    "DeadWrench",
]
