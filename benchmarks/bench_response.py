"""Free response: modal formula against matrix exponentials and time integration.

Work-precision for the free response of one linearized system at 1000 time
points, each method timed in this process (median of repeats):

- ``modal``: ``pinlin.free_response`` (theory: responses), modal analysis included;
- ``modal, modes reused``: the same with a precomputed ``pinlin.modal_analysis``
  (the cost of evaluating the formula alone);
- ``expm per point``: ``scipy.linalg.expm(A t_k) z0`` at every time point;
- ``exact discretization``: ``pinlin.forced_response(sys, None, t, ...)`` (one
  ``expm`` of the step, then repeated products);
- ``solve_ivp`` (DOP853 and RK45) on z' = A z at rtol 1e-3 ... 1e-12, with
  atol = 1e-3 rtol ||z0||.

The error is max_t ||x(t) - x_ref(t)|| / max_t ||x_ref(t)||, with x_ref from
mpmath at 50 significant digits: the exponential of A h (mpmath's ``expm``,
Taylor/Pade, not an eigen-decomposition) applied step by step on the uniform
grid, with A built in mpmath from the double-precision M, C, K.  No method is
measured against itself.

System: a 6-link pendulum chain (1 m, 1 kg) under gravity with joint springs,
light joint damping and a follower force at the tip (M, D, S and a circulatory
N: a non-symmetric, non-proportional case), over 10 s.

Run as ``python -m benchmarks.bench_response``: BLAS is then limited to one
thread (``OPENBLAS_NUM_THREADS=1`` unless set): on a shared two-core machine
threaded BLAS calls on these small matrices were up to 100 times slower, at
random, which made every timing meaningless.  The setting is recorded in the
report.
"""

from __future__ import annotations

import os

if __name__ == "__main__":  # before numpy loads BLAS
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    os.environ.setdefault("OMP_NUM_THREADS", "1")

import time  # noqa: E402

import mpmath  # noqa: E402
import numpy as np  # noqa: E402
import scipy.linalg  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

import pinlin  # noqa: E402

from .common import Report, Table, median_time, result_path, save_figure, write_report  # noqa: E402

POINTS = 1000
DURATION = 10.0
DIGITS = 50
RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
QUICK_RTOLS = (1e-3, 1e-6, 1e-10, 1e-12)
#: Target: modal at least this many times faster than solve_ivp at rtol 1e-10.
TARGET_SPEEDUP = 100.0


def chain_system(n: int = 6) -> pinlin.LinearizedSystem:
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    elements = [pinlin.JointSpring(f"joint{i}", 2.0) for i in range(1, n + 1)]
    elements += [pinlin.JointDamper(f"joint{i}", 0.002) for i in range(1, n + 1)]
    elements.append(pinlin.FollowerWrench("tip", force=(0, 0, 1.0)))
    scene = pinlin.Scene(robot, elements)
    return pinlin.linearize(scene, scene.neutral())


def mp_reference(sys: pinlin.LinearizedSystem, z0: np.ndarray, t: np.ndarray, digits: int = DIGITS) -> np.ndarray:
    """x(t) on a uniform grid from mpmath: z_{k+1} = expm(A h) z_k at ``digits`` digits."""
    n = sys.n
    with mpmath.workdps(digits):
        M = mpmath.matrix(sys.M.tolist())
        C = mpmath.matrix(sys.C.tolist())
        K = mpmath.matrix(sys.K.tolist())
        Minv = M**-1
        A = mpmath.zeros(2 * n, 2 * n)
        for i in range(n):
            A[i, n + i] = 1
        MK, MC = -(Minv * K), -(Minv * C)
        for i in range(n):
            for j in range(n):
                A[n + i, j] = MK[i, j]
                A[n + i, n + j] = MC[i, j]
        h = mpmath.mpf(DURATION) / (len(t) - 1)
        E = mpmath.expm(A * h)
        z = mpmath.matrix(z0.tolist())
        out = np.empty((len(t), n))
        for k in range(len(t)):
            out[k] = [float(z[i]) for i in range(n)]
            z = E * z
    return out


def _error(x: np.ndarray, ref: np.ndarray) -> float:
    return float(np.max(np.linalg.norm(x - ref, axis=1)) / np.max(np.linalg.norm(ref, axis=1)))


