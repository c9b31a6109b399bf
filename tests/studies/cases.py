"""Sweeps with known answers, shared by the tracking and plot tests (``from studies.cases import ...``)."""

import numpy as np


def crossing_sweep():
    """Two uncoupled oscillators, frequencies p and 2 - p: they cross at p = 1.

    Eigenvalues given sorted by frequency at each step (what a naive plot would
    use), with their shapes e1 (frequency p) and e2 (frequency 2 - p) in the same order.
    Returns (p (11,), eigenvalues (11, 2), shapes (11, 2, 2)).
    """
    ps = np.linspace(0.5, 1.5, 11)
    lams, vecs = [], []
    for p in ps:
        lam = np.array([1j * p, 1j * (2 - p)])
        order = np.argsort(lam.imag)
        lams.append(lam[order])
        vecs.append(np.eye(2, dtype=complex)[:, order])
    return ps, np.array(lams), np.array(vecs)
