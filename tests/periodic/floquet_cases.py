"""Hand-derived periodic systems for the tests of pinlin.periodic (theory: Floquet reference cases)."""

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


def lag_rotor(N: int = 3, *, Omega: float = 3.0, hub=(10.0, 40.0, 60.0, 0.4, 0.4), blade=(1.0, 0.3, 1.2, 0.05),
              lag=(2.0, 0.02), blade_changes=None):
    """Coleman-Feingold ground resonance: a hub (mass m_h on springs k_x, k_y with dampers c_x, c_y) carrying
    N blades on lag hinges at offset e, blade k at azimuth psi_k = Omega t + 2 pi (k - 1) / N, point mass m_b
    at distance b beyond the hinge plus inertia I_b, lag spring k_z and damper c_z; coordinates
    (x, y, zeta_1, ..., zeta_N).

    Lagrangian (blade mass at r_k = (x, y) + e (cos psi_k, sin psi_k) + b (cos, sin)(psi_k + zeta_k)),
    linearized about x = y = zeta = 0 (the steady terms cancel for N >= 2 equally spaced blades):

        (m_h + N m_b) x'' + c_x x' + k_x x - m_b b sum_k (s_k zeta_k'' + 2 Omega c_k zeta_k' - Omega^2 s_k zeta_k) = 0
        (m_h + N m_b) y'' + c_y y' + k_y y + m_b b sum_k (c_k zeta_k'' - 2 Omega s_k zeta_k' - Omega^2 c_k zeta_k) = 0
        (I_b + m_b b^2) zeta_k'' + c_z zeta_k' + (k_z + m_b e b Omega^2) zeta_k + m_b b (-s_k x'' + c_k y'') = 0

    with s_k, c_k = sin psi_k, cos psi_k.  ``hub`` = (m_h, k_x, k_y, c_x, c_y); ``blade`` = (m_b, e, b, I_b);
    ``lag`` = (k_z, c_z); ``blade_changes`` = {k: factor} scales blade k's lag spring (dissimilar blades).
    Returns (M, C, K) callables and the period 2 pi / Omega.
    """
    m_h, k_x, k_y, c_x, c_y = hub
    m_b, e, b, I_b = blade
    k_z, c_z = lag
    changes = blade_changes or {}
    n = N + 2

    def parts(t):
        psi = Omega * t + 2 * np.pi * np.arange(N) / N
        return np.sin(psi), np.cos(psi)

    def M(t):
        s, c = parts(t)
        out = np.zeros((n, n))
        out[0, 0] = out[1, 1] = m_h + N * m_b
        out[0, 2:], out[1, 2:] = -m_b * b * s, m_b * b * c
        out[2:, 0], out[2:, 1] = out[0, 2:], out[1, 2:]
        out[2:, 2:] = (I_b + m_b * b * b) * np.eye(N)
        return out

    def C(t):
        s, c = parts(t)
        out = np.diag([c_x, c_y] + [c_z] * N)
        out[0, 2:], out[1, 2:] = -2 * m_b * b * Omega * c, -2 * m_b * b * Omega * s
        return out

    def K(t):
        s, c = parts(t)
        spring = np.array([k_z * changes.get(k, 1.0) for k in range(N)])
        out = np.diag(np.concatenate([[k_x, k_y], spring + m_b * e * b * Omega ** 2]))
        out[0, 2:], out[1, 2:] = m_b * b * Omega ** 2 * s, -m_b * b * Omega ** 2 * c
        return out

    return (M, C, K), 2 * np.pi / Omega
