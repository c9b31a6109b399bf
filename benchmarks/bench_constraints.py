"""Constrained systems: the price of constraints, the KKT equilibrium, the accuracy.

- ``linearize`` of a constrained scene against the unconstrained ``linearize`` of the
  same robot at the same configuration (held by balancing forces, since without its
  contacts a standing robot is no equilibrium), timed interleaved in one process
  (:func:`common.interleaved_medians`, thread CPU time: the machine is shared):
  solo12 on four point contacts with springs on its twelve leg joints (target:
  within 3x), and the bundled four-bar;
- ``find_equilibrium`` with constraints: assembly steps, Newton iterations on the
  manifold, time and residuals, for the four-bar from an open start and from its
  assembled pose, and for solo12 from its SRDF standing pose;
- accuracy: the four-bar's frequency against the energy method (closed form along
  the loop, tests/constrained_cases.py) over the crank angle, with and without the
  constraint-force stiffness K_lambda; solo12's contact forces against its weight.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

import pinlin

from .common import Report, Table, interleaved_medians, load_average

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from constrained_cases import BUNDLED  # noqa: E402  (the closed form lives with the tests)

G = 9.81
#: Crank spring of the four-bar [N m/rad] and leg springs of solo12 [N m/rad].
K_CRANK, K_LEG = 50.0, 20.0
FEET = ("FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT")


def _solo():
    robot = pinlin.load_example("solo12", free_flyer=True)
    q0 = robot.reference_configurations["standing"].copy()
    springs = [pinlin.JointSpring(j, K_LEG, rest=q0[robot.joint(j).idx_q]) for j in robot.joint_names[1:]]
    contacts = pinlin.ground_contacts(robot, q0, FEET, friction=0.8)
    return pinlin.Scene(robot, springs, constraints=contacts), pinlin.Scene(robot, springs), q0


def _four_bar(theta0: float = math.radians(75.0)):
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    spring = [pinlin.JointSpring("crank_joint", K_CRANK, rest=BUNDLED.spring_rest(theta0, K_CRANK, G))]
    loop = pinlin.PointConstraint("rocker_tip", (BUNDLED.ground, 0.0, 0.0))
    return pinlin.Scene(robot, spring, constraints=[loop]), pinlin.Scene(robot, spring), BUNDLED.joints(theta0)


def _timing(repeats: int) -> tuple[Table, dict]:
    table = Table(
        "linearize with constraints against the same robot without them (same q, interleaved medians)",
        ["case", "n", "constrained [us]", "unconstrained [us]", "ratio", "extra Pinocchio calls"],
        note="The unconstrained scene is held at q by balancing forces (it has no equilibrium there).",
    )
    summary = {}
    solo, solo_free, q0 = _solo()
    q_solo = pinlin.find_equilibrium(solo, q0).q
    bar, bar_free, q_bar = _four_bar()
    for name, scene, free, q in (("solo12, 4 point contacts", solo, solo_free, q_solo), ("four-bar", bar, bar_free, q_bar)):
        con, unc = interleaved_medians(
            [
                lambda scene=scene, q=q: pinlin.linearize(scene, q),
                lambda free=free, q=q: pinlin.linearize(free, q, balancing=True),
            ],
            repeats=repeats,
            clock=time.thread_time,
        )
        sys_c, sys_u = pinlin.linearize(scene, q), pinlin.linearize(free, q, balancing=True)
        extra = [c for c in sys_c.calls if c not in sys_u.calls]
        table.rows.append([name, sys_c.n, con * 1e6, unc * 1e6, con / unc, f"{len(extra)}: {', '.join(sorted(set(extra)))}"])
        summary[f"{name}: constrained / unconstrained"] = round(con / unc, 2)
    return table, summary


def _equilibria() -> Table:
    table = Table(
        "find_equilibrium with constraints: assembly, Newton on the manifold, residuals",
        ["case", "start", "gap at start [m]", "assembly steps", "Newton iterations", "time [ms]",
         "relative residual", "gap [m]"],
    )  # fmt: skip
    bar, _, q_bar = _four_bar()
    solo, _, q0 = _solo()
    cases = [
        ("four-bar", "open chain (0.3, 0.2, -0.4)", bar, np.array([0.3, 0.2, -0.4])),
        ("four-bar", "assembled, crank at 60 deg", bar, np.zeros(3)),
        ("four-bar", "at the equilibrium", bar, q_bar),
        ("solo12", "SRDF standing pose", solo, q0),
    ]
    for name, start, scene, q in cases:
        t0 = time.perf_counter()
        eq = pinlin.find_equilibrium(scene, q)
        dt = time.perf_counter() - t0
        table.rows.append([name, start, eq.assembly.initial_gap, eq.assembly.iterations, eq.iterations, dt * 1e3,
                           eq.error, eq.constraint_gap])  # fmt: skip
    return table


def _accuracy(quick: bool) -> tuple[Table, dict]:
    table = Table(
        "four-bar: omega against the energy method over the crank angle, with and without K_lambda",
        ["crank angle [deg]", "omega [rad/s]", "relative error", "error without K_lambda"],
    )
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    loop = pinlin.PointConstraint("rocker_tip", (BUNDLED.ground, 0.0, 0.0))
    worst = worst_wrong = 0.0
    for deg in range(0, 360, 60 if quick else 30):
        theta = math.radians(deg)
        rest = BUNDLED.spring_rest(theta, K_CRANK, G)
        scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", K_CRANK, rest=rest)], constraints=[loop])
        q = BUNDLED.joints(theta)
        sys = pinlin.linearize(scene, q, coordinates=["crank_joint"])
        lam = sys.constraint_forces[0].force
        K_lambda = pinlin.constraint_stiffness(scene, q, lam)
        wrong = (sys.K[0, 0] + (sys.basis.T @ K_lambda @ sys.basis)[0, 0]) / sys.M[0, 0]
        exact = BUNDLED.omega2(theta, K_CRANK, G)
        err, err_wrong = abs(sys.K[0, 0] / sys.M[0, 0] / exact - 1), abs(wrong / exact - 1)
        worst, worst_wrong = max(worst, err), max(worst_wrong, err_wrong)
        table.rows.append([deg, math.sqrt(exact), err, err_wrong])
    solo, _, q0 = _solo()
    eq = pinlin.find_equilibrium(solo, q0)
    weight = G * sum(body.mass for body in solo.model.inertias)
    carried = sum(f.force[2] for f in eq.constraint_forces)
    summary = {
        "four-bar omega^2 vs energy method (max relative error)": f"{worst:.1e}",
        "four-bar without K_lambda (max relative error)": f"{worst_wrong:.1e}",
        "solo12 vertical contact forces vs weight (relative)": f"{abs(carried / weight - 1):.1e}",
    }
    return table, summary


def run(quick: bool = False) -> Report:
    load = load_average()
    timing, summary = _timing(repeats=5 if quick else 25)
    summary["machine load (1-minute load average, before / after the timing)"] = f"{load} / {load_average()}"
    accuracy, acc_summary = _accuracy(quick)
    summary.update(acc_summary)
    report = Report(
        name="constraints",
        tables=[timing, _equilibria(), accuracy],
        summary=summary,
        text=__doc__.split("\n\n", 1)[1],
    )
    for key, ratio in summary.items():
        if key.startswith("solo12") and key.endswith("constrained / unconstrained"):
            report.target(11, "linearize of solo12 standing on four contacts at most 3x the unconstrained one",
                          f"{ratio:.2f}x", bool(ratio <= 3.0), "unconstrained linearize, same robot and q")
    return report
