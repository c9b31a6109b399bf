"""M(t) x'' + C(t) x' + K(t) x = 0 in first-order form, and the test of its conservative structure
(theory: Floquet).

.. math::  A = \\begin{bmatrix} 0 & I \\\\ -M^{-1} K & -M^{-1} C \\end{bmatrix}

by solves with M (no inverse: :func:`~pinlin.linearization.state_form.first_order_form`).  The system counts
as conservative when M is symmetric and constant, C is skew and constant and K symmetric:
:func:`structure_defect` measures how far sampled coefficients are from that, each part relative (max-norms).  A time-varying M or G is conservative too when the equations are the
variational equations of a Lagrangian L = x'^T M x' / 2 + x'^T F x - x^T S x / 2 (M, S symmetric, F any):
Euler-Lagrange gives

.. math::  M \\ddot x + (\\dot M + F - F^T)\\, \\dot x + (S + \\dot F)\\, x = 0,

so sym(C) = M' and skew(K) = skew(C)' / 2, and Phi(T) is symplectic for the same
Omega = [[skew(C), M], [-M, 0]] at t = 0; :func:`lagrangian_defect` measures those two identities from the
samples and the derivatives of their trigonometric interpolant.
"""

from __future__ import annotations

import numpy as np

from ..linearization.state_form import first_order_form

__all__ = ["SecondOrderA", "structure_defect", "lagrangian_defect"]

_TINY = float(np.finfo(float).tiny)


def structure_defect(M: np.ndarray, C: np.ndarray, K: np.ndarray, M0: np.ndarray, C0: np.ndarray) -> float:
    """max of asym(M), asym(K) (relative to M, K) and sym(C), M - M0, C - C0 (relative to |M| + |C| + |K|)
    over stacks (B, n, n) of coefficients: 0 for a conservative system with constant M and G.

    Examples
    --------
    >>> from pinlin.periodic.second_order import structure_defect
    >>> M, C, K = np.eye(2)[None], np.array([[[0.0, 1.0], [-1.0, 0.0]]]), np.diag([2.0, 3.0])[None]
    >>> structure_defect(M, C, K, M[0], C[0])                   # constant M, skew C, symmetric K
    0.0
    >>> print(f"{structure_defect(M, C + 0.1 * np.eye(2), K, M[0], C[0]):.4f}")   # a damping 0.1: 0.2 / 5
    0.0400
    """
    def size(X):
        return np.abs(X).max(axis=(-2, -1))
    sM, sK = size(M) + _TINY, size(K) + _TINY
    big = sM + size(C) + sK
    swap = (0, 2, 1)
    parts = (size(M - M.transpose(swap)) / sM, size(K - K.transpose(swap)) / sK,
             np.maximum(np.maximum(size(C + C.transpose(swap)), size(M - M0)), size(C - C0)) / big)
    return float(max(p.max() for p in parts))


class SecondOrderA:
    """t -> A(t) from checked callables M, C, K, recording the largest conservative-structure defect seen
    (:func:`structure_defect` against M(0), C(0)); it stops measuring once the defect passes ``give_up``
    (the structure test's tolerance).

    Examples
    --------
    >>> from pinlin.periodic.second_order import SecondOrderA
    >>> A = SecondOrderA(lambda t: np.eye(1), lambda t: np.zeros((1, 1)), lambda t: np.array([[2.0 + np.cos(t)]]), 1,
    ...                  give_up=1e-14)
    >>> print(A(0.0).tolist(), A.defect)
    [[0.0, 1.0], [-3.0, 0.0]] 0.0
    """

    def __init__(self, fM, fC, fK, n, give_up: float):
        self.fM, self.fC, self.fK, self.n = fM, fC, fK, n
        self.M0, self.C0 = fM(0.0), fC(0.0)
        self.defect = 0.0
        self.give_up = give_up

    def __call__(self, t: float) -> np.ndarray:
        M, C, K = self.fM(t), self.fC(t), self.fK(t)
        A = first_order_form(M, C, K, times=[t], residual=False)[0]
        if self.defect <= self.give_up:    # once clearly not conservative, stop measuring
            self.defect = max(self.defect, structure_defect(M[None], C[None], K[None], self.M0, self.C0))
        return A


def lagrangian_defect(M: np.ndarray, C: np.ndarray, K: np.ndarray, dM: np.ndarray, dC: np.ndarray,
                      rate: float) -> float:
    """max of ||sym(C) - M'|| and ||skew(K) - skew(C)' / 2|| over stacks (B, n, n) of samples and their time
    derivatives, relative to |C| + rate |M| and |K| + rate |C| (max-norms; ``rate`` [1/s] the highest
    frequency of the interpolant, N / 2 times 2 pi / T, by which differentiation amplifies rounding): 0 for the
    variational equation of a Lagrangian system.

    Examples
    --------
    >>> from pinlin.periodic.second_order import lagrangian_defect
    >>> M, dM = np.eye(2)[None], np.zeros((1, 2, 2))
    >>> C = dC = np.zeros((1, 2, 2))
    >>> lagrangian_defect(M, C, np.diag([2.0, 3.0])[None], dM, dC, 1.0)
    0.0
    """
    def size(X):
        return float(np.abs(X).max())
    swap = (0, 2, 1)
    symC = (C + C.transpose(swap)) / 2
    skewK, skew_dC = (K - K.transpose(swap)) / 2, (dC - dC.transpose(swap)) / 2
    first = size(symC - dM) / (size(C) + rate * size(M) + _TINY)
    second = size(skewK - skew_dC / 2) / (size(K) + rate * size(C) + _TINY)
    return max(first, second)
