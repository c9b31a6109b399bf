"""The first-order (state-space) form of a linearized system, and the null motion of a singular M.

.. math::

   z = (x, \\dot x),\\qquad \\dot z = A z + B u,\\qquad
   A = \\begin{pmatrix} 0 & I \\\\ -M^{-1} K & -M^{-1} C \\end{pmatrix},\\qquad
   B = \\begin{pmatrix} 0 \\\\ M^{-1} F \\end{pmatrix}

with M factored by Cholesky and one solve for K, C and F together.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

__all__ = ["first_order_form", "null_motion", "NULL_MOTION_SHARE"]

#: A coordinate takes part in the null motion of a singular mass matrix when its entry in
#: the unit eigenvector of the smallest eigenvalue exceeds this share: 0.3 names the few
#: coordinates that dominate the motion (an equal share over 11 coordinates is 0.30).
NULL_MOTION_SHARE = 0.3


def null_motion(M: np.ndarray, names) -> tuple[float, list[str]]:
    """Smallest eigenvalue of a symmetric M and the coordinates its eigenvector moves."""
    w, V = np.linalg.eigh(M)
    return float(w[0]), [names[i] for i in np.flatnonzero(np.abs(V[:, 0]) > NULL_MOTION_SHARE)]


def first_order_form(M: np.ndarray, C: np.ndarray, K: np.ndarray, F: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """A, B of the first-order form and the relative residual of the solves.

    The residual is ||M X - Y|| / (||M|| ||X|| + ||Y||) for X = M^-1 Y, Y = [K, C, F]
    (Frobenius norms): the backward error of the solves.  M must be symmetric
    positive definite (a :class:`~pinlin.LinearizedSystem` guarantees it).
    """
    n = M.shape[0]
    Y = np.hstack([K, C, F])
    X = sla.cho_solve(sla.cho_factor(M), Y)
    denom = np.linalg.norm(M) * np.linalg.norm(X) + np.linalg.norm(Y)
    error = float(np.linalg.norm(M @ X - Y) / denom) if denom > 0 else 0.0
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    # (+ 0.0: -X of an exact zero is -0., which python-control and every printout would show as "-0")
    A[n:, :n] = -X[:, :n] + 0.0
    A[n:, n:] = -X[:, n : 2 * n] + 0.0
    B = np.zeros((2 * n, F.shape[1]))
    B[n:] = X[:, 2 * n :] + 0.0
    return A, B, error
