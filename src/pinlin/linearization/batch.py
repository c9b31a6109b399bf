"""Linearization at many configurations of one scene: :func:`linearize_many`.

A parameter study or a gain schedule linearizes one scene at many q.  Called
point by point, :func:`~pinlin.linearization.linearize.linearize` pays per point
for what does not change between points: the tolerance checks, the fixed costs
of the numpy calls behind the element work, the norms, the checks and the
symmetric/skew split.

Two stacked paths run per point only the Pinocchio passes ``linearize`` runs
(and a quaternion's normalization, :func:`configurations`), everything else once
on arrays of all points: :mod:`.batch_static` for joint-space scenes at rest
(joint springs and dampers, follower wrenches; no prescribed joint, no
constraint), :mod:`.batch_moving` for steady motions of prescribed joints whose
time invariance is proved once per scene (the turntable), with the same
elements.  :mod:`.batch_common` holds what they share (norms, checks, result
objects).  Other scenes are linearized point by point with ``linearize`` itself
(the same results; measured, sharing only the checks and splits there saved less
than the stacking cost).
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np
import pinocchio as pin

from ..errors import ConfigurationError
from ..model.evaluation import BatchPoints
from ..model.scene import UNIT_NORM_MIN, Scene
from . import batch_moving, batch_static
from .linearize import linearize
from .options import CONSTRAINT_TOL, EQUILIBRIUM_TOL, PERIODIC_TOL, RANK_TOL, LinearizeOptions
from .periodicity import refuse_motions
from .plan import plan_of
from .system import LinearizedSystem

__all__ = ["linearize_many", "configurations", "LENGTH_MARGIN", "CHUNK_ENTRIES"]

#: A quaternion or (cos, sin) pair measured on the stack (a sum of squares, not the single
#: check's ``math.hypot``) passes only this far above UNIT_NORM_MIN: the two lengths differ by a
#: few rounding errors, so a pair that passes here passes the single check (closer ones take it).
LENGTH_MARGIN = 1.0 + 1e-12

#: The stacked paths take the points in chunks of at most this many matrix entries per stack
#: (256 KiB of doubles): a pass keeps about ten (P, nv, nv) stacks alive, which then stay in a
#: core's L2 cache (1-2 MiB); a 100-point talos batch (nv = 38) in one chunk ran 1.1-1.2x slower per
#: point than in chunks of 22, by thread time (interleaved samples), for 3 % fewer instructions.
CHUNK_ENTRIES = 1 << 15


def linearize_many(
    scene: Scene,
    qs,
    *,
    balancing: bool = False,
    equilibrium_tol: float = EQUILIBRIUM_TOL,
    structure_tol: float | None = None,
    periodic_tol: float = PERIODIC_TOL,
    constraint_tol: float = CONSTRAINT_TOL,
    rank_tol: float = RANK_TOL,
) -> tuple[LinearizedSystem, ...]:
    """The linearized equations of ``scene`` at each configuration of ``qs``.

    ``linearize_many(scene, qs, **options)[i]`` equals ``linearize(scene, qs[i],
    **options)``: the same matrices, bitwise, the same ``calls`` and ``notes``; the
    same ``residual`` and ``dropped`` figures (to rounding on the stacked paths,
    whose norms are taken for all points in one reduction; exactly where a figure
    is within :data:`~pinlin.linearization.batch_common.DECISION_MARGIN` of the
    tolerance it is tested against, so every decision is the single call's).  See
    the module docstring for what is shared.  On the stacked paths ``elapsed`` of
    each system is the batch's time divided by the number of points, and the
    matrices are read-only views into arrays of the whole batch (a constant D or G
    one view shared by the batch's systems).  Large batches of large systems are
    taken in chunks of :data:`CHUNK_ENTRIES` matrix entries per stack (22 points
    for nv = 38): ``elapsed`` is then its chunk's time per point.

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
        is refused by :meth:`Scene.check_configuration` (on the stacked paths the
        message names the row, ``qs[i]``; elsewhere it is linearize's, ``q``).
    ParameterError, ComputationError, NotAnEquilibriumError, SingularMassError, TimePeriodicError
        As :func:`~pinlin.linearization.linearize.linearize` raises them, at the first
        point concerned; on the stacked paths the checks run stage by stage over the
        points of a chunk (every residual, then finite entries, then every mass
        matrix), so with several bad points in one chunk the first failing stage
        decides.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0)])
    >>> systems = pinlin.linearize_many(scene, np.zeros((3, 2)))
    >>> len(systems), np.array_equal(systems[2].K, pinlin.linearize(scene, np.zeros(2)).K)
    (3, True)
    """
    t0 = time.perf_counter()
    options = LinearizeOptions(balancing, equilibrium_tol, structure_tol, periodic_tol, constraint_tol, rank_tol)
    if scene.motions:  # time-periodic: as linearize refuses it
        refuse_motions(scene)
    rows = _rows(scene, qs)
    if batch_static.applies(scene):
        path = batch_static.linearize_at_rest
    elif batch_moving.applies(scene, periodic_tol):
        path = batch_moving.linearize_moving
    else:
        return tuple(
            linearize(scene, q, balancing=balancing, equilibrium_tol=equilibrium_tol, structure_tol=structure_tol,
                      periodic_tol=periodic_tol, constraint_tol=constraint_tol, rank_tol=rank_tol)
            for q in rows
        )  # fmt: skip
    points = configurations(scene, rows)
    if structure_tol is None:  # the scene's default: fixed once for the batch
        options = replace(options, structure_tol=plan_of(scene).structure_tol)
    step = max(1, CHUNK_ENTRIES // scene.model.nv**2)
    batch = BatchPoints(points)  # what the element groups compute once for every chunk
    systems: tuple[LinearizedSystem, ...] = ()
    for start in range(0, len(points), step):  # the first chunk's time includes the checks above
        chunk = batch.chunk(start, start + step)
        systems += path(scene, points[chunk.rows], options, t0, time.perf_counter, chunk)
        t0 = time.perf_counter()
    return systems


def configurations(scene: Scene, rows: np.ndarray) -> np.ndarray:
    """The rows as :meth:`Scene.check_configuration` returns them (P, nq), bitwise; the checks run on the stack.

    The entry bounds are the single check's own comparison (``|q_i| <= limit_i``,
    which also refuses inf and NaN), on all rows at once.  Quaternions and (cos,
    sin) pairs are measured on the stack too, with a margin of :data:`LENGTH_MARGIN`
    over :data:`~pinlin.model.scene.UNIT_NORM_MIN`; each row is then normalized by
    Pinocchio, as the single check does.  A stack that fails (or a length within
    the margin) goes row by row through the single check itself, which raises at
    the first bad row, naming it ``qs[i]``.
    """
    limit, blocks = scene.q_limit, scene.unit_blocks
    checked = bool((np.abs(rows) <= limit).all())  # False for inf and NaN
    if checked and blocks is not None:
        for _, block in blocks:
            unit = rows[:, block]
            checked &= bool((np.sqrt(np.einsum("pi,pi->p", unit, unit)) >= UNIT_NORM_MIN * LENGTH_MARGIN).all())
    if not checked:
        return np.array([scene.check_configuration(q, label=f"qs[{i}]") for i, q in enumerate(rows)])
    if blocks is None:  # a vector space: the single check returns a copy
        return rows.copy()
    model = scene.model
    return np.array([pin.normalize(model, q) for q in rows])


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
