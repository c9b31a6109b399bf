"""The first-order (state-space) form of a linearized system, and the null motion of a singular M.

.. math::

   z = (x, \\dot x),\\qquad \\dot z = A z + B u,\\qquad
   A = \\begin{pmatrix} 0 & I \\\\ -M^{-1} K & -M^{-1} C \\end{pmatrix},\\qquad
   B = \\begin{pmatrix} 0 \\\\ M^{-1} F \\end{pmatrix}

with one (LU) solve for K, C and F together, on one system or a stack of them.
"""

from __future__ import annotations

import numpy as np

from ..errors import SingularMassError

__all__ = ["first_order_form", "null_motion", "NULL_MOTION_SHARE"]

#: A coordinate takes part in the null motion of a singular mass matrix when its entry in
#: the unit eigenvector of the smallest eigenvalue exceeds this share: 0.3 names the few
#: coordinates that dominate the motion (an equal share over 11 coordinates is 0.30).
NULL_MOTION_SHARE = 0.3


def null_motion(M: np.ndarray, names) -> tuple[float, list[str]]:
    """Smallest eigenvalue of a symmetric M and the coordinates its eigenvector moves.

    Examples
    --------
    >>> from pinlin.linearization.state_form import null_motion
    >>> value, moved = null_motion(np.diag([1e-12, 1.0]), ["x", "y"])
    >>> print(f"{value:.1e}", moved)
    1.0e-12 ['x']
    """
    w, V = np.linalg.eigh(M)
    return float(w[0]), [names[i] for i in np.flatnonzero(np.abs(V[:, 0]) > NULL_MOTION_SHARE)]


def first_order_form(M, C, K, F=None, *, times=None,
                     residual: bool = True) -> tuple[np.ndarray, np.ndarray | None, float | np.ndarray | None]:
    """A, B of the first-order form and the relative residual of the solves, for one system or a stack.

    Parameters
    ----------
    M, C, K : (..., n, n) array_like
        One system (n, n) or a stack (B, n, n); M nonsingular (not necessarily symmetric).
    F : (..., n, k) array_like or None
        Input matrix (generalized forces f = F u); None: no B.
    times : (B,) array_like or None
        The time [s] of each matrix (one for a single system), named in the error when M is singular there.
    residual : bool
        Compute ``error`` (one more product; the Floquet integrators, which form A at every node, skip it).

    Returns
    -------
    A : (..., 2n, 2n) ndarray
    B : (..., 2n, k) ndarray or None
    error : float, (B,) ndarray or None
        None when ``residual`` is False, else ||M X - Y||_F / (||M||_F ||X||_F + ||Y||_F) for X = M^-1 Y, Y = [K, C, F]: the backward error of the
        solves (0 where Y = 0).

    Raises
    ------
    SingularMassError
        M (of some matrix of the stack) is singular.

    Examples
    --------
    >>> from pinlin.linearization.state_form import first_order_form
    >>> A, B, error = first_order_form([[2.0]], [[0.4]], [[8.0]], [[2.0]])
    >>> print(A, B.ravel(), error < 1e-15)
    [[ 0.   1. ]
     [-4.  -0.2]] [0. 1.] True
    """
    M, C, K = (np.asarray(X, dtype=float) for X in (M, C, K))
    n = M.shape[-1]
    parts = [K, C]
    if F is not None:
        F = np.asarray(F, dtype=float)
        parts.append(np.broadcast_to(F, (*M.shape[:-1], F.shape[-1])))
    Y = np.concatenate(parts, axis=-1)
    try:
        X = np.linalg.solve(M, Y)
    except np.linalg.LinAlgError:
        raise _singular(M, times) from None
    error = _residual(M, X, Y) if residual else None
    A = np.zeros((*M.shape[:-2], 2 * n, 2 * n))
    A[..., :n, n:] = np.eye(n)
    # (+ 0.0: -X of an exact zero is -0., which python-control and every printout would show as "-0")
    A[..., n:, :] = -X[..., : 2 * n] + 0.0
    B = None
    if F is not None:
        B = np.zeros((*M.shape[:-2], 2 * n, Y.shape[-1] - 2 * n))
        B[..., n:, :] = X[..., 2 * n :] + 0.0
    return A, B, error


def _residual(M: np.ndarray, X: np.ndarray, Y: np.ndarray) -> float | np.ndarray:
    """||M X - Y||_F / (||M||_F ||X||_F + ||Y||_F) per matrix (0 where Y = 0)."""
    def fro(Z):
        return np.linalg.norm(Z, axis=(-2, -1))
    denom = fro(M) * fro(X) + fro(Y)
    norm = fro(M @ X - Y)
    error = np.divide(norm, denom, out=np.zeros_like(norm), where=denom > 0)
    return float(error) if error.ndim == 0 else error


def _singular(M: np.ndarray, times) -> SingularMassError:
    """The error naming the first singular M of a stack (and its time, when known)."""
    stack = M.reshape(-1, *M.shape[-2:])
    bad = next((k for k in range(stack.shape[0]) if np.linalg.matrix_rank(stack[k]) < M.shape[-1]), 0)
    where = "" if M.ndim == 2 else f" (matrix {bad} of the stack)"
    if times is not None:
        where = f" at t = {float(np.ravel(times)[bad]):.6g} s"
    return SingularMassError(f"M is singular{where}", ())
