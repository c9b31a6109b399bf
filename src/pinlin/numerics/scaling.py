"""Scales of the quadratic eigenproblem L(lam) = lam^2 M + lam C + K (theory: spectrum).

- :class:`Scaling` and :func:`fan_lin_van_dooren`: the Fan-Lin-Van Dooren
  scaling lambda = gamma mu, used by the eigensolver, the Jordan rank
  decisions and the modal expansion;
- :func:`natural_scale`: a modulus typical of the eigenvalues (contour radii,
  relative tests near lam = 0);
- :func:`eigenvalue_bounds`: bounds on the moduli of all eigenvalues (circle
  radii of the characteristic polynomial and the adjugate).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from ..errors import ComputationError
from ..results import persistent
from .floating import EPS, LOG_MAX, LOG_TINY
from .norms import coefficient_norms

__all__ = [
    "Scaling",
    "fan_lin_van_dooren",
    "system_scaling",
    "natural_scale",
    "eigenvalue_bounds",
    "INVERTIBLE_K_FACTOR",
    "RANGE_MARGIN",
]

#: K counts as safely invertible for the lower eigenvalue bound when
#: sigma_min(K) > INVERTIBLE_K_FACTOR * n * eps * sigma_max(K): a 1000-fold margin
#: over the rounding level of the SVD, so that K^-1 C and K^-1 M keep a few correct digits.
INVERTIBLE_K_FACTOR = 1e3


@persistent
@dataclass(frozen=True)
class Scaling:
    """Fan-Lin-Van Dooren scaling lambda = gamma mu, L_s(mu) = delta L(gamma mu) (theory: spectrum).

    .. math::
        \\gamma = \\sqrt{\\|K\\|/\\|M\\|},\\quad
        \\delta = 2 / (\\|K\\| + \\gamma \\|C\\|),\\quad
        M_s = \\gamma^2\\delta M,\\; C_s = \\gamma\\delta C,\\; K_s = \\delta K

    After scaling ||M_s|| = ||K_s|| and their common size and ||C_s|| add up to 2.
    When K = 0 (only possible with rigid-body modes) gamma = ||C||/||M|| balances
    M against C instead, and with C = K = 0 no frequency scaling is done (gamma = 1).

    Attributes
    ----------
    gamma : float
        Frequency scale [rad/s]: lambda = gamma mu.
    delta : float
        Scale of the coefficients [1/(unit of K)].
    """

    gamma: float
    delta: float

    @property
    def identity(self) -> bool:
        return self.gamma == 1.0 and self.delta == 1.0


#: Natural-log headroom kept between the scales of a problem and the ends of double
#: precision: the scaled eigenvalues mu are about one, and lam^2 = gamma^2 mu^2 and the
#: weights of eta must stay representable for |mu| up to 1e3 (ln 1e6 = 13.8).
RANGE_MARGIN = float(np.log(1e6))








def fan_lin_van_dooren(norm_M: float, norm_C: float, norm_K: float) -> Scaling:
    """The Fan-Lin-Van Dooren parameters from the coefficient norms (see :class:`Scaling`).

    Computed in logarithms, so that coefficients anywhere in double range give
    finite parameters; ``gamma^2 delta``, ``gamma delta`` and ``delta`` times the norms
    are then at most 2.

    Raises
    ------
    ComputationError
        ||M|| is zero or a norm is not finite; or the problem's eigenvalue scale
        gamma lies so far out that lam = gamma mu, lam^2 ||M|| or delta are not
        representable with :data:`RANGE_MARGIN` to spare (the message says to
        change units).
    """
    norms = (norm_M, norm_C, norm_K)
    if not (norm_M > 0 and all(math.isfinite(x) and x >= 0 for x in norms)):
        raise ComputationError(
            f"the coefficient norms (||M||, ||C||, ||K||) = ({norm_M:.3g}, {norm_C:.3g}, {norm_K:.3g}) must be "
            f"finite with ||M|| > 0"
        )
    if norm_K > 0:
        log_gamma = 0.5 * (math.log(norm_K) - math.log(norm_M))
    elif norm_C > 0:
        log_gamma = math.log(norm_C) - math.log(norm_M)
    else:
        log_gamma = 0.0
    # delta = 2 / (||K|| + gamma ||C||), or 2 / (gamma^2 ||M||) = 1 / ||M|| when K = C = 0 (then gamma = 1)
    log_size = max(
        math.log(norm_K) if norm_K > 0 else -math.inf,
        log_gamma + math.log(norm_C) if norm_C > 0 else -math.inf,
        2 * log_gamma + math.log(norm_M) if norm_K == 0 and norm_C == 0 else -math.inf,
    )
    for what, value in (("gamma^2", 2 * log_gamma), ("delta", math.log(2.0) - log_size), ("the weight", log_size)):
        if not LOG_TINY + RANGE_MARGIN < value < LOG_MAX - RANGE_MARGIN:
            raise ComputationError(
                f"the eigenvalue scale of this problem is out of double range ({what} about "
                f"10^{value / math.log(10):.0f}, gamma = sqrt(||K||/||M||) about 10^{log_gamma / math.log(10):.0f} rad/s "
                f"from the norms ({norm_M:.3g}, {norm_C:.3g}, {norm_K:.3g})); rescale the system (units, for "
                f"example mm and g instead of m and kg)"
            )
    if norm_K == 0 and norm_C == 0:
        return Scaling(1.0, 1.0 / norm_M)
    # within range (checked above): the plain formulas, exact where the inputs are
    gamma = float(np.sqrt(norm_K) / np.sqrt(norm_M)) if norm_K > 0 else float(norm_C / norm_M)
    delta = 2.0 / (norm_K + gamma * norm_C)
    return Scaling(gamma, float(delta))


def system_scaling(M, C, K) -> Scaling:
    """:func:`fan_lin_van_dooren` of the Frobenius norms of M, C and K."""
    return fan_lin_van_dooren(*coefficient_norms(M, C, K))


def natural_scale(sys) -> float:
    """A modulus typical of the eigenvalues of ``sys`` [1/s].

    .. math::  \\Bigl|\\frac{\\det K}{\\det M}\\Bigr|^{1/2n} = \\Bigl(\\prod_k |\\lambda_k|\\Bigr)^{1/2n}

    the geometric mean of the eigenvalue moduli when K is nonsingular, otherwise
    the Fan-Lin-Van Dooren gamma (theory: spectrum).
    """
    sk, lk = np.linalg.slogdet(sys.K)
    if sk != 0 and np.isfinite(lk):
        _, lm = np.linalg.slogdet(sys.M)
        return float(np.exp((lk - lm) / (2 * sys.n)))
    return system_scaling(sys.M, sys.C, sys.K).gamma


def eigenvalue_bounds(sys) -> tuple[float, float]:
    """Bounds ``lo <= |lam_k| <= hi`` [1/s] on the moduli of all eigenvalues of ``sys``.

    From ``lam^2 x = -M^{-1}(lam C + K) x``: ``|lam|^2 <= a |lam| + b`` with
    ``a = ||M^{-1} C||_2``, ``b = ||M^{-1} K||_2``; likewise for ``1/lam`` with
    ``K^{-1}`` when K is safely invertible (see :data:`INVERTIBLE_K_FACTOR`;
    otherwise ``lo = 0``).  M must be positive definite (a LinearizedSystem).
    """
    cho = sla.cho_factor(sys.M)
    a = np.linalg.norm(sla.cho_solve(cho, sys.C), 2)
    b = np.linalg.norm(sla.cho_solve(cho, sys.K), 2)
    hi = 0.5 * (a + np.sqrt(a * a + 4 * b))
    lo = 0.0
    if np.any(sys.K):
        sv = np.linalg.svd(sys.K, compute_uv=False)
        if sv[-1] > INVERTIBLE_K_FACTOR * sys.n * EPS * sv[0]:
            a2 = np.linalg.norm(np.linalg.solve(sys.K, sys.C), 2)
            b2 = np.linalg.norm(np.linalg.solve(sys.K, sys.M), 2)
            lo = 2.0 / (a2 + np.sqrt(a2 * a2 + 4 * b2))
    return float(lo), float(hi)
