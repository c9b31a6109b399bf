"""Following modes through a parameter sweep by their shapes, not by sorting.

Sorting eigenvalues by frequency at each step swaps two modes wherever their
frequencies cross, and a Campbell diagram drawn from sorted data shows false
veering.  :func:`track_modes` instead matches the modes of each step to those of
the previous step by the modal assurance criterion of their shapes,

.. math::  \\mathrm{MAC}(x, y) = \\frac{|x^H y|^2}{(x^H x)(y^H y)},

solved as an assignment problem (Hungarian algorithm), with the eigenvalue
distance as a tie-breaker (a mode and its complex conjugate have the same MAC).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from ..errors import ParameterError
from ..errors.deprecated import deprecated_names, renamed_keywords
from ..numerics.arrays import readonly
from ..results import Result

__all__ = [
    "TrackedModes",
    "track_modes",
    "mac",
    "one_per_conjugate_pair",
    "DEFAULT_EIGENVALUE_WEIGHT",
    "CONJUGATE_TOL",
    "IMAG_SIGN_RTOL",
]

#: Weight of the relative eigenvalue distance against 1 - MAC: a mode and its
#: complex conjugate have equal MAC, and half a unit of cost for swapping them
#: (their relative distance is ~1) decides between them without overriding a
#: clear shape match (1 - MAC of a wrong shape is ~1).
DEFAULT_EIGENVALUE_WEIGHT = 0.5
#: Columns j, k of tracked eigenvalues are a conjugate pair when lam_k = conj(lam_j) to this relative
#: distance at every step: far above rounding of computed pairs (~1e-15), far below distinct modes.
CONJUGATE_TOL = 1e-8
#: An unpaired column counts as Im lambda >= 0 when Im lambda >= -this * (1 + |lambda|): rounding of a
#: real eigenvalue's zero imaginary part.
IMAG_SIGN_RTOL = 1e-12


def mac(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Modal assurance criterion between the columns of X (n, a) and Y (n, b): (a, b) in [0, 1].

    Examples
    --------
    >>> from pinlin.studies import mac
    >>> mac(np.eye(2), np.array([[1.0, 1.0], [0.0, 1.0]]))
    array([[1. , 0.5],
           [0. , 0.5]])
    """
    X = np.asarray(X)
    Y = np.asarray(Y)
    cross = np.abs(X.conj().T @ Y) ** 2
    nx = np.einsum("ij,ij->j", X.conj(), X).real
    ny = np.einsum("ij,ij->j", Y.conj(), Y).real
    return cross / np.maximum(np.outer(nx, ny), np.finfo(float).tiny)


@dataclass(frozen=True, repr=False, eq=False)
class TrackedModes(Result):
    """Eigenvalues (and shapes) reordered so that column j is the same mode at every step.

    Attributes
    ----------
    eigenvalues : (steps, m) complex ndarray
        lam [1/s], one row per step, one column per followed mode.
    vectors : (steps, n, m) complex ndarray or None
        The mode shapes in the same order (None when none were given).
    order : (steps, m) int ndarray
        ``eigenvalues[s] = input[s][order[s]]``.
    match : (steps,) ndarray
        The smallest MAC between a mode and its match at the previous step (1 at
        step 0; nan without shapes): low values flag steps too coarse to follow.
    jump : (steps,) ndarray
        The largest relative eigenvalue distance |lam_s - lam_{s-1}| / (|lam_s| +
        |lam_{s-1}|) between a mode and its match at the previous step (0 at step 0).
    method : str
        How the modes were matched (MAC of the shapes with the eigenvalue distance
        as tie-breaker, or the eigenvalue distance alone).
    error : float
        The matching defect of the worst match, in [0, 1] (0: every mode matched
        perfectly; near 1: some step is too coarse to follow a mode): with shapes
        ``1 - min(match)``, without shapes ``max(jump)``.
    elapsed : float
        Wall time [s] of :func:`track_modes`.

    Examples
    --------
    >>> from pinlin.studies import track_modes
    >>> tracked = track_modes([[1.0, 2.0], [2.5, 1.5], [3.1, 1.1]])  # by eigenvalue distance alone
    >>> tracked.eigenvalues.real
    array([[1. , 2. ],
           [1.5, 2.5],
           [1.1, 3.1]])
    >>> tracked.order.tolist(), tracked.vectors is None
    ([[0, 1], [1, 0], [1, 0]], True)
    """

    eigenvalues: np.ndarray
    vectors: np.ndarray | None
    order: np.ndarray
    match: np.ndarray
    jump: np.ndarray
    method: str
    error: float
    elapsed: float

    def __repr__(self) -> str:
        steps, m = self.eigenvalues.shape
        shapes = "with shapes" if self.vectors is not None else "without shapes"
        return (
            f"TrackedModes({steps} steps x {m} modes, {shapes}, error={self.error:.2e}, "
            f"elapsed={self.elapsed * 1e3:.3g} ms)"
        )


