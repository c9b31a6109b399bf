"""Backward errors, condition numbers and error bounds of eigenpairs (theory: spectrum).

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

(the theory: stability "kappa eta |lambda|"), which stays finite at lam = 0.  It
is a first-order estimate, infinite for a defective eigenvalue.  In the bound
eta is taken at least :data:`~pinlin.numerics.ETA_FLOOR` (machine epsilon).
eta and kappa themselves are computed by :mod:`pinlin.numerics.accuracy`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..numerics.accuracy import ETA_FLOOR, backward_errors, homogeneous, residual_figures
from ..numerics.norms import column_norms
from .problem import QuadraticProblem
from .qualitative import quadratic_forms

__all__ = [
    "PairFigures",
    "pair_figures",
    "ErrorModel",
    "DefectiveBound",
    "defective_scale",
    "homogeneous",
    "backward_errors",
    "ETA_FLOOR",
]


@dataclass(frozen=True, kw_only=True)
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
    backward_error, error_bound : (k,) float
    sensitivity : (k,) float
        w(lam) ||x|| ||y|| / |y^T L'(lam) x| [rad/s]: the first-order change of lam per
        unit relative (normwise) perturbation of the coefficients; inf when
        y^T L' x = 0.  ``error_bound = max(eta, ETA_FLOOR) * sensitivity``.
    left_unit : (n, k) complex
        The left vectors with unit 2-norm.
    products : (3, k) complex
        y^T M x, y^T C x, y^T K x of the unit vectors (the condition number
        kappa follows from them, :func:`pinlin.numerics.condition_numbers`).
    quadratic : (3, k) complex
        x^H M x, x^H C x, x^H K x of the unit right vectors (the modal constants
        follow from them, :func:`pinlin.spectral.qualitative.constants_of`).
    weight : (k,) float or None
        w(lam) = |lam|^2 ||M|| + |lam| ||C|| + ||K|| as the figures were formed with (the cluster
        stage reuses it); None when not given.
    """

    right: np.ndarray
    left: np.ndarray
    left_normalized: np.ndarray
    derivative: np.ndarray
    backward_error: np.ndarray
    error_bound: np.ndarray
    sensitivity: np.ndarray
    left_unit: np.ndarray
    products: np.ndarray
    quadratic: np.ndarray
    weight: np.ndarray | None = None


def pair_figures(problem: QuadraticProblem, lam, P, Y=None, eta=None, norm_x=None, weight=None) -> PairFigures:
    """Normalize the vectors and compute eta, kappa and the first-order bound for each pair.

    Parameters
    ----------
    problem : QuadraticProblem
    lam : (k,) complex
    P : (4, n, k) complex
        Right eigenvectors X (any nonzero scaling) and the products M X, C X,
        K X (computed once by the solver path, which often can do it cheaper
        than here), stacked.
    Y : (n, k) complex, optional
        Left (plain transpose) eigenvectors, any nonzero scaling; None when L is
        symmetric (the left vectors are the right ones).
    eta : (k,) float, optional
        The backward errors when the solver path measured them already (they do
        not depend on the scaling of X); computed here otherwise.
    norm_x, weight : (k,) float, optional
        ||x|| of the columns of X and w(lam), when the solver path formed them
        with ``eta`` (:func:`pinlin.numerics.accuracy.residual_figures`).
    """
    lam = np.asarray(lam, dtype=complex)
    if eta is None or norm_x is None or weight is None:
        eta, norm_x, weight = residual_figures(lam, *P, problem.norms) if eta is None else (
            eta, column_norms(P[0]), problem.weight(lam))
    P = P / norm_x
    X = P[0]
    Y = X if Y is None else Y / column_norms(Y)
    yP = np.einsum("ij,kij->kj", Y, P[1:])
    # with y = x real, x^H A x = y^T A x: the same products, not formed twice
    quad = yP if Y is X and X.dtype.kind == "f" else quadratic_forms(X, P[1:])
    deriv = 2 * lam * yP[0] + yP[1]
    size = np.abs(deriv)
    if np.count_nonzero(size) == size.size:  # the common case: every derivative nonzero
        ok = np.ones(size.shape, dtype=bool)
        sens = weight / size
        left = Y / deriv
    else:
        ok = size > 0
        with np.errstate(divide="ignore", invalid="ignore"):
            sens = np.where(ok, weight / np.where(ok, size, 1.0), np.inf)
        left = np.where(ok, Y / np.where(ok, deriv, 1.0), Y)
    bound = np.maximum(eta, ETA_FLOOR) * sens
    return PairFigures(
        right=X, left=left, left_normalized=ok, derivative=deriv, backward_error=eta, error_bound=bound,
        sensitivity=sens, left_unit=Y, products=yP, quadratic=quad, weight=weight,
    )


