"""The modal method of the H(s) engine and its defect bound (theory: flexibility, responses, error figures).

X(s) = H(s) B from the modal expansion (:mod:`pinlin.frf.expansion`): with
coefficients c_k (rows of c, (2n, m)) of the state (0, M^-1 B) on the
semisimple modes,

.. math::  X(s) = \\sum_k \\frac{x_k c_k^T}{s - \\lambda_k} + \\text{(Jordan-block terms)},

O(n) per point, output and input.  Its residual has a known form: with
L(s) = L(lam) + (s - lam) L'(lam) + (s - lam)^2 M,

.. math::
    L(s) X(s) - B = \\underbrace{\\sum_k \\frac{r_k c_k^T}{s - \\lambda_k}}_{Q(s)} + \\underbrace{P_0 + s P_1}_{P(s)},
    \\qquad r_k = L(\\lambda_k) x_k,

P linear in s (P_0, P_1 vanish when the coefficients reproduce the state
exactly).  For the X(s) computed in floating point, X + E with
||L(s) E|| <= gamma ||L(s)|| sum_k ||x_k c_k^T|| / |s - lam_k| (gamma =
(n + 4) eps, the rounding of the 2n-term sum and of each term,
:data:`ROUNDING_TERMS`), so at every point

.. math::
    \\|L(s)\\hat X(s) - B\\| \\le \\sum_k \\frac{(\\|r_k\\| + \\gamma\\,\\|L(s)\\|)\\,\\|x_k c_k^T\\|}{|s - \\lambda_k|}
        + \\frac{|b - s|\\,p_a + |s - a|\\,p_b}{|b - a|},

where the linear P is bounded through its values at two sampled points a and
b: p_a >= ||P(a)|| from the residual measured there (plus the same pole and
rounding terms, and the rounding of the residual itself).  The engine's check
for the modal method is this bound at every point divided by
||L(s)|| ||X(s)|| + ||B||, with ||X(s)|| over all rows replaced by a lower
bound when only some rows are evaluated (their norm, or sigma_min of the
scaled state basis times the modal coefficients): O(n) per point like X.  The exact relative defect
is computed at :data:`CHECK_SAMPLES` points spread over the points given
(where the bound is at least the truth by construction).  With Jordan blocks
the exact defect is computed at every point instead.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from ..linearization.system import LinearizedSystem
from ..numerics import EPS
from .expansion import ModalExpansion, modal_expansion

__all__ = [
    "CHECK_SAMPLES",
    "ROUNDING_TERMS",
    "RESIDUAL_ROUNDING",
    "near_eigenvalue",
    "modal_columns",
    "ModalSolution",
    "modal_solution",
    "linear_part_bound",
]

#: Points at which the modal method's relative defect is also computed exactly (spread
#: evenly over the points given): enough to catch a systematic failure, few enough that
#: the check costs O(n) per point like the evaluation.
CHECK_SAMPLES = 32

#: gamma = (n + ROUNDING_TERMS) eps bounds the rounding of the computed modal sum relative to
#: sum_k |term_k|: (2n - 1) u = (n - 1/2) eps for adding the 2n terms, and about 4 eps for
#: forming each term, a complex quotient and a complex product (Higham, Accuracy and
#: Stability of Numerical Algorithms, Lemma 3.5: sqrt(2) gamma_2 and sqrt(2) gamma_4).
ROUNDING_TERMS = 4


#: The residual L(s) X - B measured at a sample is itself rounded, by at most
#: (3n + RESIDUAL_ROUNDING) eps (||L(s)|| ||X|| + ||B||): inner products of length 3n (the
#: three products with M, C, K), the sums of the three and the subtraction of B.
RESIDUAL_ROUNDING = 4


def near_eigenvalue(s: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """Distance [1/s] of each point to the nearest of ``lam`` (inf when there is none)."""
    if lam.size == 0:
        return np.full(s.size, np.inf)
    return np.min(np.abs(s[:, None] - lam[None, :]), axis=1)


def _coefficients(expansion: ModalExpansion, B: np.ndarray):
    """Coefficients (c, d, projection residual) of the state (0, M^-1 B)."""
    sys = expansion.system
    rhs = scipy.linalg.cho_solve(scipy.linalg.cho_factor(sys.M), B.astype(complex))
    return expansion.coefficients(np.zeros_like(rhs), rhs)


def modal_columns(expansion: ModalExpansion, s: np.ndarray, c, d, rows: np.ndarray, W=None) -> np.ndarray:
    """Rows ``rows`` of H(s) B from coefficients (c, d): (F, len(rows), m); W = 1 / (s - lam) when known."""
    m = c.shape[1]
    if W is None:
        W = 1.0 / (s[:, None] - expansion.lam[None, :])  # (F, k)
    # (F, k) x (k, r m): the Khatri-Rao product of the right vectors and the coefficients
    KR = (c[:, None, :] * expansion.right[rows].T[:, :, None]).reshape(expansion.lam.size, len(rows) * m)
    X = (W @ KR).reshape(s.size, len(rows), m)
    for block, coef in zip(expansion.blocks, d):
        # (sI - J)^-1 coef for J = lam0 I + (superdiagonal ones): back substitution from the chain's end
        r = block.length
        shift = (s - block.lam0)[:, None]
        D = np.empty((s.size, r, m), dtype=complex)
        D[:, r - 1] = coef[r - 1][None, :] / shift
        for i in range(r - 2, -1, -1):
            D[:, i] = (coef[i][None, :] + D[:, i + 1]) / shift
        X += np.einsum("fim,ri->frm", D, block.vectors[rows])
    return X


class ModalSolution:
    """What the modal method gives the engine.

    Attributes
    ----------
    expansion : ModalExpansion
    X : (F, len(rows), m) complex
    bound : (F,) float or None
        The pole and rounding part of the bound of ||L(s) X - B||_F per point (the linear part
        needs the residuals at the samples: :func:`linear_part_bound`); None when not asked,
        or with Jordan blocks.
    rows_all : bool
        X holds every row.
    projection : float
        Projection residual of the coefficients.
    samples : (k,) int or None
        The sampled points where every row was evaluated; ``exact`` X there (all rows).
    lower : (F,) float or None
        A lower bound of ||X(s)||_F over all rows (see ``_pole_and_rounding``).
    """

    def __init__(self, expansion, X, bound, rows_all, projection, samples=None, exact=None, lower=None):
        self.expansion, self.X, self.bound, self.rows_all = expansion, X, bound, rows_all
        self.projection, self.samples, self.exact, self.lower = projection, samples, exact, lower


def _pole_and_rounding(expansion: ModalExpansion, s, c, W, nL) -> tuple[np.ndarray, np.ndarray]:
    """(sum_k (||r_k|| + gamma ||L(s)||) ||x_k c_k^T|| / |s - lam_k|, a lower bound of ||X(s)||_F) per point.

    The lower bound: z = (X, s X / g) = V (w c) with V = [x_k; lam_k x_k / g] the scaled state
    basis (g the natural frequency scale), so ||X|| = ||z|| / sqrt(1 + |s / g|^2) >=
    sigma_min(V) ||diag(w) c|| / sqrt(1 + |s / g|^2), less the rounding of the computed X.
    """
    sys = expansion.system
    lam, X = expansion.lam, expansion.right
    gamma = (sys.n + ROUNDING_TERMS) * EPS
    # ||r_k|| = ||L(lam_k) x_k||, formed here: members of a semisimple cluster carry the cluster's mean
    r = np.linalg.norm((sys.M @ X) * lam**2 + (sys.C @ X) * lam + sys.K @ X, axis=0)
    cn = np.linalg.norm(c, axis=1)
    size = np.linalg.norm(X, axis=0) * cn  # ||x_k c_k^T||_F
    aW = np.abs(W)
    rounding = gamma * (aW @ size)
    g = expansion.gamma
    lower = expansion.state_sigma_min * np.sqrt((aW * aW) @ (cn * cn)) / np.sqrt(1.0 + np.abs(s / g) ** 2) - rounding
    return aW @ (r * cn) + nL * rounding, lower


def linear_part_bound(s: np.ndarray, samples: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Bound of ||P(s)|| for a P linear in s from bounds ``p`` of ||P|| at the samples (the two farthest apart).

    .. math::  \\|P(s)\\| \\le \\frac{|b - s|\\,p_a + |s - a|\\,p_b}{|b - a|}
    (P(s) = P(a) (b - s)/(b - a) + P(b) (s - a)/(b - a) exactly); p_a alone when a = b.
    """
    pts = s[samples]
    gap = np.abs(pts[:, None] - pts[None, :])
    i, j = np.unravel_index(int(np.argmax(gap)), gap.shape)  # the two samples farthest apart
    a, b = pts[i], pts[j]
    if a == b:
        return np.full(s.size, float(np.max(p)))
    return (np.abs(b - s) * p[i] + np.abs(s - a) * p[j]) / abs(b - a)


