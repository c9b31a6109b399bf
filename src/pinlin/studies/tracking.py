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

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from ..errors import ParameterError

__all__ = ["TrackedModes", "track_modes", "mac"]


def mac(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Modal assurance criterion between the columns of X (n, a) and Y (n, b): (a, b) in [0, 1]."""
    X = np.asarray(X)
    Y = np.asarray(Y)
    cross = np.abs(X.conj().T @ Y) ** 2
    nx = np.einsum("ij,ij->j", X.conj(), X).real
    ny = np.einsum("ij,ij->j", Y.conj(), Y).real
    return cross / np.maximum(np.outer(nx, ny), np.finfo(float).tiny)


@dataclass(frozen=True)
class TrackedModes:
    """Eigenvalues (and shapes) reordered so that column j is the same mode at every step.

    Attributes
    ----------
    eigenvalues : (steps, m) complex ndarray
    vectors : (steps, n, m) complex ndarray or None
    order : (steps, m) int ndarray
        ``eigenvalues[s] = input[s][order[s]]``.
    match : (steps,) ndarray
        The smallest MAC between a mode and its match at the previous step (1 at
        step 0; nan without shapes): low values flag steps too coarse to follow.
    """

    eigenvalues: np.ndarray
    vectors: np.ndarray | None
    order: np.ndarray
    match: np.ndarray


def track_modes(eigenvalues, vectors=None, *, eigenvalue_weight: float = 0.5) -> TrackedModes:
    """Reorder the modes of a sweep so that each column follows one mode.

    Parameters
    ----------
    eigenvalues : (steps, m) array_like
        Eigenvalues at each step, in any order.
    vectors : (steps, n, m) array_like, optional
        The matching mode shapes (right eigenvectors as columns).  Without them
        the modes are matched by eigenvalue distance alone.
    eigenvalue_weight : float
        Weight of the relative eigenvalue distance |lam_i - lam_j| / (|lam_i| +
        |lam_j|) added to 1 - MAC in the assignment cost (>= 0).

    Raises
    ------
    ParameterError
        Shapes that do not agree, non-finite values, a negative weight.
    """
    lam = np.asarray(eigenvalues, dtype=complex)
    if lam.ndim != 2 or lam.shape[0] == 0:
        raise ParameterError("eigenvalues", f"expected shape (steps, m), got {lam.shape}")
    if not np.all(np.isfinite(lam)):
        raise ParameterError("eigenvalues", "has non-finite values")
    if not (np.isfinite(eigenvalue_weight) and eigenvalue_weight >= 0):
        raise ParameterError("eigenvalue_weight", f"must be >= 0, got {eigenvalue_weight!r}")
    steps, m = lam.shape
    X = None
    if vectors is not None:
        X = np.asarray(vectors, dtype=complex)
        if X.ndim != 3 or X.shape[0] != steps or X.shape[2] != m:
            raise ParameterError("vectors", f"expected shape ({steps}, n, {m}), got {X.shape}")
        if not np.all(np.isfinite(X)):
            raise ParameterError("vectors", "has non-finite values")
    order = np.empty((steps, m), dtype=int)
    order[0] = np.arange(m)
    match = np.full(steps, np.nan if X is None else 1.0)
    for s in range(1, steps):
        prev = lam[s - 1, order[s - 1]]
        scale = np.abs(prev)[:, None] + np.abs(lam[s])[None, :] + np.finfo(float).tiny
        cost = eigenvalue_weight * np.abs(prev[:, None] - lam[s][None, :]) / scale
        if X is not None:
            similarity = mac(X[s - 1][:, order[s - 1]], X[s])
            cost = cost + (1.0 - similarity)
        rows, cols = linear_sum_assignment(cost)
        order[s, rows] = cols
        if X is not None:
            match[s] = similarity[rows, cols].min()
    tracked = np.take_along_axis(lam, order, axis=1)
    tracked_vectors = None
    if X is not None:
        tracked_vectors = np.take_along_axis(X, order[:, None, :], axis=2)
    return TrackedModes(tracked, tracked_vectors, order, match)
