"""Error bounds of Floquet multipliers: integration error and eigensolver backward error, each through the
multiplier's condition in the periodic eigenproblem (theory: Floquet).

With z_j, w_j the right and left periodic eigenvectors at the segment boundaries (:mod:`.cyclic`) and
u_s, v_s their images inside a segment (u_s = P_s u_{s-1} forward from z_{j-1}, v_{s-1}^H = v_s^H P_s
backward from w_j; inside a segment the growth is below the threshold, so these short propagations are
accurate), an error E_s of step s moves mu by

.. math::  \\delta\\mu = K \\lambda^{K-1} \\sum_s v_s^H E_s u_{s-1} / (w^H z),

so that, with \\hat E_s the step's Richardson estimate of its error matrix and r_s its rounding floor,

.. math::

    \\frac{|\\delta\\mu_{int}|}{|\\mu|} \\le \\frac{K \\sum_s \\left(\\rho |v_s^H \\hat E_s u_{s-1}|
    + (\\theta \\|\\hat E_s\\| + r_s) \\|v_s\\| \\|u_{s-1}\\|\\right)}{|\\lambda|\\,|w^H z|},
    \\qquad
    \\frac{|\\delta\\mu_{eig}|}{|\\mu|} \\le \\frac{K \\eta \\|\\mathcal{C}\\|}{|\\lambda|\\,|w^H z|}

(eta the eigensolver's backward error, at least eps).  The projection of the estimate (times rho =
:data:`PROJECTION_FACTOR`) is what the error does to this multiplier; theta = :data:`ESTIMATE_SLACK` of its norm covers the estimate's own
inaccuracy (Richardson is exact only as h -> 0) in any direction, and the rounding floor is directionless.
Without the projection a stiff, heavily damped mode's local error (large in norm, invisible to the other
modes) would inflate every other multiplier's bound by decades.  Both are first order: for a multiplier in (or near)
a Jordan block the condition 1 / |w^H z| is large and the bound says so, but it is not a proof there.
"""

from __future__ import annotations

import numpy as np

from .collocation import Transitions
from .cyclic import CyclicEigen

__all__ = ["multiplier_bounds", "relative_condition", "ESTIMATE_SLACK", "PROJECTION_FACTOR"]

#: theta: share of a step's estimated error norm allowed in any direction, beyond its projection.
ESTIMATE_SLACK = 1e-2

#: rho: factor on the projected Richardson estimate.  Measured against mpmath (Mathieu stable and unstable,
#: the 32-decade damped case, rtol 1e-13..1e-6, steps up to h ||D^-1 A D|| = 2): the true error reached
#: 1.65 times the plain projection (Mathieu multipliers on the unit circle at rtol 1e-7, 4 steps per
#: period); 4 keeps a factor 2.4 there, and costs a factor 2-4 of pessimism where the estimate is exact.
PROJECTION_FACTOR = 4.0

_EPS = float(np.finfo(float).eps)


def _integration_sums(tr: Transitions, eig: CyclicEigen) -> np.ndarray:
    """sum_s rho |v_s^H E_s u_{s-1}| + (theta ||E_s|| + r_s) ||v_s|| ||u_{s-1}|| per multiplier (unit stacked
    eigenvectors)."""
    m, K = eig.right.shape[0], len(tr.factors)
    sums = np.zeros(m)
    for j, (begin, end) in enumerate(tr.segments):
        steps = tr.steps[begin:end]
        U = eig.right[:, j, :].T                            # (m, modes): z_{j-1} in the 1-based notation
        V = eig.left[:, (j + 1) % K, :].T                   # w_j: where segment j lands
        rights, lefts = [], [None] * len(steps)
        for step in steps:
            rights.append(U)
            U = step.P @ U
        for i in range(len(steps) - 1, -1, -1):
            lefts[i] = V
            V = steps[i].P.conj().T @ V
        for step, U, V in zip(steps, rights, lefts):
            projected = np.abs(np.sum(V.conj() * (step.estimate @ U), axis=0))
            norms = np.linalg.norm(V, axis=0) * np.linalg.norm(U, axis=0)
            slack = ESTIMATE_SLACK * float(np.linalg.norm(step.estimate, 2)) + step.rounding
            sums += PROJECTION_FACTOR * projected + slack * norms
    return sums


def multiplier_bounds(tr: Transitions, eig: CyclicEigen) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(bound, integration part, eigensolver part) of |mu_k computed - mu_k exact| for every multiplier.

    Parameters
    ----------
    tr : Transitions
        The step transitions, their error estimates and segments.
    eig : CyclicEigen
        The lifted eigenproblem's multipliers and eigenvectors.

    Returns
    -------
    bound, integration, eigensolver : ndarray (m,)
        Absolute bounds (same unit as mu: none); ``bound = integration + eigensolver``.
    """
    K = len(tr.factors)
    overlap = np.abs(np.einsum("kjp,kjp->k", eig.left.conj(), eig.right))   # |w^H z|
    overlap = np.maximum(overlap, np.finfo(float).tiny)
    scale = K * np.abs(eig.multipliers) / (np.abs(eig.roots) * overlap)
    integration = scale * _integration_sums(tr, eig)
    eta = np.maximum(eig.backward_error, _EPS)
    eigensolver = scale * eta * eig.cyclic_norm
    return integration + eigensolver, integration, eigensolver


def relative_condition(tr: Transitions, eig: CyclicEigen) -> np.ndarray:
    """kappa_k: to first order |delta mu_k| / |mu_k| <= kappa_k delta for perturbations of every segment
    transition of relative size delta (||E_j|| <= delta ||Phi_j||),

    .. math::  \\kappa_k = K \\sum_j \\|w_j\\| \\|\\Phi_j\\| \\|z_{j-1}\\| / (|\\lambda| |w^H z|).
    """
    K = len(tr.factors)
    overlap = np.maximum(np.abs(np.einsum("kjp,kjp->k", eig.left.conj(), eig.right)), np.finfo(float).tiny)
    total = np.zeros(eig.multipliers.size)
    for j, factor in enumerate(tr.factors):
        total += (np.linalg.norm(eig.left[:, (j + 1) % K, :], axis=1) * np.linalg.norm(factor, 2)
                  * np.linalg.norm(eig.right[:, j, :], axis=1))
    return K * total / (np.abs(eig.roots) * overlap)
