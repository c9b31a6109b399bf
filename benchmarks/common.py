"""Timing and reporting helpers shared by the benchmarks.

Every timing is the median of repeats, and every comparison is a ratio against a
baseline run in the same process.  Each benchmark module exposes
``run(quick: bool) -> Report``; :func:`write_report` stores it as Markdown and
JSON in ``benchmarks/results/``; :func:`work_precision_plot` draws error against
run time (log-log) as PNG.  ``python -m benchmarks`` runs them all.
"""

from __future__ import annotations

import contextlib
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).parent / "results"


def median_time(fn: Callable[[], object], repeats: int = 7, min_time: float = 0.02) -> float:
    """Median wall time [s] of ``fn()`` over ``repeats`` samples.

    A sample loops ``fn`` enough times to last at least ``min_time`` (so short
    calls are not dominated by timer resolution) and reports the time per call.
    One warm-up call is made first.
    """
    fn()
    loops = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(loops):
            fn()
        dt = time.perf_counter() - t0
        if dt >= min_time or loops >= 1 << 20:
            break
        loops *= 2
    samples = [dt / loops]
    for _ in range(repeats - 1):
        t0 = time.perf_counter()
        for _ in range(loops):
            fn()
        samples.append((time.perf_counter() - t0) / loops)
    return statistics.median(samples)


@dataclass
class Table:
    """A titled table: column names and rows of cells (numbers or text)."""

    title: str
    columns: Sequence[str]
    rows: list[Sequence[object]] = field(default_factory=list)
    note: str = ""

    def markdown(self) -> str:
        def cell(x: object) -> str:
            if isinstance(x, (float, np.floating)):
                return f"{x:.3g}" if x != 0 else "0"
            return str(x)

        lines = [f"### {self.title}", ""]
        if self.note:
            lines += [self.note, ""]
        lines.append("| " + " | ".join(self.columns) + " |")
        lines.append("|" + "|".join("---" for _ in self.columns) + "|")
        lines += ["| " + " | ".join(cell(x) for x in row) + " |" for row in self.rows]
        return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class Target:
    """One target of an issue and what a benchmark run measured for it."""

    issue: int
    what: str
    measured: str
    met: bool | None
    baseline: str = ""

    def row(self) -> list[object]:
        verdict = "not decided" if self.met is None else ("yes" if self.met else "**no**")
        return [self.issue, self.what, self.baseline, self.measured, verdict]


#: Columns of the targets table (:meth:`Target.row`).
TARGET_COLUMNS = ("issue", "target", "baseline", "measured", "met")


@dataclass
class Report:
    """What one benchmark module measured."""

    name: str
    tables: list[Table]
    summary: dict[str, object] = field(default_factory=dict)
    figures: list[str] = field(default_factory=list)
    text: str = ""
    elapsed: float = 0.0
    #: Targets of the issues checked by this run: one :class:`Target` each; the
    #: README collects them into one table (``python -m benchmarks``).
    targets: list[Target] = field(default_factory=list)

    def target(self, issue: int, what: str, measured: str, met: bool | None, baseline: str = "") -> None:
        """Record a target: its issue, what it asks, the measured value, met or not (None: not decided)."""
        self.targets.append(Target(issue, what, measured, met, baseline))

    def markdown(self) -> str:
        parts = [f"## {self.name}", ""]
        if self.text:
            parts += [self.text.strip(), ""]
        if self.summary:
            parts += [f"- **{k}**: {v}" for k, v in self.summary.items()] + [""]
        if self.targets:
            parts += [Table("Targets checked by this run", TARGET_COLUMNS, [t.row() for t in self.targets]).markdown()]
        parts += [t.markdown() for t in self.tables]
        parts += [f"![{Path(f).stem}]({Path(f).name})\n" for f in self.figures]
        return "\n".join(parts)


#: Environment variables that set the thread count of BLAS / OpenMP libraries.
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def _memory_gib() -> str:
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    return f"{int(line.split()[1]) / 2**20:.1f}"
    except OSError:
        pass
    return "unknown"


def blas_info() -> str:
    """BLAS library numpy was built against (from ``numpy.show_config``), or 'unknown'."""
    try:
        cfg = np.show_config(mode="dicts")
        blas = cfg["Build Dependencies"]["blas"]
        return f"{blas.get('name', '?')} {blas.get('version', '')}".strip()
    except Exception:  # noqa: BLE001 - older numpy: no dict mode
        return "unknown"


def machine() -> dict[str, str]:
    import pinocchio
    import scipy

    info = {
        "python": platform.python_version(),
        "machine": platform.machine(),
        "processor": _cpu_model(),
        "cpus": str(os.cpu_count()),
        "memory [GiB]": _memory_gib(),
        "os": f"{platform.system()} {platform.release()}",
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "pinocchio": pinocchio.__version__,
        "blas": blas_info(),
    }
    for var in THREAD_VARIABLES:
        info[var] = os.environ.get(var, "unset")
    return info


