"""Eigenvalues of a product Phi_K ... Phi_1 without forming it: the lifted block-cyclic matrix (theory: Floquet).

The (K m) x (K m) matrix

.. math::

    \\mathcal{C} = \\begin{bmatrix} 0 & & & \\Phi_K \\\\ \\Phi_1 & 0 & & \\\\ & \\ddots & \\ddots & \\\\
                   & & \\Phi_{K-1} & 0 \\end{bmatrix}

has the eigenvalues lambda with lambda^K = mu for every eigenvalue mu of the product: its right eigenvector
(z_0, ..., z_{K-1}) satisfies Phi_j z_{j-1} = lambda z_j (z_K = z_0), so z_0 is an eigenvector of the product
and z_j its image at the segment boundary t_j, scaled by lambda^-j.  A backward-stable eigensolver perturbs
each Phi_j by about eps ||Phi_j||; when every segment is well conditioned (cond Phi_j <= the growth threshold)
a multiplier keeps a relative accuracy of about K eps times that threshold, however many decades separate it
from the others, while the eigenvalues of the formed product are accurate only to eps ||Phi|| absolutely.

A perturbation E_j of Phi_j moves mu to first order by

.. math::  \\delta\\mu = K \\lambda^{K-1}\\, w_j^H E_j z_{j-1} / (w^H z),

with w the left eigenvector of C (w^H C = lambda w^H).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..errors import ComputationError

__all__ = ["CyclicEigen", "cyclic_eigen"]


@dataclass(frozen=True)
class CyclicEigen:
    """The multipliers of a periodic product and their periodic eigenvectors.

    Attributes
    ----------
    multipliers : ndarray, complex (m,)
        mu_k = lambda_k^K, computed as exp(K log lambda_k) (no overflow).
    roots : ndarray, complex (m,)
        The chosen K-th roots lambda_k (one per multiplier).
    right, left : ndarray, complex (m, K, m)
        right[k, j] = z_j and left[k, j] = w_j of multiplier k (each stacked vector of unit 2-norm).
    backward_error : ndarray (m,)
        ||C z - lambda z|| / ||C||_2 for each chosen pair (unit z): the computed lambda is an exact eigenvalue of
        C + E with ||E||_2 = that times ||C||_2.
    cyclic_norm : float
        ||C||_2 = max_j ||Phi_j||_2.

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> from pinlin.periodic.cyclic import cyclic_eigen
    >>> eig = cyclic_eigen(tr.factors)
    >>> print(eig.multipliers.shape, eig.backward_error.max() < 1e-14)
    (2,) True
    """

    multipliers: np.ndarray
    roots: np.ndarray
    right: np.ndarray
    left: np.ndarray
    backward_error: np.ndarray
    cyclic_norm: float


def _lift(factors: list) -> np.ndarray:
    K, m = len(factors), factors[0].shape[0]
    C = np.zeros((K * m, K * m))
    C[:m, (K - 1) * m:] = factors[-1]
    for j in range(1, K):
        C[j * m:(j + 1) * m, (j - 1) * m:j * m] = factors[j - 1]
    return C


def _choose_roots(lam: np.ndarray, K: int, m: int) -> np.ndarray:
    """Indices of one K-th root per multiplier: the roots in a sector of angle 2 pi / K whose edge lies in the
    widest gap between the multipliers' arguments (so that rounding cannot put a root on the edge)."""
    if K == 1:
        return np.arange(lam.size)
    theta = np.mod(K * np.angle(lam), 2 * np.pi)        # the argument of mu in [0, 2 pi)
    order = np.sort(theta)
    gaps = np.diff(np.concatenate([order, [order[0] + 2 * np.pi]]))
    widest = int(np.argmax(gaps))
    cut = order[widest] + gaps[widest] / 2              # an edge far from every multiplier's argument
    # the root of mu = r exp(i phi) with argument in (cut/K - 2 pi/K, cut/K]: shift by the cut and wrap
    rel = np.mod(np.angle(lam) - cut / K, 2 * np.pi)
    chosen = np.flatnonzero(rel > 2 * np.pi - 2 * np.pi / K)
    if chosen.size != m:
        raise ComputationError(
            f"the lifted eigenproblem gave {chosen.size} roots in one sector instead of {m}: the {K} roots of "
            f"each multiplier are not separated (multipliers too close to zero or lost to rounding)")
    return chosen


def cyclic_eigen(factors: list) -> CyclicEigen:
    """Multipliers and periodic eigenvectors of Phi_K ... Phi_1 from the lifted block-cyclic matrix.

    Parameters
    ----------
    factors : list of (m, m) arrays
        Phi_1, ..., Phi_K in the order they act.

    Raises
    ------
    ComputationError
        The roots could not be grouped into one per multiplier.

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> from pinlin.periodic.cyclic import cyclic_eigen
    >>> eig = cyclic_eigen(tr.factors)
    >>> print(np.round(np.abs(eig.multipliers), 6), eig.right.shape[1] == len(tr.factors))
    [1. 1.] True
    """
    K, m = len(factors), factors[0].shape[0]
    C = _lift(factors)
    lam, W, Z = scipy.linalg.eig(C, left=True, right=True)
    chosen = _choose_roots(lam, K, m)
    lam, W, Z = lam[chosen], W[:, chosen], Z[:, chosen]
    Z = Z / np.linalg.norm(Z, axis=0)
    W = W / np.linalg.norm(W, axis=0)
    cnorm = max(float(np.linalg.norm(f, 2)) for f in factors)
    residual = np.linalg.norm(C @ Z - Z * lam, axis=0) / cnorm
    # largest modulus first; moduli equal to 1e-8 (relative) tie, and ties go by argument (conjugates adjacent)
    mu = np.exp(K * np.log(lam.astype(complex)))
    order = np.lexsort((np.angle(mu), -np.round(np.log(np.abs(mu)), 8)))
    lam, W, Z, residual, mu = lam[order], W[:, order], Z[:, order], residual[order], mu[order]
    right = Z.T.reshape(m, K, m)
    left = W.T.reshape(m, K, m)
    return CyclicEigen(mu, lam, right, left, residual, cnorm)
