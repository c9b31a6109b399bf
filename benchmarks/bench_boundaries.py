"""Stability boundaries: critical_parameter against bisection on the verdict.

For each boundary, in one process:

- fast: ``pinlin.critical_parameter(func, bracket)`` at its default tolerance (as accurate as rounding
  allows), with the verdicts beside the value checked (``verify_result=True``, two more modal analyses);
- bisection: ``pinlin.critical_parameter(func, bracket, method="bisection", tol=1e-12 |p*|)``, halving the
  bracket on ``modes.stability.kind`` alone (the way the notebooks found boundaries before).

Counted: modal analyses ("evaluations", a search's cost) and calls of ``func``; timed: the median wall
time of whole searches.  Errors are measured against closed forms (Ziegler's column 7/2 - sqrt(2) and its
Routh-Hurwitz damped loads; the paper's double pendulum, theory: double pendulum; the compressed chain's buckling load
(4k/l) sin^2(pi / (2(2n+1)))); the 50-link chain under a follower load has no closed form, and there the two
methods are compared with each other (each value inside the other's error bound).  The figure: error against
modal analyses as the tolerance is tightened, for the double pendulum's flutter load.

Run: ``python -m benchmarks.bench_boundaries [--quick]`` (the suite's ``python -m benchmarks`` lists it once
the lead engineer adds it to ``SUITE``).
"""

from __future__ import annotations

import statistics
import sys
import time

import numpy as np
from numpy.polynomial import Polynomial

import pinlin

from .common import Report, Table, result_path, work_precision_plot, write_report

#: Tolerance of the bisection baseline, relative to the boundary: the "1e-12" of the acceptance.
BISECTION_RTOL = 1e-12
#: Number of links of the chains (full run, quick run).
CHAIN_LINKS = (50, 20)

_T = np.array([[1.0, 0.0], [1.0, 1.0]])


def _bracket(A, B):
    return A[0][0] * B[1][1] + A[1][1] * B[0][0] - A[0][1] * B[1][0] - A[1][0] * B[0][1]


def _det(A):
    return A[0][0] * A[1][1] - A[0][1] * A[1][0]


def _loads(M, K0, K1, c):
    """(undamped flutter load, Routh-Hurwitz damped flutter load for D = c I) of a 2-DOF family K0 + P K1."""
    K = [[Polynomial([a, b]) for a, b in zip(r0, r1)] for r0, r1 in zip(K0, K1)]
    D = c * np.eye(2)
    a0, a1, a2, a3, a4 = _det(M), _bracket(M, D), _bracket(M, K) + _det(D), _bracket(D, K), _det(K)
    flutter = np.sort((_bracket(M, K) ** 2 - 4 * a0 * _det(K)).roots().real)[0]
    hurwitz = (a1 * a2 * a3 - a0 * a3**2 - a1**2 * a4).roots()
    damped = np.min(hurwitz[np.isreal(hurwitz) & (hurwitz.real > 0)].real)
    return float(flutter), float(damped)


def _two_link(urdf: str, k: tuple[float, float], g: float, c: float):
    robot = pinlin.load_urdf_string(urdf)

    def func(P):
        elements = [pinlin.JointSpring("joint1", k[0]), pinlin.JointSpring("joint2", k[1]),
                    pinlin.FollowerWrench("tip", force=(0.0, 0.0, P))]
        if c:
            elements += [pinlin.JointDamper("joint1", c), pinlin.JointDamper("joint2", c)]
        return pinlin.linearize(pinlin.Scene(robot, elements, gravity=(0.0, 0.0, -g)), np.zeros(2))

    return func


