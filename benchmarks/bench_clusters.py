"""Clustered spectra and busy machines: modal_analysis against eig(left=True).

Systems with repeated eigenvalues, the common case of real robots:

- talos_full_v2 from example-robot-data (n = 44), equal springs (100 N m/rad)
  on every joint: its fingers and grippers give 12 double clusters; with
  dampers (0.5 N m s/rad) and gravity held by actuator forces (general path)
  and undamped without gravity (symmetric path);
- a trunk carrying 8 identical two-link branches (n = 17, springs 3 N m/rad,
  gravity): clusters of 7 and 8; with dampers 0.05 (general path) and without
  (symmetric path);
- the small robots of ``bench_spectral`` (double pendulum, ur5, panda; springs,
  dampers, a follower force: general path).

Baselines in the same process, samples interleaved call by call, medians of
thread CPU time (``time.thread_time``; the machine is shared): a plain
``scipy.linalg.eig(A, B)`` of the companion pencil with right vectors, and
``eig(A, B, left=True)`` -- both sets of vectors, as modal_analysis computes on the
general path.  Each cluster's partial multiplicities are checked against the
block Toeplitz ranks alone (``analyse_cluster`` without the computed evidence).

Busy machine: ``_threads_worker`` runs in a subprocess without
OPENBLAS_NUM_THREADS (the user's default: one BLAS thread per core) while a
busy-loop process pinned to core 1 (``taskset -c 1``) keeps that core loaded;
modal_analysis with pinlin's one-thread limit for small kernels and without it,
against the single-thread time of this process (OPENBLAS_NUM_THREADS=1).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import scipy.linalg as sla

import pinlin
from pinlin.model.generators import branched_chain_urdf
from pinlin.model.loading import example_urdf_path
from pinlin.spectral.qep import companion_pencil

from .bench_spectral import _robot_system, analyse
from .common import THREAD_VARIABLES, Report, Table, busy_core, interleaved_medians, load_average, write_report

#: talos_full_v2 (legs, torso, arms, head and both grippers) beside talos_reduced in example-robot-data.
TALOS = example_urdf_path("talos_reduced").parent / "talos_full_v2.urdf"


def branched_chain(damping: float = 0.0) -> pinlin.LinearizedSystem:
    robot = pinlin.load_urdf_string(branched_chain_urdf())
    el = [pinlin.JointSpring(j, 3.0) for j in robot.joint_names]
    el += [pinlin.JointDamper(j, damping) for j in robot.joint_names] if damping else []
    return pinlin.linearize(pinlin.Scene(robot, el, gravity=(0, 0, -9.81)), robot.neutral())


def talos(damping: float = 0.0, gravity: bool = False) -> pinlin.LinearizedSystem:
    robot = pinlin.load_urdf(TALOS)
    el = [pinlin.JointSpring(j, 100.0) for j in robot.joint_names]
    el += [pinlin.JointDamper(j, damping) for j in robot.joint_names] if damping else []
    g = (0, 0, -9.81) if gravity else (0, 0, 0)
    return pinlin.linearize(pinlin.Scene(robot, el, gravity=g), robot.neutral(), balancing=gravity)


def _double_pendulum() -> pinlin.LinearizedSystem:
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    return pinlin.linearize(pinlin.Scene(robot, [
        pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", 2.0), pinlin.JointDamper("joint1", 0.1),
        pinlin.FollowerWrench("tip", force=(0, 0, 4.0))]), robot.neutral())


#: The benchmark's systems by name (module level: the worker process builds them too).
CASES = {
    "talos_full_v2": lambda: talos(0.5, gravity=True),
    "talos_full_v2 undamped": talos,
    "8-branch chain": lambda: branched_chain(0.05),
    "8-branch chain undamped": branched_chain,
    "double pendulum": _double_pendulum,
    "ur5": lambda: _robot_system("ur5"),
    "panda": lambda: _robot_system("panda"),
}
CLUSTERED = ("talos_full_v2", "talos_full_v2 undamped", "8-branch chain", "8-branch chain undamped")
SMALL = ("double pendulum", "ur5", "panda")


def _structure_unchanged(sys, modes) -> bool:
    """Every cluster's partial multiplicities equal those of the block Toeplitz ranks alone."""
    # internal modules, imported here: CASES import with any revision of pinlin (bench_compare)
    from pinlin.spectral.multiplicity import analyse_cluster
    from pinlin.spectral.problem import as_problem

    problem = as_problem(sys)
    tol = modes.tolerances["rank_tol"]
    return all(
        analyse_cluster(problem, modes.eigenvalues, c.indices, tol).partial == c.partial for c in modes.clusters
    )


