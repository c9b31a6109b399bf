"""What the batched paths of :func:`pinlin.linearize_many` share: stacked norms, checks and result objects.

:mod:`.batch_static` (scenes at rest) and :mod:`.batch_moving` (steady motions
of prescribed joints) compute every point's matrices on stacked arrays (P, n, n);
this module takes their norms (:func:`norms`), runs the single call's checks on
all points at once, raising the single call's own error at the first bad point
(:func:`check_points`), and builds the result objects (:func:`build_systems`).

The norms are taken for all points in one reduction, so the figures built on them
(``residual``, ``dropped``) agree with ``linearize``'s to rounding; where such a
figure decides something and lies within :data:`DECISION_MARGIN` of its
tolerance (:func:`near`), the paths take it again as ``linearize`` takes it, so
every decision is the single call's.
"""

from __future__ import annotations

import math
import numpy as np

from ..errors import ComputationError, SingularMassError
from ..model.scene import Scene
from ..numerics.norms import fro
from .assembly import Assembly
from .checks import check_equilibrium, check_finite_and_mass, check_mass
from .plan import plan_of
from .system import LinearizedSystem

__all__ = ["norms", "near", "halves", "relative_residuals", "DECISION_MARGIN", "check_points", "rows_or_zero",
           "build_systems", "TINY"]

TINY = float(np.finfo(float).tiny)

#: A figure of the stacked norms this close to the tolerance it is compared with (relative) is
#: taken again with the single call's ``fro`` before the comparison: the two norms differ by a
#: few rounding errors of a sum of squares (about 1e-16 relative), far below this margin.
DECISION_MARGIN = 1e-12


def norms(X: np.ndarray) -> np.ndarray:
    """Frobenius norm of each X[p] (P,), overflow-safe: scaled again where the squares overflow."""
    flat = X.reshape(len(X), -1)
    squares = np.einsum("pi,pi->p", flat, flat)
    if squares.sum() < math.inf:  # the usual case; False for an overflow, inf or NaN
        return np.sqrt(squares)
    out = np.sqrt(squares)
    bad = ~np.isfinite(out)  # entries beyond ~1e154 (or non-finite ones): scale by the largest entry
    with np.errstate(over="ignore", invalid="ignore"):
        big = np.abs(flat[bad]).max(axis=1)
        scaled = flat[bad] / np.where(big > 0, big, 1.0)[:, None]
        norm = big * np.sqrt(np.einsum("pi,pi->p", scaled, scaled))
    out[bad] = np.where(np.isfinite(big), norm, big)  # an infinite (NaN) entry: an infinite (NaN) norm, as fro
    return out


def near(figures: np.ndarray, tol: float) -> list[int]:
    """Indices of the figures within DECISION_MARGIN (relative) of ``tol``: equal to it when tol is 0."""
    return np.flatnonzero(np.abs(figures - tol) <= DECISION_MARGIN * tol).tolist()


