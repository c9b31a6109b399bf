"""Backward errors, condition numbers and error bounds of eigenpairs (SPEC section 4).

For an eigenpair (lam, x) with left vector y (``y^T L(lam) = 0``, plain
transpose) of L(lam) = lam^2 M + lam C + K, with Frobenius norms:

.. math::
    \\eta(x, \\lambda) = \\frac{\\|L(\\lambda) x\\|}
        {(|\\lambda|^2 \\|M\\| + |\\lambda| \\|C\\| + \\|K\\|)\\,\\|x\\|}

.. math::
    \\kappa = \\frac{\\sqrt{|a|^4\\|M\\|^2 + |a|^2|b|^2\\|C\\|^2 + |b|^4\\|K\\|^2}}
        {|y^H (2 a \\bar b M + (|b|^2 - |a|^2) C - 2 \\bar a b K) x|}

in the homogeneous form lam = a/b, |a|^2 + |b|^2 = 1, ||x|| = ||y|| = 1
(Dedieu-Tisseur).  With pinlin's plain-transpose left vectors y^H of the
formula is our y^T.  The first-order absolute error bound of lam is Tisseur's
relative condition number times eta |lam|:

.. math::
    |\\Delta\\lambda| \\lesssim r = \\eta\\,
        \\frac{(|\\lambda|^2\\|M\\| + |\\lambda|\\|C\\| + \\|K\\|)\\,\\|x\\|\\,\\|y\\|}
        {|y^T L'(\\lambda) x|},\\qquad L'(\\lambda) = 2\\lambda M + C

(the SPEC section 5 "kappa eta |lambda|"), which stays finite at lam = 0.  It
is a first-order estimate, infinite for a defective eigenvalue.  In the bound
eta is taken at least :data:`ETA_FLOOR` (the unit roundoff eps): a residual
that happens to round to less does not make the eigenvalue more accurate than
the floating-point data it came from.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .problem import QuadraticProblem

__all__ = ["PairFigures", "pair_figures", "homogeneous", "ETA_FLOOR"]

#: Smallest backward error used in error bounds (machine epsilon).
ETA_FLOOR = float(np.finfo(float).eps)


def homogeneous(lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(a, b) with lam = a / b and |a|^2 + |b|^2 = 1, b real >= 0, without overflow."""
    lam = np.asarray(lam, dtype=complex)
    r = np.abs(lam)
    small = r <= 1
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(small, 1.0, 1.0 / np.where(r == 0, 1.0, r))
        b_small = 1.0 / np.sqrt(1.0 + r * r * small)
        b_big = inv / np.sqrt(1.0 + inv * inv)
    b = np.where(small, b_small, b_big)
    a = lam * b
    return a, b


@dataclass(frozen=True)
class PairFigures:
    """Normalized vectors and the accuracy figures of a set of eigenpairs.

    Attributes
    ----------
    right : (n, k) complex
        Right eigenvectors, unit 2-norm.
    left : (n, k) complex
        Left eigenvectors scaled so that y^T L'(lam) x = 1 where ``left_normalized``,
        unit 2-norm otherwise.
    left_normalized : (k,) bool
    derivative : (k,) complex
        y^T L'(lam) x for the unit-norm x and y (0 for a defective eigenvalue).
    backward_error, condition, error_bound : (k,) float
    left_unit : (n, k) complex
        The left vectors with unit 2-norm.
    products : tuple of three (n, k) complex
        M x, C x, K x for the unit-norm right vectors.
    """

    right: np.ndarray
    left: np.ndarray
    left_normalized: np.ndarray
    derivative: np.ndarray
    backward_error: np.ndarray
    condition: np.ndarray
    error_bound: np.ndarray
    left_unit: np.ndarray
    products: tuple[np.ndarray, np.ndarray, np.ndarray]


def _colnorm(A: np.ndarray) -> np.ndarray:
    return np.sqrt(np.einsum("ij,ij->j", A.real, A.real) + np.einsum("ij,ij->j", A.imag, A.imag))


def backward_errors(problem: QuadraticProblem, lam, X, MX, CX, KX) -> np.ndarray:
    """eta for each column of X (any scaling), given the products M X, C X, K X.

    A zero column gives inf; an exactly zero residual gives 0.
    """
    R = MX * (lam * lam) + CX * lam + KX
    num = _colnorm(R)
    with np.errstate(divide="ignore", invalid="ignore"):
        eta = num / (problem.weight(lam) * _colnorm(X))
    # an exact residual 0 is eta = 0 even where the weight vanishes (lam = 0, K = 0)
    return np.where(num == 0, 0.0, np.where(np.isfinite(eta), eta, np.inf))


def pair_figures(problem: QuadraticProblem, lam, X, Y, MX, CX, KX) -> PairFigures:
    """Normalize X and Y and compute eta, kappa and the first-order bound for each pair.

    Parameters
    ----------
    problem : QuadraticProblem
    lam : (k,) complex
    X, Y : (n, k) complex
        Right and left (plain transpose) eigenvectors, any nonzero scaling.
    MX, CX, KX : (n, k) complex
        The products M X, C X, K X (computed once by the solver path, which
        often can do it cheaper than here).
    """
    lam = np.asarray(lam, dtype=complex)
    nx = _colnorm(X)
    ny = _colnorm(Y)
    X, MX, CX, KX = X / nx, MX / nx, CX / nx, KX / nx
    Y = Y / ny
    eta = backward_errors(problem, lam, X, MX, CX, KX)
    yMx = np.einsum("ij,ij->j", Y, MX)
    yCx = np.einsum("ij,ij->j", Y, CX)
    yKx = np.einsum("ij,ij->j", Y, KX)
    deriv = 2 * lam * yMx + yCx
    a, b = homogeneous(lam)
    aa, bb = np.abs(a) ** 2, np.abs(b) ** 2
    num = np.sqrt(aa * aa * problem.norm_M**2 + aa * bb * problem.norm_C**2 + bb * bb * problem.norm_K**2)
    den = np.abs(2 * a * np.conj(b) * yMx + (bb - aa) * yCx - 2 * np.conj(a) * b * yKx)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = np.where(den > 0, num / np.where(den > 0, den, 1.0), np.inf)
        eta_floor = np.maximum(eta, ETA_FLOOR)
        bound = np.where(
            np.abs(deriv) > 0, eta_floor * problem.weight(lam) / np.where(deriv != 0, np.abs(deriv), 1.0), np.inf
        )
    ok = np.abs(deriv) > 0
    left = np.where(ok, Y / np.where(ok, deriv, 1.0), Y)
    return PairFigures(X, left, ok, deriv, eta, kappa, bound, Y, (MX, CX, KX))
