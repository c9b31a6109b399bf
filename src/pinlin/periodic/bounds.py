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
Where the coefficients integrated are an interpolant of the true ones (:mod:`.sampling`), each step adds the
first-order effect of their error bound (:func:`coefficient_terms`).  Without the projection a stiff,
heavily damped mode's local error (large in norm, invisible to the other
modes) would inflate every other multiplier's bound by decades.  The reference orbit's own error adds its
first-order change of each multiplier (:func:`directional_terms` on :mod:`.orbit_error`'s responses).  All are
first order: for a multiplier in (or near) a Jordan block the condition 1 / |w^H z| is large but the change
goes as the square root of the perturbation; for the trivial pair of a conservative family's orbit
:func:`jordan_bound` says so.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from .collocation import Transitions
from .cyclic import CyclicEigen

__all__ = ["multiplier_bounds", "relative_condition", "coefficient_terms", "directional_terms",
           "monodromy_perturbation", "jordan_bound", "ORBIT_SAFETY", "ESTIMATE_SLACK", "PROJECTION_FACTOR"]

#: theta: share of a step's estimated error norm allowed in any direction, beyond its projection.
ESTIMATE_SLACK = 1e-2

#: rho: factor on the projected Richardson estimate.  Measured against mpmath (Mathieu stable and unstable,
#: the 32-decade damped case, rtol 1e-13..1e-6, steps up to h ||D^-1 A D|| = 2): the true error reached
#: 1.65 times the plain projection (Mathieu multipliers on the unit circle at rtol 1e-7, 4 steps per
#: period); 4 keeps a factor 2.4 there, and costs a factor 2-4 of pessimism where the estimate is exact.
PROJECTION_FACTOR = 4.0

#: Factor on the first-order change of a multiplier from the orbit's correction (an estimate: the correction
#: is the next Newton step, accurate to its square; the finite differences to eps^(2/3)).
ORBIT_SAFETY = 2.0

_EPS = float(np.finfo(float).eps)


def _integration_sums(tr: Transitions, eig: CyclicEigen, orbit) -> tuple[np.ndarray, np.ndarray]:
    """sum_s rho |v_s^H E_s u_{s-1}| + (theta ||E_s|| + r_s) ||v_s|| ||u_{s-1}|| per multiplier (unit stacked
    eigenvectors), each segment's steps on stacks; and the orbit's part (``orbit``: see
    :func:`multiplier_bounds`), rho_orbit |g . ds| + ||g|| ``unknown`` with g the sums' response to a unit
    change of the orbit's start."""
    m, K = eig.right.shape[0], len(tr.factors)
    sums, gradient = np.zeros(m), np.zeros((m, m), complex)
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
        R, L = np.stack(rights), np.stack(lefts)                          # (S, m, modes)
        E = np.stack([step.estimate for step in steps])
        projected = np.abs(np.sum(L.conj() * (E @ R), axis=1)).sum(axis=0)
        norms = np.linalg.norm(L, axis=1) * np.linalg.norm(R, axis=1)     # (S, modes)
        slack = np.array([ESTIMATE_SLACK * s.estimate_norm + s.rounding for s in steps])
        sums += PROJECTION_FACTOR * projected + slack @ norms
        with_error = [i for i, step in enumerate(steps) if step.coefficient_error is not None]
        if with_error:
            sums += coefficient_terms([steps[i] for i in with_error], R[with_error], L[with_error])
        if orbit is not None:
            gradient += directional_terms(steps, R, L, orbit.responses[begin:end])
    if orbit is None:
        return sums, np.zeros(m)
    return sums, (ORBIT_SAFETY * np.abs(orbit.ds @ gradient)
                  + np.linalg.norm(gradient, axis=0) * orbit.unknown)


def directional_terms(steps: list, R: np.ndarray, L: np.ndarray, dA: np.ndarray) -> np.ndarray:
    """v^H dP u summed over the steps, to first order in a known change dA of the coefficients at every node
    (variation of constants with the step's quadrature):

    .. math::  v^H \\delta P u = \\sum_i w_i\\, (\\Phi(t_1, t_i)^H v)^H\\, \\delta A(t_i)\\, \\Phi(t_i, t_0) u.

    ``R``, ``L``: (S, m, modes) as :func:`coefficient_terms`; ``dA``: (S, nodes, m, m), or (S, nodes, m, m, J)
    for J changes at once (the result then (J, modes)).

    Examples
    --------
    y' = -y changed by dA = 1e-6 over a step of 0.5 s: dP = h e^{-h} 1e-6 to first order:

    >>> from pinlin.periodic.bounds import directional_terms
    >>> from pinlin.periodic.gauss_step import try_steps
    >>> A = lambda times: np.full((np.size(times), 1, 1), -1.0)
    >>> trial = try_steps(A, np.array([0.0]), np.array([0.5]), stages=4, rtol=1e-10, scaling=np.ones((1, 1)),
    ...                   max_step_norm=2.0)
    >>> term = directional_terms(trial.steps, np.ones((1, 1, 1)), np.ones((1, 1, 1)), np.full((1, 8, 1, 1), 1e-6))
    >>> print(f"{term[0].real:.6e}", f"{0.5 * np.exp(-0.5) * 1e-6:.6e}")
    3.032653e-07 3.032653e-07
    """
    Z = np.stack([step.stage for step in steps])                              # (S, nodes, m, m)
    P = np.stack([step.P for step in steps])
    W = np.stack([step.weights for step in steps])
    right = Z @ R[:, None]                                                    # (S, nodes, m, modes)
    left = np.linalg.inv(Z).transpose(0, 1, 3, 2) @ (P.transpose(0, 2, 1) @ L)[:, None]
    if dA.ndim == 5:
        return np.einsum("si,sipk,sipqj,siqk->jk", W, left.conj(), dA, right)
    return np.einsum("si,sipk,sipq,siqk->k", W, left.conj(), dA, right)


def coefficient_terms(steps: list, R: np.ndarray, L: np.ndarray) -> np.ndarray:
    """First-order effect of an error dA of the integrated coefficients on each mode, summed over steps,

    .. math::  |v^H \\delta P u| \\le \\sum_i w_i \\sum_{ab} E_{ab}\\, \\|(\\Phi(t_1, t_i)^H v)_a\\|\\,
               \\|(\\Phi(t_i, t_0) u)_b\\|,

    with Phi(t_i, t_0) = Z_i the stage transitions, Phi(t_1, t_i) = P Z_i^-1, w_i the quadrature weights and
    E the step's block bound on dA (rows split into E's blocks).  ``R``, ``L``: (S, m, modes) the modes at
    each step's start and the left vectors at its end.

    Examples
    --------
    y' = -y integrated with a coefficient known to 1e-6: over a step of 0.5 s the transition's error is
    h e^{-h} 1e-6 to first order (variation of constants):

    >>> from pinlin.periodic.bounds import coefficient_terms
    >>> from pinlin.periodic.gauss_step import try_steps
    >>> A = lambda times: np.full((np.size(times), 1, 1), -1.0)
    >>> trial = try_steps(A, np.array([0.0]), np.array([0.5]), stages=4, rtol=1e-10, scaling=np.ones((1, 1)),
    ...                   max_step_norm=2.0, coefficient_error=np.array([[1e-6]]))
    >>> term = coefficient_terms(trial.steps, np.ones((1, 1, 1)), np.ones((1, 1, 1)))
    >>> print(f"{term[0]:.6e}", f"{0.5 * np.exp(-0.5) * 1e-6:.6e}")
    3.032653e-07 3.032653e-07
    """
    Z = np.stack([step.stage for step in steps])                              # (S, nodes, m, m), real
    P = np.stack([step.P for step in steps])
    S, nodes, m = Z.shape[:3]
    E = np.stack([step.coefficient_error for step in steps])
    modes, g = R.shape[2], E.shape[1]

    def block_norms(X):
        """Per-block 2-norms of the complex columns X = [Re | Im] (real products, |x|^2 = |Re|^2 + |Im|^2)."""
        sq = np.sum((X * X).reshape(S, nodes, g, m // g, 2, modes), axis=3)
        return np.sqrt(sq[..., 0, :] + sq[..., 1, :])                         # (S, nodes, g, modes)

    def at_nodes(F, X):
        """F_i X for every node i of a step: one product per step, (S, nodes m, m) x (S, m, 2 modes)."""
        return (F.reshape(S, nodes * m, m) @ X).reshape(S, nodes, m, 2 * modes)

    rn = block_norms(at_nodes(Z, np.concatenate([R.real, R.imag], axis=2)))
    # Z_i^-H P^H v through the real inverses (one factorization per node, not one complex solve per mode)
    PL = P.transpose(0, 2, 1) @ np.concatenate([L.real, L.imag], axis=2)
    ln = block_norms(at_nodes(np.ascontiguousarray(np.linalg.inv(Z).transpose(0, 1, 3, 2)), PL))
    W = np.stack([step.weights for step in steps])
    Er = np.matmul(E[:, None], rn)                                            # (S, nodes, g, modes)
    return np.einsum("si,sik->k", W, np.sum(ln * Er, axis=2))


def multiplier_bounds(tr: Transitions, eig: CyclicEigen, orbit=None
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(bound, integration part, eigensolver part, orbit part) of |mu_k computed - mu_k exact| for every
    multiplier.

    Parameters
    ----------
    tr : Transitions
        The step transitions, their error estimates and segments.
    eig : CyclicEigen
        The lifted eigenproblem's multipliers and eigenvectors.
    orbit : OrbitError or None
        The reference orbit's own error (:mod:`.orbit_error`): ``responses`` (steps, nodes, m, m, m) dA at
        every node per unit change of the orbit's start, ``ds`` the start's first-order correction (its change
        of the multipliers, times :data:`ORBIT_SAFETY`, enters the orbit part) and ``unknown`` the norm of the
        correction's part of unknown direction.

    Returns
    -------
    bound, integration, eigensolver, orbit : ndarray (m,)
        Absolute bounds (same unit as mu: none); ``bound = integration + eigensolver + orbit``.

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> from pinlin.periodic.cyclic import cyclic_eigen
    >>> eig = cyclic_eigen(tr.factors)
    >>> from pinlin.periodic.bounds import multiplier_bounds
    >>> bound, integration, eigensolver, orbit = multiplier_bounds(tr, eig)
    >>> print(bool(np.all(bound == integration + eigensolver)), bool(np.all(bound < 1e-10)), orbit)
    True True [0. 0.]
    """
    K = len(tr.factors)
    overlap = np.abs(np.einsum("kjp,kjp->k", eig.left.conj(), eig.right))   # |w^H z|
    overlap = np.maximum(overlap, np.finfo(float).tiny)
    scale = K * np.abs(eig.multipliers) / (np.abs(eig.roots) * overlap)
    sums, orbit_sums = _integration_sums(tr, eig, orbit)
    integration, orbit = scale * sums, scale * orbit_sums
    eta = np.maximum(eig.backward_error, _EPS)
    eigensolver = scale * eta * eig.cyclic_norm
    return integration + eigensolver + orbit, integration, eigensolver, orbit


def monodromy_perturbation(tr: Transitions, orbit_errors: list | None = None) -> float:
    """A bound on ||Phi(T) computed - Phi(T) exact||_2: each step's error (its projected-estimate factor rho
    on the estimate's norm, its rounding floor, h ||P|| times its coefficient errors) carried to T by the
    norms of the transitions before and after it, plus eps ||Phi(T)|| per segment.

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> from pinlin.periodic.bounds import monodromy_perturbation
    >>> tr = integrate_transitions(lambda t: np.array([[0.0, 1.0], [-1.0, 0.0]]), 2 * np.pi, 2)
    >>> print(monodromy_perturbation(tr) < 1e-12)
    True
    """
    m = tr.steps[0].P.shape[0]
    before, Phi = [], np.eye(m)
    for step in tr.steps:
        before.append(float(np.linalg.norm(Phi, 2)))
        Phi = step.P @ Phi
    after, Psi = [0.0] * len(tr.steps), np.eye(m)
    for i in range(len(tr.steps) - 1, -1, -1):
        after[i] = float(np.linalg.norm(Psi, 2))
        Psi = Psi @ tr.steps[i].P
    total = len(tr.factors) * _EPS * float(np.linalg.norm(Phi, 2))
    for i, step in enumerate(tr.steps):
        local = PROJECTION_FACTOR * step.estimate_norm + step.rounding
        for E in (step.coefficient_error, None if orbit_errors is None else orbit_errors[i]):
            if E is not None:
                local += step.h * step.norm * float(np.abs(E).sum())
        total += after[i] * local * before[i]
    return total


def jordan_bound(monodromy: np.ndarray, multipliers: np.ndarray, pair: np.ndarray, perturbation: float) -> float:
    """How far a defective double multiplier at 1 (a Jordan block: the trivial pair of a conservative
    family's orbit) moves under a perturbation of the monodromy of 2-norm ``perturbation``.  In a Schur basis
    the block is I + N on its invariant subspace, N nilpotent with ||N|| = c; a perturbation F of it moves
    the pair to 1 + lambda with lambda^2 - tr(F) lambda - c F_21 + ... = 0, so |lambda| <= sqrt(c ||F||) + ||F||
    (not kappa ||F||: the square root is what a Jordan block does), with ||F|| <= ||Y|| ``perturbation``, Y
    the projector's left basis.

    Examples
    --------
    [[1, 1], [0, 1]] perturbed by 1e-10 in its corner has the multipliers 1 +- 1e-5:

    >>> from pinlin.periodic.bounds import jordan_bound
    >>> Phi = np.array([[1.0, 1.0], [1e-10, 1.0]])
    >>> mu = np.linalg.eigvals(Phi)
    >>> print(f"{abs(mu - 1).max():.3e}", f"{jordan_bound(Phi, mu, np.array([True, True]), 1e-10):.3e}")
    1.000e-05 1.000e-05
    """
    radius = float(np.max(np.abs(multipliers[pair] - 1))) * (1 + 1e-8) + np.finfo(float).tiny
    T, Q, k = scipy.linalg.schur(monodromy.astype(complex), output="complex", sort=lambda x: abs(x - 1) <= radius)
    N = T[:k, :k] - np.eye(k)
    c = float(np.linalg.norm(np.triu(N, 1), 2))
    Y = 1.0
    if k < T.shape[0]:
        X = scipy.linalg.solve_sylvester(T[:k, :k], -T[k:, k:], -T[:k, k:])
        Y = float(np.sqrt(1.0 + np.linalg.norm(X, 2) ** 2))
    F = Y * perturbation
    return float(np.sqrt(c * F) + F)


def relative_condition(tr: Transitions, eig: CyclicEigen) -> np.ndarray:
    """kappa_k: to first order |delta mu_k| / |mu_k| <= kappa_k delta for perturbations of every segment
    transition of relative size delta (||E_j|| <= delta ||Phi_j||),

    .. math::  \\kappa_k = K \\sum_j \\|w_j\\| \\|\\Phi_j\\| \\|z_{j-1}\\| / (|\\lambda| |w^H z|).

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> from pinlin.periodic.cyclic import cyclic_eigen
    >>> eig = cyclic_eigen(tr.factors)
    >>> from pinlin.periodic.bounds import relative_condition
    >>> print(np.round(relative_condition(tr, eig), 3))
    [1.19 1.19]
    """
    K = len(tr.factors)
    overlap = np.maximum(np.abs(np.einsum("kjp,kjp->k", eig.left.conj(), eig.right)), np.finfo(float).tiny)
    total = np.zeros(eig.multipliers.size)
    for j, factor in enumerate(tr.factors):
        total += (np.linalg.norm(eig.left[:, (j + 1) % K, :], axis=1) * np.linalg.norm(factor, 2)
                  * np.linalg.norm(eig.right[:, j, :], axis=1))
    return K * total / (np.abs(eig.roots) * overlap)
