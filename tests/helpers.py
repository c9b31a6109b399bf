"""Shared test helpers: finite differences taken on the configuration manifold."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from pinlin.linearization.assembly import assemble


def residual(scene, q, v):
    """r(q, v) = tau(q, v, 0, fext) - Q_e(q, v) on the whole tangent space."""
    return assemble(scene, q, v, stiffness=False).residual


def fd_jacobians(scene, q, v=None, h=1e-6):
    """Central differences of r in q (through pin.integrate) and in v: (K_fd, C_fd), nv x nv."""
    v = np.array(scene.v0 if v is None else v, dtype=float)
    nv = scene.model.nv
    K = np.zeros((nv, nv))
    C = np.zeros((nv, nv))
    for k in range(nv):
        e = np.zeros(nv)
        e[k] = h
        K[:, k] = (residual(scene, pin.integrate(scene.model, q, e), v) - residual(scene, pin.integrate(scene.model, q, -e), v)) / (2 * h)
        C[:, k] = (residual(scene, q, v + e) - residual(scene, q, v - e)) / (2 * h)
    return K, C


def rel_err(a, b):
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)) / max(np.linalg.norm(b), 1e-300))
