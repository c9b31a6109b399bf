"""The first-order (state-space) form of the linearized equations.

.. math::
    z = \\begin{bmatrix} x \\\\ \\dot x \\end{bmatrix},\\qquad
    \\dot z = A z + B f,\\qquad
    A = \\begin{bmatrix} 0 & I \\\\ -M^{-1} K & -M^{-1} C \\end{bmatrix},\\quad
    B = \\begin{bmatrix} 0 \\\\ M^{-1} \\end{bmatrix}

(SPEC section 1 with C = D + G, K = S + N).  Its eigenvalues are those of the
dynamic stiffness L(lam) = lam^2 M + lam C + K.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from ..linearization.system import LinearizedSystem
from ..numerics import check_system

__all__ = ["first_order"]


def first_order(sys: LinearizedSystem) -> tuple[np.ndarray, np.ndarray]:
    """A (2n x 2n) and B (2n x n) of the first-order form (M is factored by Cholesky).

    Raises
    ------
    ParameterError
        ``sys`` is not a LinearizedSystem.
    """
    check_system(sys)
    n = sys.n
    factor = scipy.linalg.cho_factor(sys.M)
    Minv_K = scipy.linalg.cho_solve(factor, sys.K)
    Minv_C = scipy.linalg.cho_solve(factor, sys.C)
    Minv = scipy.linalg.cho_solve(factor, np.eye(n))
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -Minv_K
    A[n:, n:] = -Minv_C
    B = np.zeros((2 * n, n))
    B[n:] = Minv
    return A, B
