"""Hand-derived periodic systems for the tests of pinlin.periodic (SPEC section 13 reference cases)."""

from __future__ import annotations

import numpy as np


def mathieu(delta: float, eps: float, damping: float = 0.0):
    """x'' + damping x' + (delta + eps cos t) x = 0: (M, C, K) callables, period 2 pi."""
    return (lambda t: np.eye(1), lambda t: np.array([[damping]]),
            lambda t: np.array([[delta + eps * np.cos(t)]]))


def hill_characteristic(kind: str, r: int, q: float, size: int = 60) -> float:
    """Mathieu characteristic value a_r(q) (kind "a") or b_r(q) (kind "b") of y'' + (a - 2 q cos 2z) y = 0
    from the truncated symmetric tridiagonal matrix of its Fourier coefficients (Hill's method; the
    truncation error decays like q^size / (size!)^2).

    The four families: cos 2kz (a_even: diagonal 4k^2, first off-diagonal sqrt(2) q), sin (2k+2)z (b_even:
    (2k+2)^2), cos (2k+1)z (a_odd: (2k+1)^2, first diagonal entry 1 + q), sin (2k+1)z (b_odd: 1 - q).
    """
    k = np.arange(size)
    if r % 2 == 0 and kind == "a":
        d, off = (2.0 * k) ** 2, np.full(size - 1, q)
        off[0] = np.sqrt(2) * q
        index = r // 2
    elif r % 2 == 0:
        d, off, index = (2.0 * k + 2) ** 2, np.full(size - 1, q), r // 2 - 1
    else:
        d, off, index = (2.0 * k + 1) ** 2, np.full(size - 1, q), (r - 1) // 2
        d[0] += q if kind == "a" else -q
    T = np.diag(d) + np.diag(off, 1) + np.diag(off, -1)
    return float(np.linalg.eigvalsh(T)[index])


def shaft_inertial(m: float, k1: float, k2: float, Omega: float, c: float = 0.0):
    """Asymmetric shaft in inertial coordinates: M = m I, C = c I, K(t) = R(Omega t) diag(k1, k2) R^T;
    period pi / Omega."""
    def K(t):
        ct, st = np.cos(Omega * t), np.sin(Omega * t)
        R = np.array([[ct, -st], [st, ct]])
        return R @ np.diag([k1, k2]) @ R.T
    return (lambda t: m * np.eye(2), lambda t: c * np.eye(2), K), np.pi / Omega


def shaft_rotating_eigenvalues(m: float, k1: float, k2: float, Omega: float, c: float = 0.0) -> np.ndarray:
    """Eigenvalues [1/s] of the same shaft in rotating coordinates: m I, G = 2 m Omega J + c I,
    K = diag(k1, k2) - m Omega^2 I + c Omega J (the damping's rotating-frame circulatory part)."""
    J = np.array([[0.0, -1.0], [1.0, 0.0]])
    M, C = m * np.eye(2), 2 * m * Omega * J + c * np.eye(2)
    K = np.diag([k1, k2]) - m * Omega ** 2 * np.eye(2) + c * Omega * J
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    return np.linalg.eigvals(A)


def residues_modulo(values: np.ndarray, references: np.ndarray, step: float) -> float:
    """Largest distance from each value to the nearest reference shifted by an integer multiple of i step."""
    worst = 0.0
    for v in values:
        shifted = references + 1j * step * np.round((v.imag - references.imag) / step)
        worst = max(worst, float(np.min(np.abs(shifted - v))))
    return worst
