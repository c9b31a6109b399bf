"""Timing and reporting helpers shared by the benchmarks.

Every timing is the median of repeats, and every comparison is a ratio against a
baseline run in the same process.  Each benchmark module exposes
``run(quick: bool) -> Report``; :func:`write_report` stores it as Markdown and
JSON in ``benchmarks/results/``.
"""

from __future__ import annotations

import json
import platform
import statistics
import time
from collections.abc import Callable, Sequence
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


@dataclass
class Report:
    """What one benchmark module measured."""

    name: str
    tables: list[Table]
    summary: dict[str, object] = field(default_factory=dict)
    figures: list[str] = field(default_factory=list)

    def markdown(self) -> str:
        parts = [f"## {self.name}", ""]
        if self.summary:
            parts += [f"- **{k}**: {v}" for k, v in self.summary.items()] + [""]
        parts += [t.markdown() for t in self.tables]
        parts += [f"![{Path(f).stem}]({Path(f).name})\n" for f in self.figures]
        return "\n".join(parts)


def machine() -> dict[str, str]:
    import pinocchio
    import scipy

    return {
        "python": platform.python_version(),
        "machine": platform.machine(),
        "processor": platform.processor() or "unknown",
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "pinocchio": pinocchio.__version__,
    }


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
        "summary": report.summary,
        "tables": [{"title": t.title, "columns": list(t.columns), "rows": t.rows, "note": t.note} for t in report.tables],
        "figures": report.figures,
    }
    (directory / f"{report.name}.json").write_text(json.dumps(payload, indent=2, default=_jsonable), encoding="utf-8")
    return md
