"""Systems shared by the interop tests, each with what is known about it in closed form.

- the paper's double pendulum (theory: double pendulum) with its follower load P and a joint damper:
  circulatory and damped; tip at (-(l1 sin phi1 + l2 sin phi2), 0, -(l1 cos phi1 + l2 cos phi2)),
  phi1 = theta1, phi2 = theta1 + theta2 (joints about +y, bars along -z);
- the rotating ring (theory: rotating ring) with damping: gyroscopic, with a prescribed ring speed;
- the turntable (theory: turntable): gyroscopic, undamped;
- a 4-link chain with Rayleigh damping;
- a seeded random system from matrices (M spd, C and K general).
"""

from __future__ import annotations

import numpy as np

import pinlin

#: Double pendulum parameters of theory: double pendulum: m1, l1, m2, l2 [kg, m], k1, k2 [N m/rad], P [N], g [m/s^2].
M1, L1, M2, L2, K1, K2, P, G = 1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 4.0, 9.81
#: Joint damper on joint1 [N m s/rad]: makes D nonzero.
C1 = 0.1


def double_pendulum_scene(P=P, extra=()):
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf(M1, L1, M2, L2))
    elements = [
        pinlin.JointSpring("joint1", K1),
        pinlin.JointSpring("joint2", K2),
        pinlin.JointDamper("joint1", C1),
        *extra,
    ]
    if P:
        elements.append(pinlin.FollowerWrench("tip", force=(0, 0, P)))
    return pinlin.Scene(robot, elements, gravity=(0, 0, -G))


def double_pendulum():
    scene = double_pendulum_scene()
    return scene, pinlin.linearize(scene, np.zeros(2))


def tip_position(theta) -> np.ndarray:
    """World position of the double pendulum's tip at relative angles theta [m] (closed form)."""
    phi1, phi2 = theta[0], theta[0] + theta[1]
    return np.array([-(L1 * np.sin(phi1) + L2 * np.sin(phi2)), 0.0, -(L1 * np.cos(phi1) + L2 * np.cos(phi2))])


def rotating_ring(mass=1.0, k=4.0, c=0.2, omega=1.5):
    robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf(mass))
    elements = [
        pinlin.JointSpring("x", k),
        pinlin.JointSpring("y", k),
        pinlin.JointDamper("x", c),
        pinlin.JointDamper("y", c),
    ]
    scene = pinlin.Scene(robot, elements, gravity=(0, 0, 0), prescribed={"ring": omega})
    return scene, pinlin.linearize(scene, robot.neutral())


def turntable(a=0.5, mass=1.0, k=10.0, l0=0.3, omega=1.2):
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(a, mass))
    scene = pinlin.Scene(
        robot, [pinlin.JointSpring("slider", k, rest=l0)], gravity=(0, 0, 0), prescribed={"table": omega}
    )
    r0 = (k * l0 + mass * omega**2 * a) / (k - mass * omega**2)
    q = robot.neutral()
    q[robot.joint("slider").idx_q] = r0
    return scene, pinlin.linearize(scene, q)


def damped_chain(n=4):
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=2.0))
    elements = [pinlin.JointSpring(f"joint{i}", 5.0) for i in range(1, n + 1)]
    elements.append(pinlin.RayleighDamping(alpha=0.05, beta=0.01))
    scene = pinlin.Scene(robot, elements)
    return scene, pinlin.linearize(scene, robot.neutral())


def random_system(n=5, seed=7):
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    M = A @ A.T + n * np.eye(n)
    C = 0.3 * rng.standard_normal((n, n))
    K = rng.standard_normal((n, n)) + 2 * n * np.eye(n)
    return None, pinlin.LinearizedSystem.from_matrices(M, C, K)


CASES = {
    "double_pendulum": double_pendulum,
    "rotating_ring": rotating_ring,
    "turntable": turntable,
    "damped_chain": damped_chain,
    "random": random_system,
}
