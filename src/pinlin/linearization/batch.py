"""Linearization at many configurations of one scene (issue 14): :func:`linearize_many`.

A parameter study or a gain schedule linearizes one scene at many q.  Called
point by point, :func:`~pinlin.linearization.linearize.linearize` pays per point
for what does not change between points: the tolerance checks, the fixed costs
of the numpy calls behind the element work, the norms, the checks and the
symmetric/skew split.

For a joint-space scene at rest (joint springs and dampers, follower wrenches;
no prescribed joint, no constraint) :mod:`.batch_static` runs only the
configuration check and Pinocchio per point, and everything else once on
stacked arrays.  Other scenes are linearized point by point with ``linearize``
itself (the same results; measured, sharing only the checks and splits there
saved less than the stacking cost).
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import ConfigurationError
from ..model.scene import Scene
from . import batch_static
from .constraint_set import CONSTRAINT_TOL, RANK_TOL
from .linearize import _check_tolerances, linearize
from .system import LinearizedSystem

__all__ = ["linearize_many"]


def linearize_many(
    scene: Scene,
    qs,
    *,
    balancing: bool = False,
    equilibrium_tol: float = 1e-8,
    structure_tol: float | None = None,
    periodic_tol: float = 1e-8,
    constraint_tol: float = CONSTRAINT_TOL,
    rank_tol: float = RANK_TOL,
) -> tuple[LinearizedSystem, ...]:
    """The linearized equations of ``scene`` at each configuration of ``qs``.

    ``linearize_many(scene, qs, **options)[i]`` equals ``linearize(scene, qs[i],
    **options)``: the same matrices, bitwise, the same ``calls`` and ``notes``; the
    same ``residual`` and ``dropped`` figures (to rounding on the at-rest path, whose
    norms are taken for all points in one reduction).  See the module docstring
    for what is shared.  On the at-rest path ``elapsed`` of each system is the
    batch's time divided by the number of points, and the matrices are read-only
    views into arrays of the whole batch.

    Parameters
    ----------
    scene : Scene
    qs : (P, nq) array
        Full configurations, one per row (prescribed joints included).
    balancing, equilibrium_tol, structure_tol, periodic_tol, constraint_tol, rank_tol
        As for :func:`~pinlin.linearization.linearize.linearize`, for every point.

    Returns
    -------
    tuple of LinearizedSystem
        One per row of ``qs``, in order.

    Raises
    ------
    ConfigurationError
        ``qs`` is not a (P, nq) array of numbers with P >= 1, or one of its rows
        is refused by :meth:`Scene.check_configuration` (on the at-rest path the
        message names the row, ``qs[i]``; elsewhere it is linearize's, ``q``).
    ParameterError, ComputationError, NotAnEquilibriumError, SingularMassError, TimePeriodicError
        As :func:`~pinlin.linearization.linearize.linearize` raises them, at the first
        point concerned; on the at-rest path the checks run stage by stage over all
        points (every residual, then finite entries, then every mass matrix), so with
        several bad points the first failing stage decides.
    """
    t0 = time.perf_counter()
    _check_tolerances(equilibrium_tol, periodic_tol, structure_tol, constraint_tol, rank_tol)
    rows = _rows(scene, qs)
    if not batch_static.applies(scene):
        options = dict(balancing=balancing, equilibrium_tol=equilibrium_tol, structure_tol=structure_tol,
                       periodic_tol=periodic_tol, constraint_tol=constraint_tol, rank_tol=rank_tol)  # fmt: skip
        return tuple(linearize(scene, q, **options) for q in rows)
    points = [scene.check_configuration(q, label=f"qs[{i}]") for i, q in enumerate(rows)]
    tol = scene.linearization_plan.structure_tol if structure_tol is None else float(structure_tol)
    return batch_static.linearize_at_rest(scene, points, equilibrium_tol, tol, balancing, t0, time.perf_counter)


def _rows(scene: Scene, qs) -> np.ndarray:
    """``qs`` as a (P, nq) float array with P >= 1, or ConfigurationError."""
    try:
        complex_entries = np.iscomplexobj(qs)
        rows = np.asarray(qs, dtype=float) if not complex_entries else None
    except (TypeError, ValueError):
        raise ConfigurationError(f"qs must be a (P, nq) array of numbers, got {qs!r:.80}") from None
    if rows is None:
        raise ConfigurationError("qs must be real, got complex entries")
    nq = scene.robot.nq
    if rows.ndim != 2 or rows.shape[1] != nq or rows.shape[0] == 0:
        raise ConfigurationError(
            f"qs has shape {rows.shape}; linearize_many needs a (P, nq) array with P >= 1 rows, "
            f"each a full configuration of size nq = {nq}"
        )
    return rows