def _checked(eigenvalues, vectors, eigenvalue_weight) -> tuple[np.ndarray, np.ndarray | None]:
    lam = np.asarray(eigenvalues, dtype=complex)
    if lam.ndim != 2 or lam.shape[0] == 0:
        raise ParameterError("eigenvalues", f"expected shape (steps, m), got {lam.shape}")
    if not np.all(np.isfinite(lam)):
        raise ParameterError("eigenvalues", "has non-finite values")
    if not (np.isfinite(eigenvalue_weight) and eigenvalue_weight >= 0):
        raise ParameterError("eigenvalue_weight", f"must be >= 0, got {eigenvalue_weight!r}")
    if vectors is None:
        return lam, None
    steps, m = lam.shape
    X = np.asarray(vectors, dtype=complex)
    if X.ndim != 3 or X.shape[0] != steps or X.shape[2] != m:
        raise ParameterError("vectors", f"expected shape ({steps}, n, {m}), got {X.shape}")
    if not np.all(np.isfinite(X)):
        raise ParameterError("vectors", "has non-finite values")
    return lam, X


def _relative_distance(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """|a_i - b_j| / (|a_i| + |b_j|) for every pair, in [0, 1]."""
    scale = np.abs(a)[:, None] + np.abs(b)[None, :] + np.finfo(float).tiny
    return np.abs(a[:, None] - b[None, :]) / scale


def track_modes(eigenvalues, vectors=None, *, eigenvalue_weight: float = DEFAULT_EIGENVALUE_WEIGHT) -> TrackedModes:
    """Reorder the modes of a sweep so that each column follows one mode.

    At each step the modes are assigned to those of the previous step by
    minimizing the total cost

    .. math::  c_{ij} = 1 - \\mathrm{MAC}(x_i, x_j)
               + w \\frac{|\\lambda_i - \\lambda_j|}{|\\lambda_i| + |\\lambda_j|}

    (the MAC term only with shapes), solved exactly (Hungarian algorithm).

    Parameters
    ----------
    eigenvalues : (steps, m) array_like
        Eigenvalues [1/s] at each step, in any order.
    vectors : (steps, n, m) array_like, optional
        The matching mode shapes (right eigenvectors as columns).  Without them
        the modes are matched by eigenvalue distance alone.
    eigenvalue_weight : float
        Weight w of the relative eigenvalue distance in the assignment cost (>= 0);
        see :data:`DEFAULT_EIGENVALUE_WEIGHT`.

    Returns
    -------
    TrackedModes
        ``error`` is the matching defect of the worst match (see its docstring).

    Raises
    ------
    ParameterError
        Shapes that do not agree, non-finite values, a negative weight.

    Examples
    --------
    Two modes cross between the steps; sorted eigenvalues hide it, the shapes show it:

    >>> from pinlin.studies import track_modes
    >>> lam = np.array([[1.0, 2.0], [1.8, 2.2]])
    >>> shapes = np.array([np.eye(2), np.eye(2)[:, ::-1]])
    >>> tracked = track_modes(lam, shapes)
    >>> tracked.eigenvalues.real
    array([[1. , 2. ],
           [2.2, 1.8]])
    >>> float(tracked.error)
    0.0
    """
    t0 = time.perf_counter()
    lam, X = _checked(eigenvalues, vectors, eigenvalue_weight)
    steps, m = lam.shape
    order = np.empty((steps, m), dtype=int)
    order[0] = np.arange(m)
    match = np.full(steps, np.nan if X is None else 1.0)
    jump = np.zeros(steps)
    for s in range(1, steps):
        distance = _relative_distance(lam[s - 1, order[s - 1]], lam[s])
        cost = eigenvalue_weight * distance
        if X is not None:
            similarity = mac(X[s - 1][:, order[s - 1]], X[s])
            cost = cost + (1.0 - similarity)
        rows, cols = linear_sum_assignment(cost)
        order[s, rows] = cols
        jump[s] = distance[rows, cols].max(initial=0.0)
        if X is not None:
            match[s] = similarity[rows, cols].min(initial=1.0)
    tracked = np.take_along_axis(lam, order, axis=1)
    tracked_vectors = None if X is None else readonly(np.take_along_axis(X, order[:, None, :], axis=2))
    if X is not None:
        method = f"assignment by shape (1 - MAC) plus {eigenvalue_weight:g} x relative eigenvalue distance"
        error = float(1.0 - match.min())
    else:
        method = "assignment by relative eigenvalue distance (no shapes given)"
        error = float(jump.max())
    return TrackedModes(
        readonly(tracked), tracked_vectors, readonly(order), readonly(match), readonly(jump), method, error,
        time.perf_counter() - t0,
    )


@renamed_keywords(rtol="conjugate_tol")
def one_per_conjugate_pair(lam, conjugate_tol: float = CONJUGATE_TOL) -> list[int]:
    """Columns of tracked eigenvalues (steps, m) to draw: one of each conjugate pair.

    Columns j and k are a pair when lam[:, k] = conj(lam[:, j]) at every step
    (relative to the step's largest |lam|); of a pair the column with the larger
    sum of Im lam is kept.  Unpaired columns are kept when Im lam >= 0 throughout
    (to :data:`IMAG_SIGN_RTOL`).  Campbell diagrams draw these columns.

    Parameters
    ----------
    lam : (steps, m) array_like
        Tracked eigenvalues [1/s] (``TrackedModes.eigenvalues``).
    conjugate_tol : float
        Relative distance within which two columns are conjugates (see :data:`CONJUGATE_TOL`;
        ``rtol`` before 0.4).

    Raises
    ------
    ParameterError
        ``lam`` not two-dimensional.

    Examples
    --------
    >>> from pinlin.studies import one_per_conjugate_pair
    >>> one_per_conjugate_pair(np.array([[1j, -1j, -0.5], [2j, -2j, -0.4]]))
    [0, 2]
    """
    lam = np.asarray(lam, dtype=complex)
    if lam.ndim != 2:
        raise ParameterError("lam", f"expected shape (steps, m), got {lam.shape}")
    scale = np.abs(lam).max(axis=1, keepdims=True) + np.finfo(float).tiny
    keep: list[int] = []
    used: set[int] = set()
    for j in range(lam.shape[1]):
        if j in used:
            continue
        dist = np.max(np.abs(lam - np.conj(lam[:, [j]])) / scale, axis=0)
        dist[j] = np.inf
        dist[list(used)] = np.inf
        k = int(np.argmin(dist))
        if dist[k] <= conjugate_tol:
            used.update((j, k))
            keep.append(j if lam[:, j].imag.sum() >= lam[:, k].imag.sum() else k)
        elif np.all(lam[:, j].imag >= -IMAG_SIGN_RTOL * (1 + np.abs(lam[:, j]))):
            keep.append(j)
    return sorted(keep)


__getattr__ = deprecated_names(__name__, {"CONJUGATE_RTOL": (f"{__name__}.CONJUGATE_TOL", lambda: CONJUGATE_TOL)})
