"""Scaling of the whole pipeline with the size of a pendulum chain, and the memory guard.

For n = 10 ... 400 links (springs, dampers, gravity; theory: pendulum chains), each n in a
fresh subprocess, the stages of the data flow:

1. ``load``: ``load_urdf_string(pendulum_chain_urdf(n))`` and ``Scene(...)``
   (the memory guard checks the estimate; no Pinocchio ``Data`` yet);
2. ``createData``: the thread's workspace, ``workspace(scene)`` (memory guard +
   ``model.createData()``): Pinocchio allocates four nv^3 derivative tensors
   (32 nv^3 bytes kept, about twice that at the peak; theory: equations) that no
   algorithm pinlin calls uses, an upstream limit.  pinlin creates one Data per
   robot and thread and shares it among the robot's scenes (a sweep pays once);
3. ``equilibrium``: ``find_equilibrium`` from every joint 0.2/n rad off (a 0.2 rad curl);
4. ``linearize``;
5. ``spectrum``: ``modal_analysis`` (the general path: joint dampers are not
   proportional);
6. ``frequency response``: ``frequency_response`` at 1000 frequencies from the
   tip torque to every angle, modal form with the modes of stage 5, residual
   check on.

Measured per stage: wall time (median of repeats for small n); peak resident
set size (RSS) during the stage, sampled every millisecond from
``/proc/self/statm`` by a thread (so C++ allocations by Pinocchio and LAPACK
count; a spike shorter than a millisecond can be missed), minus the RSS before
the pipeline; and the tracemalloc peak (Python and numpy allocations only:
Pinocchio's C++ allocations are invisible to it).  The subprocess's VmHWM
(its true peak RSS, interpreter included) is reported as the high-water mark.
The cost exponents are the least-squares slopes of log(time) against log(n)
for n >= :data:`FIT_FROM` only: below it fixed costs dominate and flatten the
slope (a "linearize 0.99" fitted from n = 50 was 1.9 from 100 to 500).

Chains up to the largest n the memory guard admits on this machine:
a full run adds that n and one between (a few minutes that allocate most of
the memory the guard allows; CI runs no benchmark); ``PINLIN_BENCH_LARGE=0``
leaves them out.

The memory guard: ``load_urdf_string`` estimates Pinocchio's data before
allocating it and refuses with ``ModelTooLargeError`` beyond its limit (80 % of
the available memory by default); shown for a chain too large for this machine
and for an explicit limit.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time
import tracemalloc

import numpy as np

SIZES = (10, 20, 50, 100, 200, 300, 400)
QUICK_SIZES = (10, 20, 50, 100)
STAGES = ("load", "createData", "equilibrium", "linearize", "spectrum", "frequency response")
FREQUENCIES = 1000
#: Exponents are fitted from this n on: below it the stages' fixed costs dominate.
FIT_FROM = 100
#: Stages cheap enough to repeat at every n (a single sample of a millisecond is noise on a shared machine).
CHEAP = ("equilibrium", "linearize")
CHEAP_REPEATS = 7
#: How many times a largest chain refused in its worker (whose own memory the parent's estimate of the
#: guard's limit does not see) is retried 10 links shorter.
MAX_REFUSALS = 6
#: Environment variable: "0" leaves the largest chains the memory guard admits out of a full run.
LARGE = "PINLIN_BENCH_LARGE"
PAGE = os.sysconf("SC_PAGE_SIZE")


def _rss() -> int:
    with open("/proc/self/statm", encoding="ascii") as f:
        return int(f.read().split()[1]) * PAGE


def _vm_hwm() -> int:
    """The process's peak RSS [bytes] (VmHWM; unlike ru_maxrss it is not inherited from the parent)."""
    with open("/proc/self/status", encoding="ascii") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    return 0


class PeakRSS:
    """Peak RSS [bytes] while the context is open, sampled every ``interval`` s by a thread."""

    def __init__(self, interval: float = 1e-3):
        self.interval = interval
        self.peak = 0
        self._stop = threading.Event()

    def _run(self):
        while not self._stop.is_set():
            self.peak = max(self.peak, _rss())
            time.sleep(self.interval)

    def __enter__(self):
        self.peak = _rss()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()
        self.peak = max(self.peak, _rss())


