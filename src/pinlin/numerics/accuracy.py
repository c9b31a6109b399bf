"""Backward error eta, condition number kappa and the Jordan-chain residual (theory: spectrum, error figures).

For an eigenpair (lam, x) with left vector y (``y^T L(lam) = 0``, plain
transpose) of L(lam) = lam^2 M + lam C + K, with Frobenius norms:

.. math::
    \\eta(x, \\lambda) = \\frac{\\|L(\\lambda) x\\|}{w(\\lambda)\\,\\|x\\|},\\qquad
    w(\\lambda) = |\\lambda|^2 \\|M\\| + |\\lambda| \\|C\\| + \\|K\\|

.. math::
    \\kappa = \\frac{\\sqrt{|a|^4\\|M\\|^2 + |a|^2|b|^2\\|C\\|^2 + |b|^4\\|K\\|^2}}
        {|y^H (2 a \\bar b M + (|b|^2 - |a|^2) C - 2 \\bar a b K) x|}

in the homogeneous form lam = a/b, |a|^2 + |b|^2 = 1, ||x|| = ||y|| = 1
(Dedieu-Tisseur).  With pinlin's plain-transpose left vectors, the y^H of the
formula is our y^T.

The functions work on batches of pairs (columns) given the products M X, C X,
K X, which the eigensolver paths compute cheaply; the single-pair forms
:func:`backward_error` and :func:`condition_number` take the matrices.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .floating import EPS
from .norms import column_norms

__all__ = [
    "ETA_FLOOR",
    "homogeneous",
    "eigen_weight",
    "backward_errors",
    "residual_figures",
    "condition_numbers",
    "backward_error",
    "condition_number",
    "chain_residuals",
]

#: Smallest backward error used in error bounds (machine epsilon): a residual
#: that happens to round to less does not make an eigenvalue more accurate than
#: the floating-point data it came from.
ETA_FLOOR = EPS

Norms = Sequence[float]


def homogeneous(lam) -> tuple[np.ndarray, np.ndarray]:
    """(a, b) with lam = a / b and |a|^2 + |b|^2 = 1, b real >= 0, without overflow."""
    lam = np.asarray(lam, dtype=complex)
    r = np.abs(lam)
    small = r <= 1
    rs = np.where(small, r, 0.0)  # |lam| <= 1: b = 1 / sqrt(1 + |lam|^2)
    inv = np.where(small, 1.0, 1.0 / np.where(small, 1.0, r))  # |lam| > 1: b = (1/|lam|) / sqrt(1 + 1/|lam|^2)
    b_small = 1.0 / np.sqrt(1.0 + rs * rs)
    b_big = inv / np.sqrt(1.0 + inv * inv)
    b = np.where(small, b_small, b_big)
    return lam * b, b


def eigen_weight(lam, norms: Norms):
    """w(lam) = |lam|^2 ||M|| + |lam| ||C|| + ||K||: the scale of L(lam) in eta."""
    norm_M, norm_C, norm_K = norms
    a = np.abs(lam)
    return a * a * norm_M + a * norm_C + norm_K






def backward_errors(lam, X, MX, CX, KX, norms: Norms) -> np.ndarray:
    """eta for each column of X (any scaling), given the products M X, C X, K X.

    The arrays may carry leading batch axes (..., n, k), with ``lam`` of shape (k,).
    An exactly zero residual gives 0 (also where the weight vanishes: lam = 0
    with K = 0); a zero column x gives inf (it is no eigenvector).
    """
    return residual_figures(lam, X, MX, CX, KX, norms)[0]


def residual_figures(lam, X, MX, CX, KX, norms: Norms) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(eta, ||x||, w(lam)) for each column: :func:`backward_errors` with the column norms and weights it formed.

    A caller that normalizes the vectors or forms error bounds next reuses ||x|| and
    w(lam) = |lam|^2 ||M|| + |lam| ||C|| + ||K|| instead of computing them again.
    """
    lam = np.asarray(lam, dtype=complex)
    lam2 = lam * lam
    shape = (2,) + np.shape(MX)  # X, M X, C X, K X: arrays of one shape
    real_lam = np.count_nonzero(lam.imag) == 0
    if _real_residual(real_lam, lam2, X, MX, CX, KX):
        # real vectors and products, lam^2 real and no imaginary C x lam term: L(lam) x is real, and formed
        # in real arithmetic it has the same real part (the complex form adds exact zeros) and no imaginary one
        RX = np.empty(shape)
        R = np.multiply(MX, lam2.real, out=RX[0])
        if real_lam:
            R += CX * lam.real
        R += KX
    else:
        RX = np.empty(shape, dtype=complex)  # L(lam) x beside x
        R = np.multiply(MX, lam2, out=RX[0])
        R += CX * lam
        R += KX
    RX[1] = X
    num, nx = column_norms(RX)  # one pass over both
    w = eigen_weight(lam, norms)
    den = w * nx
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        eta = num / den
    if np.count_nonzero(np.isfinite(eta)) == eta.size:
        # no zero x (den = 0 would give inf or nan), no overflow; num = 0 gives 0 also where den = inf
        return eta, nx, w
    eta = np.where(num == 0, 0.0, np.where(np.isfinite(eta), eta, np.inf))
    return np.where(nx == 0, np.inf, eta), nx, w


