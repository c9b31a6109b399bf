"""From a scene to M x'' + (D + G) x' + (S + N) x = f (the second stage of the data flow).

One concept per module:

- :mod:`.workspace` -- :class:`Workspace`, the Pinocchio ``Data`` that one caller owns,
  and :class:`Evaluation`, the kinematic quantities at one (q, v) that elements share;
- :mod:`.assembly` -- the residual r(q, v) and its analytic derivatives, running only
  the Pinocchio algorithms a scene needs;
- :mod:`.equilibrium` -- Newton on the configuration manifold;
- :mod:`.linearize` -- :func:`linearize`: restriction to the free coordinates,
  symmetric and skew parts;
- :mod:`.system` -- :class:`LinearizedSystem`, the frozen result.
"""

from .equilibrium import EquilibriumResult, equilibrium_residual, find_equilibrium
from .linearize import generalized_force, linearize
from .system import LinearizedSystem
from .workspace import Evaluation, Workspace

__all__ = [
    "Workspace",
    "Evaluation",
    "EquilibriumResult",
    "find_equilibrium",
    "equilibrium_residual",
    "linearize",
    "generalized_force",
    "LinearizedSystem",
]