def _ziegler_urdf() -> str:
    link = ('  <link name="link{i}"><inertial><origin xyz="0 0 -1"/><mass value="{m}"/>'
            '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>\n'
            '  <joint name="joint{i}" type="revolute"><parent link="{parent}"/><child link="link{i}"/>'
            '<origin xyz="0 0 {z}"/><axis xyz="0 1 0"/>'
            '<limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/></joint>\n')
    return ('<?xml version="1.0"?>\n<robot name="ziegler">\n  <link name="base"/>\n'
            + link.format(i=1, m=2.0, parent="base", z=0) + link.format(i=2, m=1.0, parent="link1", z=-1)
            + '  <link name="tip"/><joint name="tip_joint" type="fixed"><parent link="link2"/><child link="tip"/>'
            '<origin xyz="0 0 -1"/></joint>\n</robot>\n')


def _chain(n: int, follower: bool):
    """n links, total length 1 m and mass 1 kg, springs EI / l (EI = 1 N m^2), no gravity; a follower
    load (Beck's column, discretized: flutter) or a dead compressive load (buckling) at the tip."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    k = float(n)
    wrench = pinlin.FollowerWrench if follower else pinlin.DeadWrench

    def func(P):
        elements = [pinlin.JointSpring(f"joint{i}", k) for i in range(1, n + 1)]
        elements.append(wrench("tip", force=(0.0, 0.0, P)))
        return pinlin.linearize(pinlin.Scene(robot, elements, gravity=(0.0, 0.0, 0.0)), np.zeros(n))

    return func, 4 * k * n * np.sin(np.pi / (2 * (2 * n + 1))) ** 2


def cases(quick: bool):
    """(name, func, bracket, reference or None) for every boundary."""
    dp = dict(m1=1.3, l1=0.7, m2=0.9, l2=0.5)
    M_dp = _T.T @ np.array([[(dp["m1"] / 3 + dp["m2"]) * dp["l1"] ** 2, dp["m2"] * dp["l1"] * dp["l2"] / 2],
                            [dp["m2"] * dp["l1"] * dp["l2"] / 2, dp["m2"] * dp["l2"] ** 2 / 3]]) @ _T
    K0_dp = _T.T @ np.array([[3 + 2 + (dp["m1"] / 2 + dp["m2"]) * 9.81 * dp["l1"], -2.0],
                             [-2.0, 2 + dp["m2"] * 9.81 * dp["l2"] / 2]]) @ _T
    K1_dp = _T.T @ np.array([[-dp["l1"], dp["l1"]], [0.0, 0.0]]) @ _T
    M_z = _T.T @ np.array([[3.0, 1.0], [1.0, 1.0]]) @ _T
    K0_z, K1_z = _T.T @ np.array([[2.0, -1.0], [-1.0, 1.0]]) @ _T, _T.T @ np.array([[-1.0, 1.0], [0.0, 0.0]]) @ _T
    pf_dp, pc_dp = _loads(M_dp, K0_dp, K1_dp, 0.01)
    pf_z, pc_z = _loads(M_z, K0_z, K1_z, 0.1)
    dp_urdf = pinlin.double_pendulum_urdf(dp["m1"], dp["l1"], dp["m2"], dp["l2"])
    n = CHAIN_LINKS[1] if quick else CHAIN_LINKS[0]
    beck, _ = _chain(n, follower=True)
    buckling, p_buckling = _chain(n, follower=False)
    return [
        ("Ziegler's column, undamped (coalescence)", _two_link(_ziegler_urdf(), (1.0, 1.0), 0.0, 0.0), (0.5, 3.0),
         pf_z),
        ("Ziegler's column, c = 0.1 (crossing)", _two_link(_ziegler_urdf(), (1.0, 1.0), 0.0, 0.1), (0.5, 3.0), pc_z),
        ("double pendulum theory: double pendulum, P_f (coalescence)", _two_link(dp_urdf, (3.0, 2.0), 9.81, 0.0), (10.0, 20.0),
         pf_dp),
        ("double pendulum, c = 0.01 (crossing)", _two_link(dp_urdf, (3.0, 2.0), 9.81, 0.01), (1.0, 40.0), pc_dp),
        (f"{n}-link chain, dead load: buckling (mu through 0)", buckling, (0.5 * p_buckling, 2.0 * p_buckling),
         p_buckling),
        (f"{n}-link chain, follower load: flutter (coalescence)", beck, (10.0, 30.0), None),
    ]


def _timed(fn, repeats: int):
    samples, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        samples.append(time.perf_counter() - t0)
    return out, statistics.median(samples)


def _precision_series(func, bracket, reference):
    """(evaluations, relative error) of both methods as the tolerance tightens."""
    fast, slow = [], []
    for rtol in (1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, None):
        tol = None if rtol is None else rtol * reference
        a = pinlin.critical_parameter(func, bracket, tol=tol)
        fast.append((a.evaluations, abs(a.value - reference) / reference))
        if rtol is not None:
            b = pinlin.critical_parameter(func, bracket, tol=tol, method="bisection")
            slow.append((b.evaluations, abs(b.value - reference) / reference))
    return {"critical_parameter": fast, "bisection on the verdict": slow}


def run(quick: bool = False) -> Report:
    repeats = 1 if quick else 3
    table = Table(
        "Evaluations, time and error per boundary",
        ["boundary", "p*", "fast: modal analyses", "fast: func calls", "fast [ms]", "fast error", "fast bound",
         "bisection: modal analyses", "bisection [ms]", "bisection error", "analyses ratio", "time ratio",
         "bounds hold"],
        note=("Errors are relative to the reference (closed form) or, without one, the relative difference "
              "between the two methods; bounds are relative error bounds. 'bounds hold': every error bound "
              "contains the reference (or the other method's value)."),
    )
    worst_fast, ratios = 0, []
    for name, func, bracket, reference in cases(quick):
        fast, t_fast = _timed(lambda func=func, bracket=bracket: pinlin.critical_parameter(func, bracket), repeats)
        scale = reference if reference is not None else fast.value
        slow, t_slow = _timed(lambda func=func, bracket=bracket, scale=scale: pinlin.critical_parameter(
            func, bracket, method="bisection", tol=BISECTION_RTOL * abs(scale)), repeats)
        ref = reference if reference is not None else slow.value
        e_fast, e_slow = abs(fast.value - ref) / abs(ref), abs(slow.value - ref) / abs(ref)
        if reference is None:  # no closed form: the two methods against each other
            holds = abs(fast.value - slow.value) <= fast.error_bound + slow.error_bound
            e_slow = float("nan")
        else:
            holds = abs(fast.value - ref) <= fast.error_bound and abs(slow.value - ref) <= slow.error_bound
        table.rows.append([name, f"{fast.value:.15g}", fast.evaluations, fast.function_calls, t_fast * 1e3, e_fast,
                           fast.error_bound / abs(ref), slow.evaluations, t_slow * 1e3, e_slow,
                           slow.evaluations / fast.evaluations, t_slow / t_fast, "yes" if holds else "NO"])
        worst_fast = max(worst_fast, fast.evaluations)
        ratios.append(slow.evaluations / fast.evaluations)
    dp_name, dp_func, dp_bracket, dp_ref = cases(quick)[2]
    figure = work_precision_plot(
        result_path("boundaries", quick), _precision_series(dp_func, dp_bracket, dp_ref),
        f"{dp_name}: error against cost", xlabel="modal analyses", ylabel="relative error of p*",
        connect=("critical_parameter", "bisection on the verdict"))
    summary = {
        "most modal analyses per boundary (critical_parameter, 1e-12 or better)": worst_fast,
        "bisection / critical_parameter modal analyses": f"{min(ratios):.1f}x to {max(ratios):.1f}x",
        "target": "<= 10 modal analyses for 1e-12, against about 40 for bisection",
    }
    return Report("boundaries", [table], summary, [figure] if figure else [], text=__doc__.split("\n\n")[0])


if __name__ == "__main__":
    quick = "--quick" in sys.argv[1:]
    report = run(quick=quick)
    if quick:
        report.name += "_quick"
    print(write_report(report))
