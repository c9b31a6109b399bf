"""Run pinlin's benchmark suite: ``python -m benchmarks [--quick] [--only NAME ...]``.

Writes Markdown, JSON and PNG files into ``benchmarks/results/`` and
regenerates ``benchmarks/README.md`` with the latest tables, the machine and how
to reproduce them.  BLAS and OpenMP are limited to one thread before numpy is
imported (unless the variables are already set): on a shared two-core machine
threaded OpenBLAS made the timings of small products erratic.  The settings in
force are recorded in every JSON file and in the README.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import importlib  # noqa: E402
import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

#: Benchmark modules in the order they run: (name, module, what it measures).
SUITE = (
    ("linearize", "bench_linearize", "analytic linearization against finite differences (and MuJoCo)"),
    ("catalog", "bench_catalog", "spectrum of stiff and extreme cases: every eigen-method against mpmath"),
    ("spectral", "bench_spectral", "modal analysis paths against plain QZ: time and backward error"),
    ("clusters", "bench_clusters",
     "clustered spectra (talos_full_v2, 8 identical branches) and busy machines: modal_analysis vs eig(left=True)"),
    ("adjoint", "bench_adjoint", "frequency responses (modal vs direct) and the characteristic polynomial"),
    ("response", "bench_response", "free response: modal formula against expm and time integration"),
    ("scaling", "bench_scaling", "time and memory per stage for chains of n = 10 ... 400; the memory guard"),
    ("constraints", "bench_constraints", "constrained systems: linearize overhead, KKT equilibrium, accuracy"),
    ("frame_elements", "bench_frame_elements",
     "elements between frames: cost per element against a joint spring's, and against central differences"),
    ("boundaries", "bench_boundaries", "stability boundaries: critical_parameter against bisection on the verdict"),
    ("floquet", "bench_floquet", "Floquet analysis of periodic scenes against DOP853 on the matrix equation + eig"),
)

HERE = Path(__file__).parent
RESULTS = HERE / "results"
README = HERE / "README.md"
#: Hand-written commentary, ``notes/<name>.md``: put into the README before the
#: generated section of benchmark ``<name>``, so that regenerating keeps it.
NOTES = HERE / "notes"


def _parse(argv):
    p = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="smaller sizes and fewer repeats (a smoke run, ~2 min)")
    p.add_argument("--only", action="append", default=[], metavar="NAME",
                   help=f"run only these benchmarks (repeatable or comma-separated): {', '.join(s[0] for s in SUITE)}")
    p.add_argument("--list", action="store_true", help="list the benchmarks and exit")
    p.add_argument("--no-readme", action="store_true", help="do not regenerate benchmarks/README.md")
    args = p.parse_args(argv)
    names = [n.strip() for item in args.only for n in item.split(",") if n.strip()]
    unknown = sorted(set(names) - {s[0] for s in SUITE})
    if unknown:
        p.error(f"unknown benchmark(s) {unknown}; choose from {[s[0] for s in SUITE]}")
    args.names = names or [s[0] for s in SUITE]
    return args


def main(argv=None) -> int:
    args = _parse(sys.argv[1:] if argv is None else argv)
    if args.list:
        for name, module, what in SUITE:
            print(f"{name:10s} benchmarks/{module}.py: {what}")
        return 0
    from .common import machine, write_report

    t0 = time.perf_counter()
    elapsed = {}
    for name, module, _ in SUITE:
        if name not in args.names:
            continue
        print(f"[benchmarks] {name} ...", flush=True)
        t = time.perf_counter()
        mod = importlib.import_module(f"benchmarks.{module}")
        report = mod.run(quick=args.quick)
        if args.quick:  # a smoke run never overwrites the tables of a full run
            report.name += "_quick"
        report.elapsed = time.perf_counter() - t
        path = write_report(report)
        elapsed[report.name] = report.elapsed
        print(f"[benchmarks] {name}: {report.elapsed:.1f} s -> {path}", flush=True)
    total = time.perf_counter() - t0
    run = {
        "command": "python -m benchmarks" + (" --quick" if args.quick else "")
        + "".join(f" --only {n}" for n in (args.names if len(args.names) < len(SUITE) else [])),
        "quick": args.quick,
        "wall time [s]": total,
        "elapsed [s]": elapsed,
        "finished": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "machine": machine(),
    }
    (RESULTS / ("run_quick.json" if args.quick else "run.json")).write_text(json.dumps(run, indent=2), encoding="utf-8")
    print(f"[benchmarks] total wall time {total:.1f} s", flush=True)
    if not args.no_readme and not args.quick:
        write_readme(run)
        print(f"[benchmarks] {README} regenerated", flush=True)
    return 0


def _load(name: str):
    path = RESULTS / f"{name}.json"
    return json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None


def _headlines() -> list[str]:
    """The headline numbers (accuracy, stability, scaling), from the latest JSON files."""
    out = []
    lin = _load("linearize")
    if lin:
        s = lin["summary"]
        out.append(f"**Linearization**: {s.get('headline', '')}. Robots: {s.get('robots (n >= 6)', '')}.")
    cat = _load("catalog")
    if cat:
        s = cat["summary"]
        out.append(f"**Spectrum**: scaled QZ max eta over the catalog {s.get('scaled QZ max eta over the catalog')}; "
                   f"roots of the characteristic polynomial lose all accuracy at n = "
                   f"{s.get('roots of p lose all accuracy (max rel. eigenvalue error >= 1) at n')}.")
    sc = _load("scaling")
    if sc:
        s = sc["summary"]
        out.append(f"**Scaling**: fitted cost exponent of the whole pipeline "
                   f"{s.get('fitted cost exponent of the whole pipeline (n >= 100)')} "
                   f"({s.get('exponents per stage')}); memory guard: {s.get('memory guard')}.")
    return out


def _targets() -> list[str]:
    """One table of every issue target the latest runs checked (each benchmark's JSON ``targets``)."""
    from .common import TARGET_COLUMNS, Table

    rows = []
    for name, _, _ in SUITE:
        data = _load(name)
        for t in (data or {}).get("targets", []):
            met = t["met"]
            rows.append([t["issue"], t["target"], t["baseline"], t["measured"],
                         "not decided" if met is None else ("yes" if met else "**no**"), name])
    if not rows:
        return []
    rows.sort(key=lambda r: r[0])
    table = Table("Targets of the issues, as measured by the latest run", (*TARGET_COLUMNS, "benchmark"), rows,
                  note="Collected from `results/<benchmark>.json`; each row links a target to the run that measured it.")
    return ["## Targets", "", table.markdown()]


def write_readme(run: dict) -> None:
    m = run["machine"]
    lines = [
        "# pinlin benchmarks",
        "",
        "Error against run time, and numerical stability on stiff and extreme cases. "
        "Generated by `python -m benchmarks`; do not edit by hand: the tables come from `results/`, the "
        "commentary before a benchmark's tables from `notes/<name>.md`.",
        "",
        "## Reproduce",
        "",
        "```",
        "pip install -e '.[bench]'          # matplotlib, mpmath",
        "python -m benchmarks               # the whole suite (~10 min on 2 cores), rewrites this file",
        "python -m benchmarks --quick       # smaller sizes, a smoke run; results/*_quick.*, README untouched",
        "python -m benchmarks --only catalog --only linearize",
        "python -m benchmarks --list",
        "```",
        "",
        "Before/after comparison of pinlin at a git revision with a working tree, on the user-level rows "
        "(`linearize_many` on ur5, panda, solo12, talos against the Pinocchio floor; a sweep; `modal_analysis` "
        "against `eig(left=True)`, also with the default BLAS threads and one core busy; `floquet_analysis`, "
        "`floquet_campbell`):",
        "",
        "```",
        "python -m benchmarks.bench_compare --base 86bc0a5             # this tree against 86bc0a5 (~4-5 min)",
        "python -m benchmarks.bench_compare --base 86bc0a5 --head PATH --name NAME  # another checkout: results/NAME.*",
        "python -m benchmarks.bench_compare --base 86bc0a5 --quick     # 16 rounds, a smoke run (~1.5 min)",
        "```",
        "",
        "The base revision is checked out into a temporary `git worktree` (removed afterwards); the rows run "
        "in child processes on either tree's `src/` (the same benchmark code), which take one sample at a time "
        "in turn, base and head, thread CPU time; head / base is the median of the paired ratios. Results: "
        "`results/compare.md` and `.json` (head / base per row with a 95 % interval, rows more than 15 % slower "
        "flagged, the absolute targets), every sample in `results/compare_samples.json`; "
        "`results/compare_noise.*` compares a tree with its own revision: the noise floor of the ratios "
        "(within 5 % on this machine).",
        "",
        "Optional: with `mujoco` importable, the linearization benchmark adds MuJoCo's `mjd_inverseFD` as a peer "
        "(it is not a dependency of pinlin; without it the benchmark says it skipped it). "
        "Results: `benchmarks/results/<name>.md`, `.json` (with the machine description) and `.png`.",
        "",
        "## Last run",
        "",
        f"- command: `{run['command']}`, finished {run['finished']}, wall time **{run['wall time [s]']:.0f} s**"
        + "; per benchmark: " + ", ".join(f"{k} {v:.0f} s" for k, v in run["elapsed [s]"].items()),
        "- tables below, by the time their run wrote them: " + ", ".join(
            f"{name} {time.strftime('%Y-%m-%d %H:%M', time.gmtime((RESULTS / f'{name}.json').stat().st_mtime))}"
            for name, _, _ in SUITE if (RESULTS / f"{name}.json").is_file()) + " UTC",
        f"- machine: {m['processor']}, {m['cpus']} CPUs, {m['memory [GiB]']} GiB, {m['os']}; Python {m['python']}, "
        f"numpy {m['numpy']}, scipy {m['scipy']}, pinocchio {m['pinocchio']}, BLAS {m['blas']}",
        "- threads: " + ", ".join(f"{k}={m[k]}" for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"))
        + " (set by `python -m benchmarks` before numpy is imported unless already set: threaded OpenBLAS made "
        "small products erratic on this shared 2-core machine)",
        "- timings are medians of repeats, baselines run in the same process; errors are measured against "
        "references that do not share the method (closed forms, mpmath at 50 digits, Richardson extrapolation).",
        "",
        "## Headline numbers",
        "",
    ]
    lines += [f"- {h}" for h in _headlines()] + [""]
    lines += _targets()
    for name, module, what in SUITE:
        md = RESULTS / f"{name}.md"
        if not md.is_file():
            continue
        note = NOTES / f"{name}.md"
        if note.is_file():
            lines += [f"<!-- notes/{name}.md -->", note.read_text(encoding="utf-8").rstrip(), ""]
        lines += [f"<!-- {module}.py: {what} -->"]
        text = md.read_text(encoding="utf-8")
        for png in sorted(RESULTS.glob("*.png")):
            text = text.replace(f"]({png.name})", f"](results/{png.name})")
        lines += [text, ""]
    README.write_text("\n".join(lines), encoding="utf-8")


if __name__ == "__main__":
    raise SystemExit(main())
