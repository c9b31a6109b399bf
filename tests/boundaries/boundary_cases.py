"""Parameter families with stability boundaries known in closed form (theory: worked examples, boundaries).

Each family is ``func(p) -> LinearizedSystem`` built through pinlin's own pipeline
(URDF -> Scene -> linearize), and each reference is derived by hand below and
evaluated with mpmath at 40 digits, so that a reference never shares the method
under test.

- :func:`double_pendulum` -- theory: double pendulum (the paper's Example 6.2): m1 = 1.3,
  l1 = 0.7, m2 = 0.9, l2 = 0.5, k1 = 3, k2 = 2, g = 9.81, follower load P,
  optional equal joint dampers c.  Undamped, det(mu M + K(P)) = det M mu^2 +
  b(P) mu + det K(P) with b and det K affine in P; the flutter load P_f and the
  divergence load P_d are the roots of the discriminant b^2 - 4 det M det K
  (P_f = 16.4328976484...).
- :func:`ziegler` -- Ziegler's column (Ziegler 1952; Bolotin, *Nonconservative
  Problems of the Theory of Elastic Stability*, 1963): two massless rigid links
  of length l, point masses 2m at the middle joint and m at the tip, joint
  springs k, follower load P at the tip; in absolute angles M = m l^2 [[3, 1],
  [1, 1]], K = [[2k - P l, P l - k], [-k, k]], so det(mu M + K) = m^2 l^4 (2 mu^2 +
  (7 - 2P) mu + 1) for k = l = m = 1: P_f = 7/2 - sqrt(2).
- Damped flutter loads (both families): with equal joint dampers c (D = c I in
  joint coordinates) p(lam) = a0 lam^4 + a1 lam^3 + a2 lam^2 + a3 lam + a4 with
  a0 = det M, a1 = <M, D>, a2 = <M, K> + det D, a3 = <D, K>, a4 = det K
  (<A, B> = A11 B22 + A22 B11 - A12 B21 - A21 B12); Routh-Hurwitz: stable iff all
  a_i > 0 and a1 a2 a3 - a0 a3^2 - a1^2 a4 > 0, a quadratic in P whose smallest
  positive root is the damped flutter load.
- :func:`ring_matrices` -- theory: rotating ring, the particle in a rotating ring with damping
  c > 0, from its matrices: stable iff m Omega^2 < k, critical speed sqrt(k/m).
  (Through the URDF, ``linearize`` refuses the critical speed itself: its
  time-invariance check divides by ||K||, which vanishes there.)
- :func:`compressed_chain` -- n equal links of length l (no gravity), joint
  springs k, a dead compressive tip force P: in absolute angles K = k T - P l I
  with T = tridiag(-1, 2, -1) except T_nn = 1, whose eigenvalues are
  4 sin^2((2j - 1) pi / (2 (2n + 1))): buckling at P = (4 k / l) sin^2(pi / (2 (2n + 1))).
"""

from __future__ import annotations

import mpmath as mp
import numpy as np

import pinlin

mp.mp.dps = 40

# ----------------------------------------------------------------------------- the paper's double pendulum

DP = dict(m1=1.3, l1=0.7, m2=0.9, l2=0.5, k1=3.0, k2=2.0, g=9.81)
_DP_ROBOT = pinlin.load_urdf_string(pinlin.double_pendulum_urdf(DP["m1"], DP["l1"], DP["m2"], DP["l2"]))


def double_pendulum_scene(P, c=0.0):
    elements = [pinlin.JointSpring("joint1", DP["k1"]), pinlin.JointSpring("joint2", DP["k2"]),
                pinlin.FollowerWrench("tip", force=(0.0, 0.0, P))]
    if c:
        elements += [pinlin.JointDamper("joint1", c), pinlin.JointDamper("joint2", c)]
    return pinlin.Scene(_DP_ROBOT, elements, gravity=(0.0, 0.0, -DP["g"]))


def double_pendulum(c=0.0):
    """P -> the linearized double pendulum hanging straight down (an equilibrium for every P)."""
    return lambda P: pinlin.linearize(double_pendulum_scene(P, c), np.zeros(2))


def _dp_phi_matrices(P):
    """M, K = S + N in absolute angles (theory: double pendulum), mpmath."""
    m1, l1, m2, l2, k1, k2, g = (mp.mpf(str(DP[k])) for k in ("m1", "l1", "m2", "l2", "k1", "k2", "g"))
    M = mp.matrix([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]])
    K = mp.matrix([[k1 + k2 + (m1 / 2 + m2) * g * l1 - P * l1, -k2 + P * l1 / 2 + P * l1 / 2],
                   [-k2 + P * l1 / 2 - P * l1 / 2, k2 + m2 * g * l2 / 2]])
    return M, K


_T = mp.matrix([[1, 0], [1, 1]])


def double_pendulum_theta(P):
    """M, K in the URDF's relative angles theta (phi = T theta), mpmath."""
    M, K = _dp_phi_matrices(P)
    return _T.T * M * _T, _T.T * K * _T


def _bracket(A, B):
    return A[0, 0] * B[1, 1] + A[1, 1] * B[0, 0] - A[0, 1] * B[1, 0] - A[1, 0] * B[0, 1]


def _det(A):
    return A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]