def _jsonable(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    return str(x)


def write_report(report: Report, directory: Path = RESULTS) -> Path:
    """Write ``<name>.md`` and ``<name>.json``; return the Markdown path."""
    directory.mkdir(parents=True, exist_ok=True)
    md = directory / f"{report.name}.md"
    md.write_text(report.markdown(), encoding="utf-8")
    payload = {
        "name": report.name,
        "machine": machine(),
        "elapsed [s]": report.elapsed,
        "text": report.text,
        "summary": report.summary,
        "tables": [{"title": t.title, "columns": list(t.columns), "rows": t.rows, "note": t.note} for t in report.tables],
        "figures": report.figures,
        "targets": [dict(zip(TARGET_COLUMNS, (t.issue, t.what, t.baseline, t.measured, t.met))) for t in report.targets],
    }
    (directory / f"{report.name}.json").write_text(json.dumps(payload, indent=2, default=_jsonable), encoding="utf-8")
    return md


def work_precision_plot(
    path: Path | None,
    series: dict[str, Sequence[tuple[float, float]]],
    title: str,
    *,
    xlabel: str = "run time [s]",
    ylabel: str = "relative error",
    floor: float = 1e-17,
    connect: Sequence[str] = (),
    ax=None,
) -> str | None:
    """Error against run time, log-log, one marker style per series; returns the PNG path or None.

    ``series`` maps a label to (time, error) points; errors below ``floor`` are
    drawn at ``floor`` (an exact result has no place on a log axis).  Series
    named in ``connect`` are joined by lines (a sweep of one method's setting).
    Without matplotlib nothing is drawn.  With ``ax`` the curves are drawn on
    that axes and nothing is saved (``path`` may be None).
    """
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(7, 4.8))
    markers = "o^sDvP<>Xh*p"
    for i, (label, pts) in enumerate(series.items()):
        pts = np.array([(t, max(e, floor)) for t, e in pts if np.isfinite(t) and np.isfinite(e)], dtype=float)
        if pts.size == 0:
            continue
        style = "-" if label in connect else ""
        ax.loglog(pts[:, 0], pts[:, 1], style + markers[i % len(markers)], label=label, alpha=0.85)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    if not own:
        return None
    return save_figure(fig, path)


def save_figure(fig, path: Path, dpi: int = 110) -> str:
    """Lay out, write and close a benchmark figure; returns the path as a string."""
    import matplotlib.pyplot as plt

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return str(path)


def result_path(name: str, quick: bool, suffix: str = "png") -> Path:
    """``results/<name>.<suffix>``, or ``<name>_quick.<suffix>`` for a quick run."""
    return RESULTS / f"{name}{'_quick' if quick else ''}.{suffix}"


def loops_for(fn: Callable[[], object], min_time: float = 0.01, clock: Callable[[], float] = time.perf_counter) -> int:
    """Loop count making one sample of ``fn()`` last at least ``min_time`` by ``clock``, after one warm-up call."""
    fn()
    n = 1
    while True:
        t0 = clock()
        for _ in range(n):
            fn()
        if clock() - t0 >= min_time or n >= 1 << 20:
            return n
        n *= 2


def interleaved_medians(
    fns: Sequence[Callable[[], object]],
    repeats: int = 7,
    min_time: float = 0.01,
    clock: Callable[[], float] = time.perf_counter,
) -> list[float]:
    """Median time [s] per call of each function, sampled in turn.

    Each function gets one warm-up call and a loop count making one sample last
    at least ``min_time`` (:func:`loops_for`); then the samples of all functions
    are taken alternately, so a change of machine load (this machine is shared)
    does not favour one side of a ratio.  ``clock``: wall time by default;
    ``time.thread_time`` counts this thread's CPU time only, so other processes'
    load shows less (it still slows the caches).
    """
    loops = [loops_for(fn, min_time, clock) for fn in fns]
    samples: list[list[float]] = [[] for _ in fns]
    for _ in range(repeats):
        for fn, n, out in zip(fns, loops, samples):
            t0 = clock()
            for _ in range(n):
                fn()
            out.append((clock() - t0) / n)
    return [statistics.median(s) for s in samples]


def load_average() -> str:
    """The 1-minute load average (from /proc/loadavg), or 'unknown': how busy the shared machine was."""
    try:
        with open("/proc/loadavg", encoding="ascii") as f:
            return f.read().split()[0]
    except OSError:
        return "unknown"


@contextlib.contextmanager
def busy_core() -> Iterator[subprocess.Popen | None]:
    """A busy-loop process pinned to core 1 while the block runs (None where taskset or a second core is missing)."""
    if shutil.which("taskset") is None or (os.cpu_count() or 1) < 2:
        yield None
        return
    busy = subprocess.Popen(["taskset", "-c", "1", sys.executable, "-c", "while True: pass"])
    try:
        yield busy
    finally:
        busy.kill()
        busy.wait()