def worker(n: int) -> dict:
    """Run the pipeline once for an n-link chain in this process; times, memory, figures."""
    import pinlin

    repeats = 3 if n <= 100 else 1
    base = _rss()
    out: dict = {"n": n, "stages": {}}
    state: dict = {}

    from pinlin.model.evaluation import workspace

    def load():
        state.pop("scene", None)  # a repeat must not hold two Pinocchio datas at once
        robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n))
        el = [pinlin.JointSpring(f"joint{i + 1}", 5.0) for i in range(n)]
        el += [pinlin.JointDamper(f"joint{i + 1}", 0.01 * (1 + i % 3)) for i in range(n)]
        state["scene"] = pinlin.Scene(robot, el)

    def create_data():
        state["workspace"] = workspace(state["scene"])

    def equilibrium():
        q0 = np.full(state["scene"].robot.nq, 0.2 / n)
        state["eq"] = pinlin.find_equilibrium(state["scene"], q0)

    def linearize():
        state["sys"] = pinlin.linearize(state["scene"], state["eq"].q)

    def spectrum():
        state["modes"] = pinlin.modal_analysis(state["sys"])

    def response():
        omega = np.logspace(-1, 3, FREQUENCIES)
        state["fr"] = pinlin.frequency_response(state["sys"], omega, [n - 1], None, method="modal", modes=state["modes"])

    tracemalloc.start()
    for name, fn in zip(STAGES, (load, create_data, equilibrium, linearize, spectrum, response)):
        if name == "createData":  # once: the thread's workspace is made on first use and kept
            with PeakRSS() as p:
                t0 = time.perf_counter()
                fn()
                elapsed = time.perf_counter() - t0
            out["stages"][name] = {"time": elapsed, "peak_rss": p.peak - base, "tracemalloc_peak": 0}
            continue
        times = []
        peak_rss = 0
        peak_py = 0
        for k in range(max(repeats, CHEAP_REPEATS) if name in CHEAP else repeats):
            tracemalloc.reset_peak()
            with PeakRSS() as p:
                t0 = time.perf_counter()
                fn()
                times.append(time.perf_counter() - t0)
            if k == 0:  # memory of the first run (later repeats reuse freed pages)
                peak_rss, peak_py = p.peak, tracemalloc.get_traced_memory()[1]
        out["stages"][name] = {
            "time": float(np.median(times)),
            "peak_rss": peak_rss - base,
            "tracemalloc_peak": peak_py,
        }
    tracemalloc.stop()
    out["maxrss"] = _vm_hwm()
    out["base_rss"] = base
    out["estimate"] = pinlin.model.memory.pinocchio_data_bytes(n)
    out["method"] = state["modes"].method.name
    out["max_eta"] = state["modes"].max_backward_error
    out["fr_error"] = state["fr"].error
    out["eq_iterations"] = state["eq"].iterations
    out["stability"] = state["modes"].stability.kind
    return out


def _run_worker(n: int) -> dict:
    env = dict(os.environ)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env["PYTHONPATH"] = root + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    res = subprocess.run(
        [sys.executable, "-m", "benchmarks.bench_scaling", "--worker", str(n)],
        capture_output=True, text=True, env=env, cwd=root, check=False,
    )
    if res.returncode != 0:
        raise RuntimeError(f"scaling worker n = {n} failed:\n{res.stderr[-2000:]}")
    return json.loads(res.stdout.strip().splitlines()[-1])


def guard_demo() -> list[list]:
    """The memory guard refusing, with its estimate, before any allocation."""
    import pinlin

    rows = []
    for n, limit in ((2000, None), (400, 2**30)):
        text = pinlin.pendulum_chain_urdf(n)
        t0 = time.perf_counter()
        before = _rss()
        try:
            pinlin.load_urdf_string(text, memory_limit=limit)
            outcome = "loaded (no refusal)"
        except pinlin.ModelTooLargeError as exc:
            outcome = f"ModelTooLargeError: {exc}"
        rows.append([n, "default (80 % of available)" if limit is None else f"{limit / 2**30:.0f} GiB",
                     pinlin.model.memory.pinocchio_data_bytes(n) / 2**30, (time.perf_counter() - t0) * 1e3,
                     (_rss() - before) / 2**20, outcome])
    return rows


