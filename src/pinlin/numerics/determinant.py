"""Whether a square matrix is certainly nonsingular, and the sign of its determinant (theory: stability).

The leading coefficient of p(lam) = det L(lam) is det M and p(0) = det K:
opposite signs prove a real positive root.  The signs are decided like
definiteness (:mod:`pinlin.numerics.definiteness`): against the rounding bound
c n eps sigma_max of the singular value decomposition and a relative data
uncertainty.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg.lapack import dgesdd as _dgesdd
from scipy.linalg.lapack import dgetrf as _dgetrf

from .checks import check_uncertainty
from .definiteness import DEFAULT_UNCERTAINTY, EIGENVALUE_ROUNDING, square_matrix
from .floating import EPS

__all__ = ["Nonsingularity", "nonsingularity", "validated_nonsingularity", "det_sign"]


@dataclass(frozen=True, kw_only=True)
class Nonsingularity:
    """Whether a square matrix is certainly nonsingular, and the sign of its determinant.

    Attributes
    ----------
    sign : int
        Sign of det A when certain, else 0.
    margin : float
        ``(sigma_min - rho) / sigma_max`` (0 if negative): the largest relative
        2-norm perturbation that keeps A nonsingular (rho the rounding bound of
        the SVD, as for eigenvalues).
    uncertainty : float
    computed_sign : int
        Sign of the determinant of the matrix as factorized (0 for the zero
        matrix); certain only when ``sign`` is not 0.
    """

    sign: int
    margin: float
    uncertainty: float
    computed_sign: int = 0

    def at(self, uncertainty: float) -> Nonsingularity:
        """The same decision against another relative data uncertainty.

        Raises
        ------
        ParameterError
            ``uncertainty`` not in [0, 1).
        """
        u = check_uncertainty(uncertainty)
        return Nonsingularity(
            sign=self.computed_sign if self.margin > u else 0, margin=self.margin, uncertainty=u,
            computed_sign=self.computed_sign,
        )


def nonsingularity(
    A, uncertainty: float = DEFAULT_UNCERTAINTY, *, rounding_factor: float = EIGENVALUE_ROUNDING
) -> Nonsingularity:
    """Sign of det A from one SVD, decided against rounding and a data uncertainty.

    .. math::
        A = U \\Sigma V^T,\\quad \\operatorname{sign}\\det A = \\det U \\det V^T
        \\text{ when } \\hat\\sigma_{\\min} - c\\,n\\,\\epsilon\\,\\hat\\sigma_{\\max} > u\\,\\hat\\sigma_{\\max}

    (U, V orthogonal: their determinants are +-1 to full accuracy).

    Raises
    ------
    ParameterError
        A not a finite real square matrix; ``uncertainty`` not in [0, 1).
    """
    return validated_nonsingularity(square_matrix(A), check_uncertainty(uncertainty), rounding_factor)


def validated_nonsingularity(A: np.ndarray, u: float, rounding_factor: float = EIGENVALUE_ROUNDING) -> Nonsingularity:
    """:func:`nonsingularity` of a matrix known to be a finite real (n, n) float array, ``u`` known valid.

    For callers whose matrices are validated already (a LinearizedSystem's K): no input checks.
    """
    n = A.shape[0]
    if not A.any():
        return Nonsingularity(sign=0, margin=0.0, uncertainty=u, computed_sign=0)
    U, s, Vh, info = _dgesdd(A)
    if info != 0:  # LAPACK's divide and conquer did not converge: numpy's driver (it raises if that fails too)
        U, s, Vh = np.linalg.svd(A)
    margin = max(float((s[-1] - rounding_factor * n * EPS * s[0]) / s[0]), 0.0)
    sign = _orthogonal_sign(U) * _orthogonal_sign(Vh)
    return Nonsingularity(sign=sign if margin > u else 0, margin=margin, uncertainty=u, computed_sign=sign)


def _orthogonal_sign(Q: np.ndarray) -> int:
    """det Q (+1 or -1) of an orthogonal Q from its LU factorization: the signs of U's diagonal and the swaps."""
    lu, piv, _ = _dgetrf(Q)
    negative = int(np.count_nonzero(np.diagonal(lu) < 0)) + int(np.count_nonzero(piv != np.arange(piv.size)))
    return -1 if negative % 2 else 1


def det_sign(A, uncertainty: float = DEFAULT_UNCERTAINTY) -> int:
    """Sign of det A, or 0 when A is singular within rounding and ``uncertainty``.

    See :func:`nonsingularity`.

    Raises
    ------
    ParameterError
        A not a finite real square matrix; ``uncertainty`` not in [0, 1).
    """
    return nonsingularity(A, uncertainty).sign