def _affine_roots(f, lo, hi):
    """Roots of the quadratic P -> f(P) (exact in P: sampled at three points), real and in [lo, hi], sorted."""
    ps = [mp.mpf(0), mp.mpf(1), mp.mpf(2)]
    v = [f(p) for p in ps]
    a = (v[2] - 2 * v[1] + v[0]) / 2
    b = v[1] - v[0] - a
    c = v[0]
    if a == 0:
        roots = [-c / b]
    else:
        disc = b * b - 4 * a * c
        if disc < 0:
            return []
        q = -(b + mp.sign(b) * mp.sqrt(disc)) / 2  # the quadratic formula without cancellation
        roots = [q / a, c / q]
    return sorted(float(r) for r in roots if lo <= r <= hi)


def undamped_loads(matrices):
    """Roots of the discriminant b(P)^2 - 4 det M det K(P) of det(mu M + K(P)), a quadratic in P."""
    def disc(P):
        M, K = matrices(P)
        return _bracket(M, K) ** 2 - 4 * _det(M) * _det(K)

    return _affine_roots(disc, -1e6, 1e6)


def damped_flutter_load(matrices, c, upper):
    """The smallest positive root of the Routh-Hurwitz determinant a1 a2 a3 - a0 a3^2 - a1^2 a4 for D = c I."""
    D = mp.matrix([[c, 0], [0, c]])

    def hurwitz(P):
        M, K = matrices(P)
        a0, a1, a2 = _det(M), _bracket(M, D), _bracket(M, K) + _det(D)
        a3, a4 = _bracket(D, K), _det(K)
        return a1 * a2 * a3 - a0 * a3**2 - a1**2 * a4

    return _affine_roots(hurwitz, 0.0, upper)[0]


def double_pendulum_dlam(P, lam):
    """d lam / dP of the undamped double pendulum from the quadratic in mu = lam^2 (closed form)."""
    def coefficients(P):
        M, K = double_pendulum_theta(mp.mpf(P))
        return _det(M), _bracket(M, K), _det(K)

    a, b0, c0 = coefficients(0)
    _, b1, c1 = coefficients(1)
    db, dc = b1 - b0, c1 - c0  # b and det K are affine in P
    mu = mp.mpc(lam) ** 2
    b = b0 + db * P
    dmu = -(db * mu + dc) / (2 * a * mu + b)
    return complex(dmu / (2 * mp.mpc(lam)))


# ----------------------------------------------------------------------------- Ziegler's column

ZIEGLER_URDF = """<?xml version="1.0"?>
<robot name="ziegler_column">
  <link name="base"/>
  <link name="link1">
    <inertial><origin xyz="0 0 -1" rpy="0 0 0"/><mass value="2.0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <joint name="joint1" type="revolute">
    <parent link="base"/><child link="link1"/><origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>
  </joint>
  <link name="link2">
    <inertial><origin xyz="0 0 -1" rpy="0 0 0"/><mass value="1.0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <joint name="joint2" type="revolute">
    <parent link="link1"/><child link="link2"/><origin xyz="0 0 -1" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>
  </joint>
  <link name="tip"/>
  <joint name="tip_joint" type="fixed">
    <parent link="link2"/><child link="tip"/><origin xyz="0 0 -1" rpy="0 0 0"/>
  </joint>
</robot>
"""
_ZIEGLER_ROBOT = pinlin.load_urdf_string(ZIEGLER_URDF)


def ziegler(c=0.0):
    """P -> Ziegler's column (k = l = m = 1, no gravity), with equal joint dampers c."""
    def func(P):
        elements = [pinlin.JointSpring("joint1", 1.0), pinlin.JointSpring("joint2", 1.0),
                    pinlin.FollowerWrench("tip", force=(0.0, 0.0, P))]
        if c:
            elements += [pinlin.JointDamper("joint1", c), pinlin.JointDamper("joint2", c)]
        scene = pinlin.Scene(_ZIEGLER_ROBOT, elements, gravity=(0.0, 0.0, 0.0))
        return pinlin.linearize(scene, np.zeros(2))

    return func


def ziegler_theta(P):
    """M, K of Ziegler's column in relative joint angles (k = l = m = 1), mpmath."""
    M = mp.matrix([[3, 1], [1, 1]])
    K = mp.matrix([[2 - P, P - 1], [-1, 1]])
    return _T.T * M * _T, _T.T * K * _T


ZIEGLER_FLUTTER = 3.5 - np.sqrt(2.0)


# ----------------------------------------------------------------------------- rotating ring, compressed chain

RING = dict(m=1.3, k=10.0)


def ring_matrices(c):
    """Omega -> theory: rotating ring's ring from its matrices."""
    m, k = RING["m"], RING["k"]

    def func(omega):
        J = np.array([[0.0, -1.0], [1.0, 0.0]])
        return pinlin.LinearizedSystem(m * np.eye(2), c * np.eye(2), 2 * m * omega * J,
                                       (k - m * omega**2) * np.eye(2), np.zeros((2, 2)))

    return func


def compressed_chain(n, k=2.0, length=1.5):
    """P -> an n-link chain (total length ``length``, no gravity) with springs k under a dead compressive tip force."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=length, mass=1.0))

    def func(P):
        elements = [pinlin.JointSpring(f"joint{i}", k) for i in range(1, n + 1)]
        elements.append(pinlin.DeadWrench("tip", force=(0.0, 0.0, P)))
        scene = pinlin.Scene(robot, elements, gravity=(0.0, 0.0, 0.0))
        return pinlin.linearize(scene, np.zeros(n))

    return func


def chain_buckling_load(n, k=2.0, length=1.5):
    """(4 k / l) sin^2(pi / (2 (2n + 1))), l = length / n."""
    return float(4 * k / (mp.mpf(length) / n) * mp.sin(mp.pi / (2 * (2 * n + 1))) ** 2)
