"""Scenes, reference solutions and result checks shared by the tests of frf and response."""

from __future__ import annotations

import json
import time

import numpy as np
import scipy.linalg

import pinlin

#: Parameters of the turntable case (theory: turntable).
TURNTABLE = {"a": 0.5, "m": 1.0, "k": 10.0, "l0": 0.3, "Omega": 2.0}


def double_pendulum_tilted(P: float = 4.0) -> pinlin.Scene:
    """The double pendulum with follower load (theory: double pendulum) with springs pre-stressed (rest angles 0.4, -0.3),
    so that its equilibrium is not symmetric and the nonlinearity has quadratic terms."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    return pinlin.Scene(
        robot,
        [
            pinlin.JointSpring("joint1", 3.0, rest=0.4),
            pinlin.JointSpring("joint2", 2.0, rest=-0.3),
            pinlin.FollowerWrench("tip", force=(0, 0, P)),
        ],
    )


def double_pendulum(P: float = 4.0, damping: float = 0.0) -> pinlin.Scene:
    """The double pendulum of theory: double pendulum (equilibrium at the neutral configuration)."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    elements = [
        pinlin.JointSpring("joint1", 3.0),
        pinlin.JointSpring("joint2", 2.0),
        pinlin.FollowerWrench("tip", force=(0, 0, P)),
    ]
    if damping:
        elements += [pinlin.JointDamper("joint1", damping), pinlin.JointDamper("joint2", damping)]
    return pinlin.Scene(robot, elements)


def turntable() -> tuple[pinlin.Scene, np.ndarray]:
    """Particle on a turntable (theory: turntable) and its stable equilibrium r0 = (k l0 + m W^2 a) / (k - m W^2)."""
    p = TURNTABLE
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(a=p["a"], mass=p["m"]))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("slider", p["k"], rest=p["l0"])], prescribed={"table": p["Omega"]})
    q = scene.neutral()
    m, k, W, a, l0 = p["m"], p["k"], p["Omega"], p["a"], p["l0"]
    q[robot.joint("slider").idx_q] = (k * l0 + m * W**2 * a) / (k - m * W**2)
    return scene, q


def rotating_ring(Omega: float = 1.5, k: float = 5.0, c: float = 0.2) -> pinlin.Scene:
    """Particle in a rotating ring (theory: rotating ring); equilibrium at the neutral configuration."""
    robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf())
    return pinlin.Scene(
        robot,
        [pinlin.JointSpring("x", k), pinlin.JointSpring("y", k), pinlin.JointDamper("x", c), pinlin.JointDamper("y", c)],
        prescribed={"ring": Omega},
    )


def ur5_springs() -> tuple[pinlin.Scene, np.ndarray]:
    """The ur5 hanging under gravity, held by joint springs, at its equilibrium near the neutral pose."""
    robot = pinlin.load_example("ur5")
    stiffness = [800.0, 800.0, 400.0, 60.0, 60.0, 30.0]
    scene = pinlin.Scene(robot, [pinlin.JointSpring(name, k) for name, k in zip(robot.joint_names, stiffness)])
    eq = pinlin.find_equilibrium(scene, scene.neutral())
    return scene, eq.q


def state_matrix(sys: pinlin.LinearizedSystem) -> np.ndarray:
    """A of z' = A z, z = (x, x'), built here from M, C, K independently of pinlin.response."""
    n = sys.n
    Minv = np.linalg.inv(sys.M)
    return np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ sys.K, -Minv @ sys.C]])


def expm_free_response(sys, x0, v0, t) -> tuple[np.ndarray, np.ndarray]:
    """Reference free response z(t) = expm(A t) z0: (x, xdot), each (len(t), n).

    On a uniform grid the state is carried from t[0] by powers of expm(A h)
    (two matrix exponentials in all, rounding growing like the number of
    steps); otherwise one exponential per time point.
    """
    A = state_matrix(sys)
    z0 = np.concatenate([x0, v0])
    t = np.asarray(t, dtype=float)
    h = np.diff(t)
    if t.size > 2 and np.allclose(h, h[0], rtol=1e-12, atol=0):
        step = scipy.linalg.expm(A * ((t[-1] - t[0]) / (t.size - 1)))
        Z = np.empty((t.size, z0.size))
        Z[0] = scipy.linalg.expm(A * t[0]) @ z0
        for k in range(1, t.size):
            Z[k] = step @ Z[k - 1]
    else:
        Z = np.array([scipy.linalg.expm(A * ti) @ z0 for ti in t])
    return Z[:, : sys.n], Z[:, sys.n :]


def timed(func):
    """``func()`` and the wall time around it [s] (an upper bound for the result's ``elapsed``)."""
    t0 = time.perf_counter()
    out = func()
    return out, time.perf_counter() - t0


def json_round_trip(result) -> dict:
    """``result.to_dict()`` checked as strict JSON (led by type, method, error, elapsed) and read back."""
    data = result.to_dict()
    assert list(data)[:4] == ["type", "method", "error", "elapsed"]
    assert data["type"] == type(result).__name__
    back = json.loads(json.dumps(data, allow_nan=False))
    assert back == data
    return back
