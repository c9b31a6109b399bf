"""Force elements of a scene: a base class and one small file per kind.

- :mod:`.base` -- :class:`Element` (the protocol), :class:`ElementGroup`, :class:`WrenchElement`;
- :mod:`.joint_spring`, :mod:`.joint_damper` -- on joint coordinates (vectorized groups);
- :mod:`.rayleigh` -- alpha M + beta K_e;
- :mod:`.wrenches` -- follower (body-fixed) and dead (world-fixed) wrenches.
"""

from .base import Element, ElementGroup, WrenchElement
from .joint_damper import JointDamper
from .joint_spring import JointSpring
from .rayleigh import RayleighDamping
from .wrenches import DeadWrench, FollowerWrench

__all__ = [
    "Element",
    "WrenchElement",
    "ElementGroup",
    "JointSpring",
    "JointDamper",
    "RayleighDamping",
    "FollowerWrench",
    "DeadWrench",
]
