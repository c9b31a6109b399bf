"""Systems and independent references for the spectral tests (theory: spectrum).

References never share pinlin's method: closed forms, hand derivations, and
mpmath at 50 digits (roots of det L(lam) interpolated exactly).
"""

from __future__ import annotations

import mpmath as mp
import numpy as np

import pinlin
from pinlin import FollowerWrench, JointDamper, JointSpring, Scene
from pinlin.testing import cantilever_beam

# theory: spectrum check problem lam^2 A2 + lam A1 + A0 (A2 not symmetric)
A2 = np.array([[1, 2, 2], [3, 1, 1], [3, 2, 1.0]])
A1 = np.array([[3, 2, 1], [2, 1, 3], [1, 3, 2.0]])
A0 = np.array([[1, 1, 2], [2, 3, 1], [3, 1, 2.0]])


def chain(n, ks=None, *, gravity=(0, 0, -9.81), dampers=None):
    """Hanging n-link chain (1 m, 1 kg), optional joint springs and dampers."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    el = [] if ks is None else [JointSpring(f"joint{i + 1}", k) for i, k in enumerate(ks)]
    if dampers is not None:
        el += [JointDamper(f"joint{i + 1}", c) for i, c in enumerate(dampers)]
    scene = Scene(robot, el, gravity=gravity)
    return pinlin.linearize(scene, robot.neutral())


def ring(k=4.0, c=0.0, Omega=1.0):
    """theory: rotating ring: particle (m = 1) in a ring turning at Omega, springs k, dampers c."""
    el = [JointSpring("x", k), JointSpring("y", k)]
    if c:
        el += [JointDamper("x", c), JointDamper("y", c)]
    scene = Scene(pinlin.load_urdf_string(pinlin.rotating_ring_urdf(1.0)), el, prescribed={"ring": Omega})
    return pinlin.linearize(scene, scene.neutral())


def ring_closed_form(m, k, c, Omega):
    """Roots of m lam^2 + (c + 2 i m Omega) lam + (k - m Omega^2) = 0 and their conjugates (z = x + i y)."""
    a, b, cc = m, c + 2j * m * Omega, k - m * Omega**2
    disc = np.sqrt(b * b - 4 * a * cc + 0j)
    r = np.array([(-b + disc) / (2 * a), (-b - disc) / (2 * a)])
    return np.concatenate([r, np.conj(r)])


def double_pendulum(P=4.0, c=0.0, gravity=(0, 0, -9.81)):
    """The paper's double pendulum (theory: double pendulum) with follower load P and joint dampers c."""
    el = [JointSpring("joint1", 3.0), JointSpring("joint2", 2.0), FollowerWrench("tip", force=(0, 0, P))]
    if c:
        el += [JointDamper("joint1", c), JointDamper("joint2", c)]
    scene = Scene(pinlin.load_urdf_string(pinlin.double_pendulum_urdf()), el, gravity=gravity)
    return pinlin.linearize(scene, scene.neutral())


def double_pendulum_spec(P=4.0, m1=1.3, l1=0.7, m2=0.9, l2=0.5, k1=3.0, k2=2.0, g=9.81):
    """theory: double pendulum hand-derived (M, S, N) in relative angles theta."""
    Mp = np.array([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]])
    Sp = np.array(
        [[k1 + k2 + (m1 / 2 + m2) * g * l1 - P * l1, -k2 + P * l1 / 2], [-k2 + P * l1 / 2, k2 + m2 * g * l2 / 2]]
    )
    Np = P * l1 / 2 * np.array([[0, 1.0], [-1.0, 0]])
    T = np.array([[1.0, 0], [1.0, 1.0]])
    return T.T @ Mp @ T, T.T @ Sp @ T, T.T @ Np @ T


def cantilever(ne=40, L=2.0, E=2.1e11, I=8.33e-10, rhoA=0.785, c=50.0, at=None):
    """Clamped-free Euler-Bernoulli beam with one dashpot (see :func:`pinlin.testing.cantilever_beam`)."""
    return cantilever_beam(ne, L, E, I, rhoA, c, at)