def timing_table(quick: bool) -> tuple[Table, dict]:
    rows, out = [], {}
    for name in CLUSTERED + SMALL:
        sys = CASES[name]()
        A, B = companion_pencil(sys.M, sys.C, sys.K)
        t_eig, t_left, t_modal = interleaved_medians(
            [lambda A=A, B=B: sla.eig(A, B), lambda A=A, B=B: sla.eig(A, B, left=True), lambda s=sys: analyse(s)],
            repeats=31 if quick else 151, min_time=0.0, clock=time.thread_time,
        )
        m = pinlin.modal_analysis(sys)
        sizes = sorted((c.algebraic for c in m.clusters), reverse=True)
        how = sorted({c.method.split(":")[0].split(" (")[0] for c in m.clusters})
        same = _structure_unchanged(sys, m)
        rows.append([name, sys.n, m.method.name, str(sizes) if sizes else "-", "; ".join(how) or "-", same,
                     t_eig * 1e3, t_left * 1e3, t_modal * 1e3, t_modal / t_left, t_modal / t_eig])
        out[name] = {"n": sys.n, "eig": t_eig, "eig_left": t_left, "modal": t_modal, "unchanged": same}
    table = Table(
        "modal_analysis against scipy.linalg.eig of the companion pencil, right vectors and both [ms, thread CPU "
        "time, medians of interleaved single calls, OPENBLAS_NUM_THREADS=1]",
        ["case", "n", "path", "cluster sizes", "how the clusters were decided", "structure = Toeplitz ranks",
         "eig", "eig(left=True)", "modal_analysis", "/ eig(left=True)", "/ eig"],
        rows,
        note=(f"load average before the table {load_average()} on {os.cpu_count()} CPUs (shared machine). "
              "Each modal_analysis call forms C = D + G and K = S + N afresh (see bench_spectral.analyse)."),
    )
    return table, out


def busy_table(quick: bool, single: dict) -> tuple[Table, dict]:
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
    root = Path(__file__).resolve().parent.parent
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(root / "src"), str(root), env.get("PYTHONPATH", "")) if p)
    rows, out = [], {}
    with busy_core() as busy:
        load = load_average()
        for name in ("talos_full_v2", "8-branch chain", "panda"):
            run = subprocess.run(
                [sys.executable, "-m", "benchmarks._threads_worker", name, "7" if quick else "25"],
                env=env, cwd=root, capture_output=True, text=True, check=True,
            )
            r = json.loads(run.stdout.strip().splitlines()[-1])
            one = single[name]["modal"]
            rows.append([name, str(r["blas_threads"]), one * 1e3, r["limited_thread"] * 1e3,
                         r["limited_wall"] * 1e3, r["limited_thread"] / one, r["threaded_thread"] * 1e3,
                         r["threaded_wall"] * 1e3, r["threaded_wall_max"] * 1e3, r["threaded_thread"] / one])
            out[name] = r | {"single": one}
    table = Table(
        "Default BLAS threads with a busy-loop process on core 1: modal_analysis with pinlin's one-thread limit "
        "for small kernels and without it, against its single-thread time [ms]",
        ["case", "BLAS threads (default)", "single thread (thread CPU)", "limited: thread CPU", "limited: wall",
         "limited / single", "unlimited: thread CPU", "unlimited: wall", "unlimited: slowest wall",
         "unlimited / single"],
        rows,
        note=(f"busy loop: {'taskset -c 1' if busy is not None else 'none (no taskset)'}; load average before "
              f"{load} on {os.cpu_count()} CPUs, other engineers' jobs included. 'single thread' is the previous "
              "table's median (this process, OPENBLAS_NUM_THREADS=1); the others are medians of interleaved samples "
              "in a worker process without the thread variables."),
    )
    return table, out


def run(quick: bool = False) -> Report:
    t1, single = timing_table(quick)
    t2, busy = busy_table(quick, single)
    summary = {
        name: f"modal_analysis / eig(left=True) {s['modal'] / s['eig_left']:.2f} ({s['modal'] * 1e3:.2f} ms against "
              f"{s['eig_left'] * 1e3:.2f} ms), structure unchanged: {s['unchanged']}"
        for name, s in single.items()
    }
    summary |= {
        f"{name}, default threads, core 1 busy": (
            f"{b['limited_thread'] * 1e3:.2f} ms thread CPU ({b['limited_wall'] * 1e3:.2f} ms wall) with the limit, "
            f"{b['threaded_thread'] * 1e3:.2f} ms ({b['threaded_wall'] * 1e3:.2f} ms) without; single thread "
            f"{b['single'] * 1e3:.2f} ms")
        for name, b in busy.items()
    }
    report = Report("clusters", [t1, t2], summary)
    for name in ("talos_full_v2", "8-branch chain"):
        s = single[name]
        r = s["modal"] / s["eig_left"]
        report.target(27, f"modal_analysis at most 2x eig(left=True), Jordan structure unchanged: {name} (n = {s['n']})",
                      f"{r:.2f}x, structure unchanged: {s['unchanged']}", bool(r <= 2 and s["unchanged"]),
                      "scipy.linalg.eig(A, B, left=True), thread CPU")
        b = busy[name]
        rb = b["limited_thread"] / b["single"]
        report.target(27, f"default BLAS threads, one core busy: modal_analysis at most 3x its single-thread time: {name}",
                      f"{rb:.2f}x by thread CPU ({b['limited_wall'] / b['single']:.2f}x by wall; without the limit "
                      f"{b['threaded_thread'] / b['single']:.1f}x / {b['threaded_wall'] / b['single']:.1f}x)",
                      bool(rb <= 3), "modal_analysis with OPENBLAS_NUM_THREADS=1")
    for name in SMALL:
        s = single[name]
        r = s["modal"] / s["eig_left"]
        report.target(27, f"modal_analysis at most 1.5x eig(left=True), n <= 9: {name} (n = {s['n']})", f"{r:.2f}x",
                      bool(r <= 1.5), "scipy.linalg.eig(A, B, left=True), thread CPU")
    return report


if __name__ == "__main__":
    report = run()
    print(report.markdown())
    print("written to", write_report(report))