def halves(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """((A^T + A) / 2, A - A^T) of each A[p] of a stack (P, n, n): :func:`~.split.split_stiffness`'s arithmetic.

    The same operations, entry by entry, as the single call's split; both results
    are new stacks.
    """
    At = A.transpose(0, 2, 1)
    return (A + At) / 2, A - At


def relative_residuals(tau, Q, K, r, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """(force scales, relative residuals) of all points: ``check_equilibrium``'s figures of linearize, stacked.

    ``r`` (P, n) is tau - Q on the free coordinates; the scale is ||tau|| + ||Q|| +
    ||K|| (0 gives a relative residual of 0).  Where a figure lies within
    :data:`DECISION_MARGIN` of ``tol`` it is taken again with the single call's ``fro``.
    """
    force_scale = norms(tau) + norms(Q) + norms(K)
    rel = norms(r) / np.where(force_scale > 0, force_scale, 1.0)
    rel[force_scale <= 0] = 0.0
    for i in near(rel, tol):  # as check_equilibrium, where it decides
        force_scale[i] = fro(tau[i]) + fro(Q[i]) + fro(K[i])
        rel[i] = fro(r[i]) / force_scale[i] if force_scale[i] > 0 else 0.0
    return force_scale, rel


def check_points(scene: Scene, residual, force_scale, rel, M, C, tol: float, balancing: bool) -> None:
    """The single call's equilibrium and finite-entry checks on all points; its own errors at the first bad one.

    ``residual`` (P, nv) holds the residuals on all coordinates, ``rel`` (P,) their
    relative sizes on the free ones, ``M`` (P, n, n) the mass matrices and ``C`` the
    damping matrices (P, n, n), or one (n, n) matrix for all points.  The checks run
    stage by stage (every residual, then finite entries); the mass matrices are the
    constructor's to check (:func:`build_systems`), once.
    """
    plan = plan_of(scene)
    if not balancing and (rel > tol).any():
        i = int(np.argmax(rel > tol))
        check_equilibrium(scene, plan, _assembly(residual[i], force_scale[i]), tol, balancing)  # raises
    if not (np.isfinite(force_scale).all() and np.isfinite(M).all() and np.isfinite(C).all()):
        for i in range(len(M)):  # raises at the first bad point
            check_finite_and_mass(scene, M[i], C[i] if C.ndim == 3 else C, _assembly(residual[i], force_scale[i]))
        raise ComputationError("linearize_many: non-finite entries in M, C, K or the residual")  # pragma: no cover


def _assembly(residual: np.ndarray, force_scale: float) -> Assembly:
    """A one-point Assembly carrying what the single call's checks read (for their error messages)."""
    return Assembly(residual=residual, force_scale=float(force_scale), M=None, C=None, K=None,
                    rounding_scale_C=0.0, rounding_scale_K=0.0, coriolis_D=None, calls=[])  # fmt: skip


def rows_or_zero(X: np.ndarray, sizes: list[float], tol: float, name: str, zero: np.ndarray, dropped: list[dict]):
    """The rows of the stack X, each whose size is at or below ``tol`` replaced by ``zero`` (the single call's skew test).

    A nonzero size so replaced goes to ``dropped[p][name]``, as the single call reports
    it.  Returns X itself when no row is replaced (the usual case), else a list.
    """
    small = [p for p, size in enumerate(sizes) if size <= tol]
    if not small:
        return X
    rows = list(X)
    for p in small:
        rows[p] = zero
        if sizes[p]:
            dropped[p][name] = sizes[p]
    return rows


def build_systems(scene: Scene, calls: tuple, notes: tuple, elapsed: float, balancing: bool, matrices: dict,
                  qs: np.ndarray, rel: list[float], r: np.ndarray, dropped: list[dict]) -> tuple[LinearizedSystem, ...]:  # fmt: skip
    """The batch's systems through :meth:`LinearizedSystem.stack`, with the single call's notes and figures.

    ``matrices`` maps M, D, G, S, N to a stack (P, n, n), a list of P matrices or one
    matrix shared by the batch; ``r`` holds the residuals on the free coordinates
    (kept with ``balancing``), ``rel`` the relative residuals, ``dropped`` one
    dictionary per point (taken over).
    """
    if balancing:
        point_notes = [notes + (f"held at q by constant actuator forces (relative residual {rel_i:.2e})",) for rel_i in rel]
    else:
        point_notes = [notes] * len(rel)
    try:
        return LinearizedSystem.stack(
            **matrices, dof_names=scene.dof_names, q=qs, v=scene.v0, residual=rel, balancing=r if balancing else None,
            elapsed=elapsed, calls=calls, dropped=dropped, notes=point_notes,
        )  # fmt: skip
    except SingularMassError:  # the constructor decides; the single call's message names the scene's joints
        for Mi in matrices["M"]:
            check_mass(scene, Mi)
        raise
