"""From a scene to M x'' + (D + G) x' + (S + N) x = f (the second stage of the data flow).

One concept per module:

- :mod:`.workspace` -- :class:`Workspace`, the Pinocchio ``Data`` that one caller owns,
  and :class:`Evaluation`, the kinematic quantities at one (q, v) that elements share;
- :mod:`.assembly` -- the residual r(q, v) and its analytic derivatives, running only
  the Pinocchio algorithms a scene needs;
- :mod:`.plan` -- :class:`~.plan.LinearizationPlan`, what a linearization decides once
  per scene (``plan_of(scene)``);
- :mod:`.time_invariance` -- do the equations depend on a prescribed joint's position?
  Proofs once per scene, the numerical check elsewhere;
- :mod:`.equilibrium` -- Newton on the configuration manifold;
- :mod:`.linearize` -- :func:`linearize`: restriction to the free coordinates and
  the checks; :mod:`.split` the symmetric and skew parts;
- :mod:`.batch` -- :func:`linearize_many`: one scene at many configurations; its
  stacked paths :mod:`.batch_static` (joint-space scenes at rest) and
  :mod:`.batch_moving` (steady motions proved time-invariant), with
  :mod:`.batch_common` (stacked norms, checks, result objects);
- :mod:`.system` -- :class:`LinearizedSystem`, the frozen result;
- constraints (theory: constraints): :mod:`.constraint_set` (Phi, J_c, rank and
  multipliers at one q), :mod:`.closure` (closing the loops, :func:`close_loops`),
  :mod:`.singularity` (redundant constraints or a singular configuration?, probed)
  and :mod:`.constrained_structure` (redundancy proved: planar loops),
  :mod:`.coordinates` (the basis B of ker J_c), :mod:`.constrained_equilibrium`
  (Newton with the KKT matrix), :mod:`.constrained` (the projected linearization,
  the constraint stiffness K_lambda).
"""

from ..model.evaluation import Evaluation, Workspace
from .batch import linearize_many
from .closure import ClosureResult, close_loops
from .constrained import constraint_stiffness
from .equilibrium import equilibrium_residual, find_equilibrium
from .equilibrium_result import EquilibriumResult
from .linearize import generalized_force, linearize
from .system import LinearizedSystem

__all__ = [
    "Workspace",
    "Evaluation",
    "EquilibriumResult",
    "find_equilibrium",
    "equilibrium_residual",
    "linearize",
    "linearize_many",
    "generalized_force",
    "LinearizedSystem",
    "close_loops",
    "ClosureResult",
    "constraint_stiffness",
]
