"""Frequency identification of Floquet modes by their harmonic content (SPEC section 13).

A Floquet mode y_k(t) = Phi(t) x_k = exp(Lambda_k t) p_k(t), Lambda_k = log(mu_k) / T (principal branch), has
a T-periodic part p_k with Fourier coefficients

.. math::  c_j = \\frac{1}{T} \\int_0^T p_k(t)\\, e^{-i j \\omega_T t}\\, dt, \\qquad \\omega_T = 2\\pi / T,

so y_k = sum_j c_j exp((Lambda_k + i j omega_T) t).  The representative exponent is Lambda_k + i j* omega_T
with j* the harmonic of largest energy ||c_j||^2 (over the chosen components, positions by default); the
content is ||c_j||^2 / ((1/T) int ||p_k||^2 dt), so a content summing well below 1 says that harmonics beyond
the reported range carry energy.  The integrals are the steps' own Gauss quadratures at their nodes (the
stage values there are accurate to order s); p_k is propagated inside each segment only, from the periodic
eigenvector at the segment's start, so a decaying mode is not swamped by the growing ones.
"""

from __future__ import annotations

import numpy as np

from .collocation import Transitions
from .cyclic import CyclicEigen

__all__ = ["harmonic_content"]


def _periodic_part_coefficients(tr, eig, k, period, harmonics, rows):
    """(Fourier coefficients (2J+1, len(rows)), mean energy) of p_k."""
    lam_T = np.log(complex(eig.multipliers[k])) / period
    log_root = np.log(complex(eig.roots[k]))
    js = np.arange(-harmonics, harmonics + 1)
    coeff = np.zeros((js.size, len(rows)), dtype=complex)
    energy = 0.0
    for j, (begin, end) in enumerate(tr.segments):
        t_seg = tr.steps[begin].t0
        # x_j = lambda^j z_j is the mode at t_j; p(t_j) = exp(-Lambda t_j) x_j
        u = eig.right[k, j] * np.exp(j * log_root - lam_T * t_seg)
        for step in tr.steps[begin:end]:
            values = np.einsum("ipq,q->ip", step.stage, u) * np.exp(-lam_T * (step.nodes - step.t0))[:, None]
            values = values[:, rows]
            phase = np.exp(-1j * np.outer(js, step.nodes) * 2 * np.pi / period)
            coeff += phase @ (values * step.weights[:, None])
            energy += float(np.sum(step.weights * np.sum(np.abs(values) ** 2, axis=1)))
            u = (step.P @ u) * np.exp(-lam_T * step.h)
    return coeff / period, energy / period


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
    """
    m = eig.multipliers.size
    rows = np.arange(eig.right.shape[2]) if rows is None else np.asarray(rows)
    content = np.zeros((m, 2 * harmonics + 1))
    dominant = np.zeros(m, dtype=int)
    for k in range(m):
        coeff, energy = _periodic_part_coefficients(tr, eig, k, period, harmonics, rows)
        e = np.sum(np.abs(coeff) ** 2, axis=1)
        content[k] = e / energy if energy > 0 else e
        dominant[k] = int(np.argmax(e)) - harmonics
    principal = np.angle(eig.multipliers) / period
    return principal + dominant * 2 * np.pi / period, content, dominant