def _fit(ns, ts) -> float:
    """Least-squares slope of log(time) against log(n) for n >= FIT_FROM (NaN with fewer than two points)."""
    ns, ts = np.asarray(ns, float), np.asarray(ts, float)
    keep = ns >= FIT_FROM
    if keep.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(ns[keep]), np.log(ts[keep]), 1)[0])


def largest_admitted_n() -> int:
    """The largest chain whose Pinocchio data the memory guard admits here by default (80 % of available)."""
    import pinlin

    available = pinlin.model.memory.available_memory() or 0
    limit = pinlin.model.memory.MEMORY_FRACTION * available
    n = 10
    while pinlin.model.memory.pinocchio_data_bytes(n + 10) <= limit:
        n += 10
    return n


def large_run(quick: bool) -> bool:
    """Whether this run measures the largest chains the guard admits (full runs, unless PINLIN_BENCH_LARGE=0)."""
    return not quick and os.environ.get(LARGE, "1") != "0"


def sizes(quick: bool) -> tuple[int, ...]:
    """The chain lengths of a run: quick, default, or up to the guard's limit when PINLIN_BENCH_LARGE is set."""
    if quick:
        return QUICK_SIZES
    if not large_run(quick):
        return SIZES
    top = largest_admitted_n()
    return tuple(sorted(set(SIZES) | {(SIZES[-1] + top) // 2 // 10 * 10, top}))


def run(quick: bool = False):
    from .common import Report, Table, result_path, work_precision_plot

    t_start = time.perf_counter()
    results, refused = [], []
    for n in sizes(quick):
        while True:
            try:
                results.append(_run_worker(n))
                break
            except RuntimeError as exc:  # the guard's limit moves with the memory available to the worker
                if n <= SIZES[-1] or "ModelTooLargeError" not in str(exc) or len(refused) >= MAX_REFUSALS:
                    raise
                refused.append(n)
                print(f"[scaling] n = {n} refused by the memory guard in its worker; trying n = {n - 10}")
                n -= 10
    rows, mem_rows = [], []
    for r in results:
        st = r["stages"]
        total = sum(s["time"] for s in st.values())
        rows.append([r["n"]] + [st[s]["time"] * 1e3 for s in STAGES] + [total * 1e3, r["method"], r["max_eta"],
                                                                          r["fr_error"], r["stability"]])
        mem_rows.append([r["n"]] + [st[s]["peak_rss"] / 2**20 for s in STAGES]
                        + [st[s]["tracemalloc_peak"] / 2**20 for s in ("linearize", "spectrum", "frequency response")]
                        + [r["maxrss"] / 2**20, r["estimate"] / 2**20])
    ns = [r["n"] for r in results]
    totals = [sum(s["time"] for s in r["stages"].values()) for r in results]
    exps = {s: _fit(ns, [r["stages"][s]["time"] for r in results]) for s in STAGES}
    exponent = _fit(ns, totals)
    t1 = Table(
        "Time per stage [ms] of the pipeline for n-link pendulum chains",
        ["n"] + [f"{s} [ms]" for s in STAGES] + ["total [ms]", "spectral path", "max eta", "response residual",
                                                  "verdict"],
        rows + [[f"exponent (n >= {FIT_FROM})"] + [f"{exps[s]:.2f}" for s in STAGES] + [f"{exponent:.2f}", "", "", "", ""]],
        note=(
            f"Each n in a fresh subprocess; medians of 3 repeats for n <= 100, one run above, but always "
            f"{CHEAP_REPEATS} for {' and '.join(CHEAP)} (createData: once, the thread's workspace is kept). Last row: least-squares slope of log(time) against log(n) for "
            f"n >= {FIT_FROM} (below, fixed costs flatten it). Frequency response: 1000 frequencies 0.1 ... 1000 "
            "rad/s, tip torque to every angle, modal form with the modes of the spectrum stage."
        ),
    )
    t2 = Table(
        "Peak memory per stage [MiB]",
        ["n"] + [f"{s}: peak RSS" for s in STAGES]
        + ["linearize: tracemalloc peak", "spectrum: tracemalloc peak", "response: tracemalloc peak",
           "process peak RSS (VmHWM)", "guard's estimate of Pinocchio's data"],
        mem_rows,
        note=(
            "Peak RSS: resident set size sampled every 1 ms during the first run of the stage "
            "(/proc/self/statm), minus the RSS before the pipeline started (interpreter, numpy, Pinocchio "
            "loaded); cumulative, so it includes what earlier stages still hold, in particular Pinocchio's C++ "
            "data (four n x n x n tensors, allocated and zeroed by createData: compare the last column). tracemalloc "
            "sees Python and numpy allocations only. VmHWM: the subprocess's true peak RSS, interpreter "
            "included. The sampling thread needs the GIL, so a transient inside one C++ call is seen only in "
            "VmHWM: Pinocchio's createData peaks at about twice its final size (64 n^3 bytes, e.g. 1.84 GiB "
            "at n = 300); the memory guard budgets for that peak (pinlin.model.memory.pinocchio_data_bytes: 72 n^3)."
        ),
    )
    guard = guard_demo()
    t3 = Table(
        "Memory guard: refusing before allocating",
        ["n", "memory_limit", "estimate [GiB]", "time to refuse [ms]", "RSS growth [MiB]", "outcome"],
        guard,
        note="The estimate is pinlin.model.memory.pinocchio_data_bytes(n) = 72 n^3 + 400 n^2 + 4e6 bytes: the peak of "
        "createData (measured 2.1-2.25 times the 32 n^3 bytes it keeps).",
    )
    share = {r["n"]: r["stages"]["createData"]["time"] / max(sum(st["time"] for st in r["stages"].values()), 1e-300)
             for r in results}
    summary = {
        f"fitted cost exponent of the whole pipeline (n >= {FIT_FROM})": f"{exponent:.2f}",
        "exponents per stage": ", ".join(f"{s} {exps[s]:.2f}" for s in STAGES),
        f"total at n = {ns[-1]}": f"{totals[-1]:.2f} s",
        "load time: createData": ", ".join(
            f"n = {r['n']} {r['stages']['createData']['time'] * 1e3:.3g} ms ({share[r['n']]:.0%} of the pipeline)"
            for r in results if r["n"] >= FIT_FROM
        ) + " (one Data per robot and thread, shared by its scenes)",
        "largest chain the memory guard admits here": f"n = {largest_admitted_n()} by this process's estimate; "
        + (f"measured up to n = {ns[-1]}" + (f" (refused in the worker: {refused})" if refused else "")
           if large_run(quick) else f"not measured (quick run or {LARGE}=0)"),
        "memory guard": "refused cleanly in every case" if all("ModelTooLargeError" in g[-1] for g in guard)
        else "DID NOT REFUSE",
    }
    figures = []
    series = {s: [(n, r["stages"][s]["time"]) for n, r in zip(ns, results)] for s in STAGES}
    series["total"] = list(zip(ns, totals))
    path = work_precision_plot(result_path("scaling", quick), series,
                               f"Pipeline time against n (fitted exponent {exponent:.2f})", xlabel="links n",
                               ylabel="time [s]", connect=tuple(series))
    if path:
        figures.append(path)
    text = ("Time and memory of every stage of the data flow for growing pendulum chains (theory: pendulum chains), and the memory "
            "guard of theory: equations refusing models whose Pinocchio data would not fit.")
    report = Report("scaling", [t1, t2, t3], summary, figures, text=text)
    top = largest_admitted_n()
    largest = bool(refused) and refused[-1] == ns[-1] + 10 or ns[-1] >= top
    report.target(14, "peak memory per stage for chains up to the largest n the memory guard admits",
                  f"measured up to n = {ns[-1]}" + (f" (the guard refused n = {', '.join(map(str, refused))} in the "
                                                    "worker)" if refused else f" (the guard's limit: n = {top})"),
                  bool(large_run(quick) and largest), "")
    report.target(14, f"cost exponents fitted for n >= {FIT_FROM} only; load time (createData) reported",
                  f"pipeline {exponent:.2f}, linearize {exps['linearize']:.2f}, spectrum {exps['spectrum']:.2f}; "
                  f"createData {share[ns[-1]]:.0%} of the pipeline at n = {ns[-1]}", True, "")
    report.elapsed = time.perf_counter() - t_start
    return report


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--worker":
        print(json.dumps(worker(int(sys.argv[2]))))
    else:
        from .common import write_report

        rep = run()
        print(rep.markdown())
        print("written to", write_report(rep))
