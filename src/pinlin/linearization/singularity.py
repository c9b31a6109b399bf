"""Is a rank deficiency of J_c structural (redundant constraints) or a singular configuration?

A rank-deficient J_c at q has two causes (theory: constraints):

- redundant equations that hold on the whole constraint manifold (a planar
  loop's out-of-plane equation): the rank is the same at every assembled
  configuration nearby, the linearization is regular and only the multipliers
  are not unique;
- a singular configuration (a linkage at a change point or toggle, all its
  pivots in line): the rank is lower at q than at the assembled configurations
  around it, the constraint manifold is not smooth there, and no linearization
  in n = nv - rank coordinates exists.

:func:`check_regular` tells them apart by stepping ``PROBE_STEP`` along
:data:`PROBES` random directions of ker J_c, closing the loops again, and
comparing ranks there.  It only runs when J_c is rank deficient: a
full-row-rank J_c (a robot standing on point contacts) costs nothing.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..errors import SingularConstraintError
from ..model.scene import Scene
from .closure import project
from .constraint_set import ConstraintState

__all__ = ["check_regular", "PROBE_STEP", "PROBES", "NAMING_SHARE", "PROBE_SEED"]

#: Length [rad or m] of the probing steps: far enough that a toggle's rank drop is
#: lifted well above RANK_TOL (the lost singular value grows like the distance, ~1e-3
#: relative), near enough to stay on the same branch of the constraint manifold.
PROBE_STEP = 1e-3
#: Number of random probing directions (each one is enough for a generic direction;
#: two guard against an unlucky one).
PROBES = 2
#: Fixed seed: the probes, and so the decision, are reproducible.
PROBE_SEED = 20240611
#: A constraint is named as taking part in a lost rank when its rows carry at least this
#: share of the largest row block of the lost direction (left singular vector).
NAMING_SHARE = 0.3


def check_regular(scene: Scene, q: np.ndarray, state: ConstraintState, calls: list[str]) -> None:
    """Raise :class:`SingularConstraintError` when the rank of J_c at q is lower than nearby.

    ``calls`` collects the Pinocchio algorithms the probes run.

    Raises
    ------
    SingularConstraintError
        J_c loses rank at q (naming the constraints whose equations become dependent).
    """
    if state.rank == state.m:
        return
    kernel = state.kernel()
    if kernel.shape[1] == 0:
        return
    rng = np.random.default_rng(PROBE_SEED)
    best = None
    for _ in range(PROBES):
        direction = kernel @ rng.standard_normal(kernel.shape[1])
        direction *= PROBE_STEP / np.linalg.norm(direction)
        _, probe, _, ok = project(scene, pin.integrate(scene.model, q, direction), rank_tol=state.rank_tol, calls=calls)
        if ok and probe.rank > (state.rank if best is None else best.rank):
            best = probe
    if best is None:
        return
    U0, U1 = state.left_null, best.left_null
    lost = U0 - U1 @ (U1.T @ U0)  # dependent directions at q that are independent nearby
    directions = np.linalg.svd(lost, full_matrices=False)[0][:, : best.rank - state.rank]
    names: list[str] = []
    for k in range(directions.shape[1]):
        names.extend(n for n in state.row_owners(directions[:, k], NAMING_SHARE) if n not in names)
    raise SingularConstraintError(
        f"singular configuration: the constraint Jacobian J_c has rank {state.rank} at q but rank "
        f"{best.rank} at the assembled configurations {PROBE_STEP:g} away; the equations of constraint(s) "
        f"{names} become dependent here (a linkage at a toggle or change point, its pivots in line), so the "
        f"constraint manifold is not smooth at q and has no linearization; move the operating point away",
        state.rank,
        best.rank,
        names,
    )