def _real_residual(real_lam: bool, lam2, X, MX, CX, KX) -> bool:
    """L(lam) x = lam^2 M x + lam C x + K x is real: real X and products, lam^2 real, and lam real or C x = 0.

    ``real_lam``: every lam is real.
    """
    if np.iscomplexobj(X) or np.iscomplexobj(MX) or np.iscomplexobj(CX) or np.iscomplexobj(KX):
        return False
    if np.count_nonzero(lam2.imag):
        return False
    return real_lam or not np.count_nonzero(CX)


def condition_numbers(lam, yMx, yCx, yKx, norms: Norms) -> np.ndarray:
    """kappa for each pair from y^T M x, y^T C x, y^T K x of unit-norm x and y.

    inf where the denominator vanishes (a defective eigenvalue: y^T L'(lam) x = 0).
    """
    big = max(norms) if max(norms) > 0 else 1.0  # the norms relative to the largest: no overflow of squares
    norm_M, norm_C, norm_K = (x / big for x in norms)
    a, b = homogeneous(lam)
    aa, bb = np.abs(a) ** 2, np.abs(b) ** 2
    num = big * np.sqrt(aa * aa * norm_M**2 + aa * bb * norm_C**2 + bb * bb * norm_K**2)
    den = np.abs(2 * a * np.conj(b) * yMx + (bb - aa) * yCx - 2 * np.conj(a) * b * yKx)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), np.inf)


def _matrices(M, C, K):
    return tuple(np.asarray(a) for a in (M, C, K))


def backward_error(M, C, K, lam: complex, x, *, left: bool = False) -> float:
    """eta of one pair (theory: spectrum); with ``left`` the residual is ``x^T L(lam)``."""
    M, C, K = _matrices(M, C, K)
    if left:
        M, C, K = M.T, C.T, K.T
    X = np.asarray(x).reshape(-1, 1)
    norms = (float(np.linalg.norm(M)), float(np.linalg.norm(C)), float(np.linalg.norm(K)))
    lam_arr = np.array([complex(lam)])
    return float(backward_errors(lam_arr, X, M @ X, C @ X, K @ X, norms)[0])


def condition_number(M, C, K, lam: complex, x, y) -> float:
    """kappa of one eigenvalue (theory: spectrum) from its right x and plain-transpose left y (any scaling)."""
    M, C, K = _matrices(M, C, K)
    x = np.asarray(x) / np.linalg.norm(x)
    y = np.asarray(y) / np.linalg.norm(y)
    norms = (float(np.linalg.norm(M)), float(np.linalg.norm(C)), float(np.linalg.norm(K)))
    products = [np.array([y @ (A @ x)]) for A in (M, C, K)]
    return float(condition_numbers(np.array([complex(lam)]), *products, norms)[0])


def chain_residuals(M, C, K, lam0: complex, chain: Sequence[np.ndarray]) -> tuple[float, ...]:
    """Relative residual of each Jordan chain equation (theory: spectrum).

    .. math::
        \\rho_i = \\frac{\\|\\sum_{j=0}^{\\min(i,2)} L^{(j)}(\\lambda_0)/j!\\; x_{i-j}\\|}
        {\\sum_{j=0}^{\\min(i,2)} w_j\\,\\|x_{i-j}\\|},\\qquad
        w_0 = w(\\lambda_0),\\; w_1 = 2|\\lambda_0|\\,\\|M\\| + \\|C\\|,\\; w_2 = \\|M\\|

    with L' = 2 lam0 M + C, L''/2 = M and the weights w_j the Frobenius-norm
    bounds of those blocks, as in eta.  A chain whose vectors are all zero gives
    inf (it is no chain).
    """
    M, C, K = _matrices(M, C, K)
    lam0 = complex(lam0)
    norms = (float(np.linalg.norm(M)), float(np.linalg.norm(C)), float(np.linalg.norm(K)))
    blocks = [lam0 * lam0 * M + lam0 * C + K, 2 * lam0 * M + C, M.astype(complex)]
    weights = [float(eigen_weight(lam0, norms)), 2 * abs(lam0) * norms[0] + norms[1], norms[0]]
    out = []
    for i in range(len(chain)):
        terms = range(min(i, 2) + 1)
        r = sum(blocks[j] @ np.asarray(chain[i - j]) for j in terms)
        w = sum(weights[j] * np.linalg.norm(chain[i - j]) for j in terms)
        rn = float(np.linalg.norm(r))
        out.append(0.0 if rn == 0 else (rn / w if w > 0 else float("inf")))
    return tuple(out)