def run(quick: bool = False) -> Report:
    sys = chain_system()
    n = sys.n
    rng = np.random.default_rng(2024)
    x0 = 0.05 * rng.standard_normal(n)
    v0 = 0.05 * rng.standard_normal(n)
    z0 = np.concatenate([x0, v0])
    t = np.linspace(0.0, DURATION, POINTS)
    repeats = 3 if quick else 7

    t_ref = time.perf_counter()
    ref = mp_reference(sys, z0, t)
    ref_time = time.perf_counter() - t_ref

    modes = pinlin.modal_analysis(sys)
    A, _, _ = sys.first_order()
    rows = []

    def add(method, setting, fn):
        x = fn()
        seconds = median_time(fn, repeats=repeats, min_time=0.005 if quick else 0.02)
        rows.append([method, setting, _error(x, ref), seconds])
        return rows[-1]

    modal = add("modal (free_response)", "modal analysis included", lambda: pinlin.free_response(sys, x0, v0, t))
    add("modal (free_response)", "modes reused", lambda: pinlin.free_response(sys, x0, v0, t, modes=modes))
    add("expm per point", "scipy.linalg.expm(A t_k) z0", lambda: np.array([scipy.linalg.expm(A * tk) @ z0 for tk in t])[:, :n])
    add("exact discretization", "forced_response(sys, None, ...)", lambda: pinlin.forced_response(sys, None, t, x0, v0).x)

    scale = float(np.linalg.norm(z0))
    ivp = {}
    for method in ("DOP853", "RK45"):
        for rtol in QUICK_RTOLS if quick else RTOLS:
            if method == "RK45" and rtol < 1e-10:
                continue  # RK45 needs millions of steps there; it only gets slower

            def integrate(method=method, rtol=rtol):
                sol = solve_ivp(lambda _t, z: A @ z, (0.0, DURATION), z0, method=method, t_eval=t, rtol=rtol, atol=1e-3 * rtol * scale)
                return sol.y[:n].T

            row = add(f"solve_ivp {method}", f"rtol {rtol:.0e}", integrate)
            ivp[(method, rtol)] = row

    best_1e10 = min((ivp[(m, 1e-10)] for m in ("DOP853", "RK45") if (m, 1e-10) in ivp), key=lambda r: r[3])
    best_method = best_1e10[0].split()[-1]

    def ivp_1e10():
        return solve_ivp(lambda _t, z: A @ z, (0.0, DURATION), z0, method=best_method, t_eval=t, rtol=1e-10, atol=1e-13 * scale)

    # The load of a shared machine drifts: the speedups are medians of ratios of timings taken back to back.
    def paired(fn):
        ratios = []
        for _ in range(3 if quick else 5):
            ratios.append(median_time(ivp_1e10, repeats=3, min_time=0.0) / median_time(fn, repeats=3, min_time=0.01))
        return float(np.median(ratios))

    speedup = paired(lambda: pinlin.free_response(sys, x0, v0, t))
    speedup_reused = paired(lambda: pinlin.free_response(sys, x0, v0, t, modes=modes))
    most_accurate = min(r[2] for r in rows)
    table = Table(
        title=f"Free response at {POINTS} points over {DURATION:g} s, n = {n} (error vs mpmath {DIGITS} digits)",
        columns=["method", "setting", "relative error", "time [s]", "time / modal"],
        rows=[r + [r[3] / modal[3]] for r in rows],
        note=(
            "Error: max_t ||x - x_ref|| / max_t ||x_ref||. Times: median of repeats in one process. "
            f"Eigenvalues: |lam| from {np.abs(modes.eigenvalues).min():.3g} to {np.abs(modes.eigenvalues).max():.3g} "
            f"rad/s; max backward error {modes.max_backward_error:.1e}."
        ),
    )
    summary = {
        "system": f"6-link pendulum chain, springs, dampers, follower tip force (nonzero: {'+'.join(sys.nonzero)})",
        "reference": f"mpmath expm(A h) at {DIGITS} digits, stepped ({ref_time:.1f} s)",
        "modal error": f"{modal[2]:.2e}",
        "modal time": f"{modal[3] * 1e3:.3f} ms (modal analysis included)",
        "solve_ivp at rtol 1e-10": f"{best_1e10[0]}: error {best_1e10[2]:.2e}, {best_1e10[3] * 1e3:.1f} ms",
        "speedup of modal over solve_ivp at rtol 1e-10": (
            f"{speedup:.0f}x (target >= {TARGET_SPEEDUP:.0f}x; median of back-to-back timing ratios)"
        ),
        "speedup with the modal analysis reused": f"{speedup_reused:.0f}x",
        "modal is the most accurate": bool(modal[2] <= most_accurate * (1 + 1e-12) or modal[2] < 1e-14),
        "target met (modal analysis included)": bool(speedup >= TARGET_SPEEDUP and modal[2] <= 10 * most_accurate),
        "target met (modal analysis reused)": bool(speedup_reused >= TARGET_SPEEDUP and modal[2] <= 10 * most_accurate),
        "BLAS threads": os.environ.get("OPENBLAS_NUM_THREADS", "library default"),
        "quick": quick,
    }
    report = Report(name="response", tables=[table], summary=summary)
    report.target(14, f"free response incl. the modal analysis >= {TARGET_SPEEDUP:.0f}x solve_ivp, and more accurate",
                  f"{speedup:.0f}x (error {modal[2]:.1e} vs {best_1e10[2]:.1e})",
                  bool(speedup >= TARGET_SPEEDUP and modal[2] <= 10 * most_accurate),
                  f"solve_ivp {best_method} at rtol 1e-10")
    figure = _plot(rows, quick)
    if figure:
        report.figures.append(figure)
    return report


def _plot(rows, quick: bool) -> str | None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    groups: dict[str, list] = {}
    for method, setting, err, seconds in rows:
        label = f"modal, {setting}" if method.startswith("modal") else method
        groups.setdefault(label, []).append((seconds, max(err, 1e-17)))
    markers = iter("o^sDvP<>")
    for method, pts in groups.items():
        pts = np.array(pts)
        style = "-" if len(pts) > 1 and method.startswith("solve_ivp") else ""
        ax.loglog(pts[:, 0], pts[:, 1], style + next(markers), label=method)
    ax.set_xlabel("run time [s]")
    ax.set_ylabel("relative error (vs mpmath, 50 digits)")
    ax.set_title(f"Free response, {POINTS} points: work-precision")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    path = save_figure(fig, result_path("response", quick), dpi=120)
    return path


if __name__ == "__main__":
    report = run()
    print(report.markdown())
    print("written to", write_report(report))
