"""High-precision Floquet references (mpmath) for the tests of pinlin.periodic.

For first-order coefficients that are trigonometric polynomials of degree one in t,
A(t) = A0 + A1 cos(t) + A2 sin(t) (period 2 pi), each step transition Phi(t0 + h, t0) is summed from its
Taylor series, whose coefficients obey

    (k + 1) Phi_{k+1} = A0 Phi_k + sum_{i=0}^{k} (c_i A1 + s_i A2) Phi_{k-i},
    c_i = cos(t0 + i pi / 2) / i!,  s_i = sin(t0 + i pi / 2) / i!,

truncated where the terms fall below 10^-(dps + 5) (the series is entire).  The steps are multiplied and
the eigenvalues taken at ``product_dps`` digits: the factors' own errors are structured (relative to each
factor), so the product's eigenvalues keep every multiplier's relative accuracy when ``product_dps`` covers
the digits wanted plus the decades the multipliers span.
"""

from __future__ import annotations

import mpmath
import numpy as np


def _mp_matrix(a) -> np.ndarray:
    return np.array([[mpmath.mpf(float(x)) for x in row] for row in np.asarray(a, dtype=float)], dtype=object)


def _step(A0, A1, A2, t0, h, tol):
    m = A0.shape[0]
    eye = np.array([[mpmath.mpf(int(i == j)) for j in range(m)] for i in range(m)], dtype=object)
    term, total, hk, k = eye, eye.copy(), mpmath.mpf(1), 0
    B1, B2, c, s = [A1.dot(eye)], [A2.dot(eye)], [], []
    while True:
        c.append(mpmath.cos(t0 + k * mpmath.pi / 2) / mpmath.factorial(k))
        s.append(mpmath.sin(t0 + k * mpmath.pi / 2) / mpmath.factorial(k))
        conv = np.tensordot(np.array(c[::-1], dtype=object), np.array(B1, dtype=object), axes=1)
        conv = conv + np.tensordot(np.array(s[::-1], dtype=object), np.array(B2, dtype=object), axes=1)
        term = (A0.dot(term) + conv) / (k + 1)
        B1.append(A1.dot(term))
        B2.append(A2.dot(term))
        hk *= h
        k += 1
        total = total + term * hk
        if k > 4 and max(abs(x) for x in (term * hk).ravel()) < tol:
            return total


def reference_multipliers(A0, A1, A2, *, steps: int, dps: int = 36, product_dps: int = 80) -> list:
    """Multipliers of y' = (A0 + A1 cos t + A2 sin t) y over T = 2 pi, sorted by decreasing modulus
    (mpmath complex numbers)."""
    with mpmath.workdps(dps):
        A0m, A1m, A2m = (_mp_matrix(a) for a in (A0, A1, A2))
        T = 2 * mpmath.pi
        h = T / steps
        tol = mpmath.mpf(10) ** (-dps - 5)
        factors = [_step(A0m, A1m, A2m, j * h, h, tol) for j in range(steps)]
    with mpmath.workdps(product_dps):
        Phi = mpmath.eye(A0.shape[0])
        for F in factors:
            Phi = mpmath.matrix(F.tolist()) * Phi
        ev = mpmath.eig(Phi, left=False, right=False)
    return sorted(ev, key=lambda z: -abs(z))


def second_order_parts(C_parts, K_parts):
    """(A0, A1, A2) of y = (x, x') for M = I, C = C0 + C1 cos t + C2 sin t, K likewise."""
    n = C_parts[0].shape[0]
    out = []
    for j, (Cj, Kj) in enumerate(zip(C_parts, K_parts)):
        A = np.zeros((2 * n, 2 * n))
        if j == 0:
            A[:n, n:] = np.eye(n)
        A[n:, :n], A[n:, n:] = -Kj, -Cj
        out.append(A)
    return out
