"""Force elements of a scene: a base class and one small file per kind.

- :mod:`.base` -- :class:`Element` (the protocol, see docs/elements.md), :class:`ElementGroup`,
  :class:`WrenchElement`;
- :mod:`.joint_spring`, :mod:`.joint_damper` -- on joint coordinates (vectorized groups);
- :mod:`.rayleigh` -- alpha M + beta K_e;
- :mod:`.wrenches` -- follower (body-fixed) and dead (world-fixed) wrenches;
- :mod:`.spring_damper` -- :class:`LinearSpringDamper` between two points (vectorized group);
- :mod:`.bushing` -- :class:`Bushing`, six-axis spring and damper on the SE(3) log of a relative placement;
- :mod:`.frame_pairs` -- kinematics the elements between frames share (support masks, the
  derivative of J^T W at fixed spatial wrenches);
- :mod:`.se3` -- the second-order expansion of SE(3)'s log (for bushings away from rest).
"""

from .base import Element, ElementGroup, WrenchElement
from .bushing import Bushing
from .joint_damper import JointDamper
from .joint_spring import JointSpring
from .rayleigh import RayleighDamping
from .spring_damper import LinearSpringDamper
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
    "LinearSpringDamper",
    "Bushing",
]