def modal_solution(sys: LinearizedSystem, s, B, modes, rows, check: bool, nL_of) -> ModalSolution:
    """Evaluate the modal method at the points ``s`` (see the module docstring).

    ``nL_of(points)`` returns ||L(s)||_F at points (the engine's ``stiffness_norms``).
    Without ``check`` only ``rows`` are evaluated; with it, rows as asked plus the
    bound at every point, and every row at the sampled points.  With Jordan blocks
    and ``check`` every row at every point (the engine computes exact defects).
    """
    expansion = modal_expansion(sys, modes)
    c, d, projection = _coefficients(expansion, B)
    full = len(rows) == sys.n or (check and bool(expansion.blocks))
    use = np.arange(sys.n) if full else rows
    W = 1.0 / (s[:, None] - expansion.lam[None, :])
    X = modal_columns(expansion, s, c, d, use, W)
    if not check or expansion.blocks:
        return ModalSolution(expansion, X, None, full, projection)
    bound, lower = _pole_and_rounding(expansion, s, c, W, nL_of(s))
    spread = np.linspace(0, s.size - 1, min(CHECK_SAMPLES, s.size)).round().astype(int)
    ends = [np.argmin(s.real), np.argmax(s.real), np.argmin(s.imag), np.argmax(s.imag)]  # the extreme points
    samples = np.unique(np.concatenate([spread, np.array(ends, dtype=int)]))
    Xs = X[samples] if full else modal_columns(expansion, s[samples], c, d, np.arange(sys.n), W[samples])
    return ModalSolution(expansion, X, bound, full, projection, samples, Xs, lower)
