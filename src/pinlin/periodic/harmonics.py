"""Frequency identification of Floquet modes by their harmonic content (theory: Floquet).

A Floquet mode y_k(t) = Phi(t) x_k = exp(Lambda_k t) p_k(t), Lambda_k = log(mu_k) / T (principal branch), has
a T-periodic part p_k with Fourier coefficients

.. math::  c_j = \\frac{1}{T} \\int_0^T p_k(t)\\, e^{-i j \\omega_T t}\\, dt, \\qquad \\omega_T = 2\\pi / T,

so y_k = sum_j c_j exp((Lambda_k + i j omega_T) t).  The representative exponent is Lambda_k + i j* omega_T
with j* the harmonic of largest energy ||c_j||^2 (over the chosen components, positions by default); the
content is ||c_j||^2 / ((1/T) int ||p_k||^2 dt), so a content summing well below 1 says that harmonics beyond
the reported range carry energy.  The integrals are the steps' own Gauss quadratures at their nodes (the
stage values there are accurate to order s); p_k is propagated inside each segment only, from the periodic
eigenvector at the segment's start, so a decaying mode is not swamped by the growing ones.  Harmonics near
the node resolution (about the number of nodes per period / 2) are aliased by the quadrature: their content
is noise of the order of the step's interpolation error (measured 1e-6 of the energy for J = 16 on a 5-step
Mathieu period), so the content may sum slightly above 1.
"""

from __future__ import annotations

import numpy as np

from .collocation import Transitions
from .cyclic import CyclicEigen

__all__ = ["harmonic_content"]


def _periodic_part_coefficients(tr, eig, period, harmonics, rows):
    """(Fourier coefficients (modes, 2J+1, len(rows)), mean energies (modes,)) of every p_k at once, each
    segment's steps on stacks."""
    lam_T = np.log(eig.multipliers.astype(complex)) / period          # (modes,)
    log_root = np.log(eig.roots.astype(complex))
    js = np.arange(-harmonics, harmonics + 1)
    modes = lam_T.size
    coeff = np.zeros((js.size, len(rows), modes), dtype=complex)
    energy = np.zeros(modes)
    for j, (begin, end) in enumerate(tr.segments):
        steps = tr.steps[begin:end]
        t_seg = steps[0].t0
        # x_j = lambda^j z_j is the mode at t_j; p(t_j) = exp(-Lambda t_j) x_j; columns are modes
        U = eig.right[:, j, :].T * np.exp(j * log_root - lam_T * t_seg)[None, :]
        starts = []
        for step in steps:
            starts.append(U)
            U = (step.P @ U) * np.exp(-lam_T * step.h)[None, :]
        stage = np.stack([step.stage for step in steps])                   # (S, nodes, m, m)
        offsets = np.stack([step.nodes - step.t0 for step in steps])        # (S, nodes)
        nodes = np.concatenate([step.nodes for step in steps])
        weights = np.concatenate([step.weights for step in steps])
        decay = np.exp(-offsets[..., None] * lam_T)                         # (S, nodes, modes)
        S, count, r = stage.shape[0], stage.shape[1], len(rows)
        U0 = np.stack(starts)
        # the real stage transitions on [Re | Im] of the complex starts: one product per step
        product = stage[:, :, rows, :].reshape(S, count * r, -1) @ np.concatenate([U0.real, U0.imag], axis=2)
        values = (product[..., :modes] + 1j * product[..., modes:]).reshape(S, count, r, modes)
        values = (values * decay[:, :, None, :]).reshape(-1, r, modes)      # (S nodes, rows, modes)
        phase = np.exp(-1j * np.outer(js, nodes) * 2 * np.pi / period) * weights[None, :]
        coeff += np.tensordot(phase, values, axes=(1, 0))
        energy += np.tensordot(weights, np.abs(values) ** 2, axes=(0, 0)).sum(axis=0)
    return coeff.transpose(2, 0, 1) / period, energy / period


def harmonic_content(tr: Transitions, eig: CyclicEigen, period: float, *, harmonics: int = 16, rows=None):
    """Frequencies [rad/s] of the modes and their harmonic content.

    Parameters
    ----------
    tr, eig : Transitions, CyclicEigen
        Steps (with their node data) and the periodic eigenvectors.
    period : float
        T [s].
    harmonics : int
        J: the content is reported for j = -J..J.
    rows : index array or None
        Components of y whose energy counts (None: all).

    Returns
    -------
    frequencies : ndarray (m,)
        Im(Lambda_k) + j*_k omega_T [rad/s].
    content : ndarray (m, 2J+1)
        Energy fraction of harmonic j (column j + J) in p_k.
    dominant : ndarray of int (m,)
        j*_k.

    Examples
    --------
    >>> from pinlin.periodic.collocation import integrate_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])       # Mathieu, undamped
    >>> tr = integrate_transitions(A, 2 * np.pi, 2)
    >>> from pinlin.periodic.cyclic import cyclic_eigen
    >>> eig = cyclic_eigen(tr.factors)
    >>> from pinlin.periodic.harmonics import harmonic_content
    >>> freq, content, dominant = harmonic_content(tr, eig, 2 * np.pi, harmonics=4)
    >>> print(content.shape, np.allclose(content.sum(axis=1), 1.0), np.round(np.abs(freq), 3))
    (2, 9) True ...
    """
    rows = np.arange(eig.right.shape[2]) if rows is None else np.asarray(rows)
    coeff, energy = _periodic_part_coefficients(tr, eig, period, harmonics, rows)
    e = np.sum(np.abs(coeff) ** 2, axis=2)                          # (modes, 2J+1)
    content = e / np.where(energy > 0, energy, 1.0)[:, None]
    dominant = np.argmax(e, axis=1) - harmonics
    principal = np.angle(eig.multipliers) / period
    return principal + dominant * 2 * np.pi / period, content, dominant