@dataclass(frozen=True, kw_only=True)
class DefectiveBound:
    """The error bound of the members of a defective cluster (chains of length p > 1).

    .. math::  r(\\delta) = \\text{spread} + \\text{scale}\\,(\\eta + \\delta)^{1/p}

    Attributes
    ----------
    indices : tuple of int
    spread : float
        Largest distance of a member from the cluster mean [rad/s].
    scale : float
        [rad/s], see :func:`defective_scale`.
    eta : float
        Largest backward error of the members (at least ETA_FLOOR).
    index : int
        p, the longest chain.
    """

    indices: tuple[int, ...]
    spread: float
    scale: float
    eta: float
    index: int


def defective_scale(problem: QuadraticProblem, center: complex, p: int) -> float:
    """The scale c of the error c eta^(1/p) of an eigenvalue with Jordan chains of length p [rad/s].

    .. math::
        c = s \\left(\\frac{w(s)}{s^2 \\|M\\|}\\right)^{1/p},\\qquad s = \\max(|\\lambda_c|, \\gamma),
        \\quad w(s) = s^2\\|M\\| + s\\|C\\| + \\|K\\|

    Near a defective eigenvalue L(lam) behaves like (lam - lam_c)^p times a
    coefficient of size ||M|| s^(2-p), while a relative perturbation eta of the
    coefficients changes L by about eta w(s): (lam - lam_c)^p ~ eta w(s) s^(p-2) / ||M||.
    For the critically damped oscillator lam^2 + 2 omega lam + omega^2 this is
    exactly the worst-case split 2 omega sqrt(eta).
    """
    s = max(abs(complex(center)), problem.scaling.gamma)
    w = float(problem.weight(s))
    return float(s * (w / (s * s * problem.norm_M)) ** (1.0 / p))


@dataclass(frozen=True, eq=False, kw_only=True)
class ErrorModel:
    """First-order error bounds of computed eigenvalues as functions of a relative data perturbation delta.

    .. math::
        r_k(\\delta) = (\\max(\\eta_k, \\epsilon) + \\delta)\\,s_k

    with s_k the :attr:`PairFigures.sensitivity` (for a semisimple cluster
    w(lam) ||y_k|| with the biorthogonalized left vectors); members of a
    defective cluster follow :class:`DefectiveBound`.  ``bound(0)`` is the
    error bound of the computation (``Modes.error_bound``); ``bound(u)`` also
    covers every system within a relative perturbation u of the data (the
    verdict's ``uncertainty``).

    Attributes
    ----------
    eta : (2n,) float
        Backward errors, at least ETA_FLOOR.
    sensitivity : (2n,) float
        [rad/s] per unit relative perturbation; inf for defective members.
    defective : tuple of DefectiveBound
    """

    eta: np.ndarray
    sensitivity: np.ndarray
    defective: tuple[DefectiveBound, ...] = ()

    def bound(self, delta: float = 0.0) -> np.ndarray:
        """r(delta) for every eigenvalue [rad/s]."""
        with np.errstate(invalid="ignore"):
            r = (self.eta + delta) * self.sensitivity
        for d in self.defective:
            r[list(d.indices)] = d.spread + d.scale * (d.eta + delta) ** (1.0 / d.index)
        return r
