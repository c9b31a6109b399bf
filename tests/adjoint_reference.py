"""Independent references for the adjoint tests: mpmath at 50 digits and closed forms.

Nothing here uses pinlin's algorithms: determinants and cofactors by mpmath's
LU at 50 digits, polynomial coefficients from the eigenvalues of the 50-digit
companion matrix, inverses by mpmath.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np

import pinlin
from pinlin.testing import mp_characteristic_coefficients

DPS = 50


def random_system(rng: np.random.Generator, n: int, *, gyroscopic: bool = True) -> pinlin.LinearizedSystem:
    """M spd, C and K general (so D, G, S, N all present), entries O(1)."""
    A = rng.standard_normal((n, n))
    M = A @ A.T + n * np.eye(n)
    C = rng.standard_normal((n, n)) if gyroscopic else np.zeros((n, n))
    K = rng.standard_normal((n, n)) + 2 * np.eye(n)
    return pinlin.LinearizedSystem.from_matrices(M, C, K)


def chain(n: int, damping: float = 0.01) -> pinlin.LinearizedSystem:
    scene = pinlin.Scene(
        pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n)),
        [pinlin.JointDamper(f"joint{i + 1}", damping) for i in range(n)],
    )
    return pinlin.linearize(scene, scene.neutral())


def double_pendulum() -> pinlin.LinearizedSystem:
    """The paper's double pendulum with follower load (theory: double pendulum)."""
    scene = pinlin.Scene(
        pinlin.load_urdf_string(pinlin.double_pendulum_urdf()),
        [
            pinlin.JointSpring("joint1", 3.0),
            pinlin.JointSpring("joint2", 2.0),
            pinlin.FollowerWrench("tip", force=(0, 0, 4.0)),
        ],
    )
    return pinlin.linearize(scene, scene.neutral())


def L_mp(sys, lam) -> mp.matrix:
    """L(lam) in mpmath (the float matrices are exact binary numbers; lam taken exactly)."""
    n = sys.n
    if not isinstance(lam, (mp.mpf, mp.mpc)):
        lam = mp.mpc(complex(lam).real, complex(lam).imag)
    return mp.matrix(
        [[lam**2 * mp.mpf(sys.M[i, j]) + lam * mp.mpf(sys.C[i, j]) + mp.mpf(sys.K[i, j]) for j in range(n)] for i in range(n)]
    )


def det_mp(sys, lam) -> complex:
    with mp.workdps(DPS):
        return complex(mp.det(L_mp(sys, lam)))


def adj_mp(sys, lam) -> np.ndarray:
    """adj L(lam) by cofactors, each a 50-digit determinant."""
    n = sys.n
    with mp.workdps(DPS):
        A = L_mp(sys, lam)
        out = np.empty((n, n), dtype=complex)
        if n == 1:
            return np.ones((1, 1), dtype=complex)
        for i in range(n):
            for j in range(n):
                minor = mp.matrix([[A[r, c] for c in range(n) if c != i] for r in range(n) if r != j])
                out[i, j] = complex((-1) ** (i + j) * mp.det(minor))
        return out


def adj_entry_mp(sys, lam, r: int, c: int):
    """Entry (r, c) of adj L(lam) as an mpmath number (lam may be an mpmath number: for mp.diff)."""
    n = sys.n
    A = L_mp(sys, lam)
    if n == 1:
        return mp.mpc(1)
    minor = mp.matrix([[A[i, j] for j in range(n) if j != r] for i in range(n) if i != c])
    return (-1) ** (r + c) * mp.det(minor)


def inv_mp(sys, lam) -> np.ndarray:
    n = sys.n
    with mp.workdps(DPS):
        H = mp.inverse(L_mp(sys, lam))
        return np.array([[complex(H[i, j]) for j in range(n)] for i in range(n)])


def poly_coefficients_mp(sys) -> np.ndarray:
    """det M prod_k (lam - lam_k), lam_k eigenvalues of the 50-digit companion matrix, ascending powers."""
    return mp_characteristic_coefficients(sys, dps=DPS)[0]


def angle(u: np.ndarray, v: np.ndarray) -> float:
    """Angle between the complex lines spanned by u and v [rad], accurate for small angles."""
    u = u / np.linalg.norm(u)
    v = v / np.linalg.norm(v)
    return float(np.linalg.norm(v - u * np.vdot(u, v)))
