"""Linearization: analytic (pinlin.linearize) against Pinocchio's floor and finite differences.

For each scene, in one process:

- ``linearize``: the median time of ``pinlin.linearize(scene, q)`` (M, D, G, S, N
  with every check pinlin makes);
- floor: Pinocchio's ``crba`` + ``computeRNEADerivatives`` at the same point,
  the least any analytic linearization must spend;
- central differences: K and C from 2 nv residual evaluations each (through
  ``pin.integrate``) plus ``crba`` for M.

Errors are against the hand-derived closed form where one exists (the paper's
double pendulum, the turntable); elsewhere the analytic-vs-difference gap is
shown, which bounds the differences' error (the analytic result agrees with the
closed forms to rounding).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

import pinlin
from pinlin.assembly import assemble

from .common import Report, Table, median_time, write_report


def fd_linearization(scene: pinlin.Scene, q: np.ndarray, h: float = 1e-6):
    """M by crba, K and C by central differences of the residual r(q, v) on the free coordinates."""
    model = scene.model
    f = scene.free_dofs
    v0 = np.asarray(scene.v0)
    nv = model.nv
    K = np.zeros((nv, nv))
    C = np.zeros((nv, nv))
    for k in f:
        e = np.zeros(nv)
        e[k] = h
        rp = assemble(scene, pin.integrate(model, q, e), v0, stiffness=False).residual
        rm = assemble(scene, pin.integrate(model, q, -e), v0, stiffness=False).residual
        K[:, k] = (rp - rm) / (2 * h)
        rp = assemble(scene, q, v0 + e, stiffness=False).residual
        rm = assemble(scene, q, v0 - e, stiffness=False).residual
        C[:, k] = (rp - rm) / (2 * h)
    M = pin.crba(model, scene.data, q)
    ix = np.ix_(f, f)
    return M[ix], C[ix], K[ix]


def _floor(scene: pinlin.Scene, q: np.ndarray):
    model, data = scene.model, scene.model.createData()
    v0 = np.asarray(scene.v0)
    zero = np.zeros(model.nv)
    fext = pin.StdVec_Force()
    for _ in range(model.njoints):
        fext.append(pin.Force.Zero())

    def run():
        pin.crba(model, data, q)
        pin.computeRNEADerivatives(model, data, q, v0, zero, fext)

    return run


def _double_pendulum():
    m1, l1, m2, l2, k1, k2, P, g = 1.3, 0.7, 0.9, 0.5, 3.0, 2.0, 4.0, 9.81
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf(m1, l1, m2, l2))
    scene = pinlin.Scene(
        robot,
        [pinlin.JointSpring("joint1", k1), pinlin.JointSpring("joint2", k2), pinlin.FollowerWrench("tip", force=(0, 0, P))],
        gravity=(0, 0, -g),
    )
    T = np.array([[1.0, 0.0], [1.0, 1.0]])
    M = np.array([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]])
    S = np.array([[k1 + k2 + (m1 / 2 + m2) * g * l1 - P * l1, -k2 + P * l1 / 2], [-k2 + P * l1 / 2, k2 + m2 * g * l2 / 2]])
    N = P * l1 / 2 * np.array([[0.0, 1.0], [-1.0, 0.0]])
    exact = (T.T @ M @ T, np.zeros((2, 2)), T.T @ (S + N) @ T)
    return "double pendulum + follower (SPEC 7.1)", scene, np.zeros(2), exact


def _turntable():
    a, m, k, l0, W = 0.5, 1.0, 10.0, 0.3, 2.0
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(a, m))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("slider", k, rest=l0)], prescribed={"table": W})
    r0 = (k * l0 + m * W**2 * a) / (k - m * W**2)
    q = scene.neutral()
    q[3] = r0
    exact = (
        np.diag([m * r0**2, m]),
        2 * m * W * r0 * np.array([[0.0, 1.0], [-1.0, 0.0]]),
        np.diag([m * W**2 * a * r0, k - m * W**2]),
    )
    return "turntable (SPEC 7.2)", scene, q, exact


def _panda():
    robot = pinlin.load_example("panda")
    elements = []
    for name in robot.joint_names:
        elements += [pinlin.JointSpring(name, 200.0), pinlin.JointDamper(name, 0.5)]
    elements.append(pinlin.FollowerWrench("panda_hand", force=(0.0, 0.0, 5.0)))
    scene = pinlin.Scene(robot, elements)
    q = pinlin.find_equilibrium(scene, robot.reference_configurations["default"]).q
    return "panda: springs, dampers, follower", scene, q, None


def _chain(n: int):
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n))
    elements = [pinlin.JointSpring(f"joint{i + 1}", 10.0) for i in range(n)]
    elements += [pinlin.JointDamper(f"joint{i + 1}", 0.1) for i in range(n)]
    elements.append(pinlin.FollowerWrench("tip", force=(0.0, 0.0, 1.0)))
    scene = pinlin.Scene(robot, elements)
    return f"{n}-link chain: springs, dampers, follower", scene, np.zeros(n), None


def _rel(a, b) -> float:
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def run(quick: bool = False) -> Report:
    cases = [_double_pendulum(), _turntable(), _panda(), _chain(30)]
    if not quick:
        cases.append(_chain(100))
    rows = []
    summary = {}
    for label, scene, q, exact in cases:
        sys = pinlin.linearize(scene, q)
        t_lin = median_time(lambda scene=scene, q=q: pinlin.linearize(scene, q))
        t_floor = median_time(_floor(scene, q))
        repeats = 3 if scene.n > 50 else 7
        t_fd = median_time(lambda scene=scene, q=q: fd_linearization(scene, q), repeats=repeats)
        M_fd, C_fd, K_fd = fd_linearization(scene, q)
        if exact is not None:
            M_ex, C_ex, K_ex = exact
            err_lin = max(_rel(sys.M, M_ex), _rel(sys.K, K_ex), _rel(sys.C, C_ex) if np.any(C_ex) else 0.0)
            err_fd = max(_rel(M_fd, M_ex), _rel(K_fd, K_ex), _rel(C_fd, C_ex) if np.any(C_ex) else 0.0)
            reference = "closed form"
        else:
            err_lin = float("nan")
            err_fd = max(_rel(K_fd, sys.K), _rel(C_fd, sys.C))
            reference = "analytic"
        rows.append(
            [label, scene.n, t_lin * 1e6, t_floor * 1e6, t_lin / t_floor, t_fd * 1e6, t_fd / t_lin, err_lin, err_fd, reference]
        )
        summary[label] = f"{t_lin / t_floor:.1f}x floor, {t_fd / t_lin:.1f}x faster than central differences"
    table = Table(
        "linearize against Pinocchio's floor and central differences (h = 1e-6)",
        [
            "scene",
            "n",
            "linearize [us]",
            "floor crba+RNEA derivs [us]",
            "linearize / floor",
            "central FD [us]",
            "FD / linearize",
            "linearize rel. error",
            "FD rel. error",
            "error reference",
        ],
        rows,
        note=(
            "Medians of repeats in one process.  Errors: max relative Frobenius error of M, C, K against the "
            "reference named in the last column ('analytic' = gap between differences and the analytic result)."
        ),
    )
    return Report("linearize", [table], summary)


if __name__ == "__main__":
    report = run()
    print(report.markdown())
    print("written to", write_report(report))