#: beta_r L of a cantilever: 1 + cos(bL) cosh(bL) = 0
CANTILEVER_BETA_L = (1.8751040687119611, 4.6940911329741745, 7.8547574382376126)


def mp_eigenvalues(M, C, K, dps=50):
    """All 2n eigenvalues as roots of det L(lam), in mpmath at ``dps`` digits.

    det L is interpolated exactly (degree 2n, 2n + 1 nodes) from mpmath
    determinants, then its roots are polished by mpmath.polyroots.
    """
    with mp.workdps(dps):
        n = M.shape[0]
        deg = 2 * n
        nodes = [mp.mpf(j) - mp.mpf(deg) / 2 for j in range(deg + 1)]

        def det_at(x):
            L = mp.matrix(n, n)
            for i in range(n):
                for j in range(n):
                    L[i, j] = x * x * mp.mpf(M[i, j]) + x * mp.mpf(C[i, j]) + mp.mpf(K[i, j])
            return mp.det(L)

        V = mp.matrix([[x**p for p in range(deg + 1)] for x in nodes])
        coef = mp.lu_solve(V, mp.matrix([det_at(x) for x in nodes]))
        roots = mp.polyroots([coef[p] for p in range(deg + 1)], maxsteps=500, extraprec=500, asc=True)
        return np.array([complex(r) for r in roots])


def match(computed, reference):
    """Reorder ``reference`` to the nearest-neighbour order of ``computed`` (greedy, one-to-one)."""
    ref = list(np.asarray(reference, dtype=complex))
    out = []
    for x in computed:
        j = int(np.argmin([abs(x - r) for r in ref]))
        out.append(ref.pop(j))
    return np.array(out)


def eta_reference(M, C, K, lam, X):
    """Backward errors recomputed here from the definition (Frobenius norms)."""
    R = (M @ X) * lam**2 + (C @ X) * lam + K @ X
    w = np.abs(lam) ** 2 * np.linalg.norm(M) + np.abs(lam) * np.linalg.norm(C) + np.linalg.norm(K)
    return np.linalg.norm(R, axis=0) / (w * np.linalg.norm(X, axis=0))


def nlevp_damped_beam(n=200, damping=5.0):
    """NLEVP ``damped_beam`` (Higham, Mackey, Tisseur and Garvey, Int. J. Numer. Meth. Eng. 73, 2008).

    A beam of length 1 m (width 0.05 m, height 0.005 m, E = 7e10 Pa, mass 0.674 kg),
    simply supported at both ends, of n/2 Hermite cubic elements, with a dashpot
    ``damping`` [N s/m] on the transverse displacement of the middle node.
    Coordinates: (theta_0, w_1, theta_1, ..., w_{m-1}, theta_{m-1}, theta_m), m = n/2.
    The modes antisymmetric about the middle do not move the dashpot: half of the
    eigenvalues are purely imaginary in exact arithmetic, the undamped beam's.
    """
    m = n // 2
    h = 1.0 / m
    EI = 7e10 * 0.05 * 0.005**3 / 12
    rho_a = 0.674 / 1.0
    ke = EI / h**3 * np.array(
        [[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
         [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]]
    )
    me = rho_a * h / 420 * np.array(
        [[156, 22 * h, 54, -13 * h], [22 * h, 4 * h * h, 13 * h, -3 * h * h],
         [54, 13 * h, 156, -22 * h], [-13 * h, -3 * h * h, -22 * h, 4 * h * h]]
    )
    size = 2 * (m + 1)
    K, M = np.zeros((size, size)), np.zeros((size, size))
    for e in range(m):
        idx = slice(2 * e, 2 * e + 4)
        K[idx, idx] += ke
        M[idx, idx] += me
    keep = [i for i in range(size) if i not in (0, 2 * m)]  # w_0 = w_m = 0: simply supported
    K, M = K[np.ix_(keep, keep)], M[np.ix_(keep, keep)]
    D = np.zeros((n, n))
    D[2 * (m // 2) - 1, 2 * (m // 2) - 1] = damping  # w at the middle node m/2
    return pinlin.LinearizedSystem.from_matrices(M, D, K)
