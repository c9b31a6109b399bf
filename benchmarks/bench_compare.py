"""Before/after comparison: pinlin at a base git revision against a working tree, on the user-level rows.

``python -m benchmarks.bench_compare --base REV [--head PATH] [--quick] [--name NAME]``

The base revision is checked out with ``git worktree add --detach`` into a
temporary directory (removed afterwards).  The rows run in child processes
(:mod:`._compare_worker`), a few in turn per side and row group, with
``PYTHONPATH=<tree>/src`` of the side and the benchmark code of this tree: both
sides run the same benchmark code and differ only in pinlin (each child reports
which pinlin it imported).  The parent asks a base and a head child for one sample
at a time, base, head, head, base, base, head, ..., so that both sides see the same
moments of the shared machine's load (and each goes first as often); a sample is
the thread CPU time (``time.thread_time``) of the row's call and then of its
same-process baseline.  A side's time is the median of its samples; head / base is
the median over the rounds of the ratio of the two samples of a round (a slow drift
of the load cancels in it); a ratio to the baseline is the median of the samples'
ratios.

Rows (public API calls only, so that they run on both revisions):

- ``linearize_many`` per point (100 points) on ur5, panda, solo12 and talos_reduced
  (``bench_linearize``'s scenes), against the Pinocchio floor of the row
  (the algorithms the linearization lists in ``calls``, replayed bare);
- a sweep of linearize + ``modal_analysis`` over the panda's joint stiffness
  (``bench_spectral.sweep_point``), per point;
- ``modal_analysis`` on talos_full_v2 and the 8-branch chain (``bench_clusters``)
  against ``scipy.linalg.eig(A, B, left=True)``, and on talos_full_v2 once more
  with the default BLAS threads while a busy loop holds core 1 (thread CPU and
  wall time);
- ``floquet_analysis`` on rotor6 and chain6 and ``floquet_campbell`` on the rotor
  at four speeds (``bench_floquet``).

Writes ``results/<name>.md`` and ``.json``: per row base, head, head/base and
whether head is more than 15 % slower; the absolute targets on the head side;
every sample in ``results/<name>_samples.json``.
"""

from __future__ import annotations

import argparse
import contextlib
import itertools
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from .common import THREAD_VARIABLES, Report, Table, busy_core, load_average, write_report

ROOT = Path(__file__).resolve().parent.parent
#: A row is flagged when head / base exceeds this.
SLOWER = 1.15
#: Absolute targets: linearize_many per point / floor, modal_analysis / eig(left=True), busy / single thread.
FLOOR_TARGET, EIG_TARGET, BUSY_TARGET = 3.0, 2.0, 3.0
#: Rounds and worker processes per side and row group of a full and a quick run: a round is one sample
#: per row and side; the rounds are shared out between the processes.
FULL, QUICK = (80, 4), (16, 2)
#: The clocks of a sample, in the worker's order.
CLOCKS = ("thread", "wall")


@dataclass(frozen=True)
class Row:
    """One compared row: its name (a key of ``_compare_worker.BUILDERS``), its group of children, its baseline."""

    name: str
    group: str
    baseline: str = ""
    busy: bool = False


BUSY_ROW = "modal_analysis talos_full_v2, default threads, core 1 busy"
ROWS = (
    *(Row(f"linearize_many {r}", "linearize_many", "Pinocchio floor") for r in ("ur5", "panda", "solo12", "talos")),
    Row("sweep panda", "sweep"),
    Row("modal_analysis talos_full_v2", "modal_analysis", "eig(left=True)"),
    Row("modal_analysis 8-branch chain", "modal_analysis", "eig(left=True)"),
    Row(BUSY_ROW, "busy", "eig(left=True)", busy=True),
    Row("floquet_analysis rotor6", "floquet"),
    Row("floquet_analysis chain6", "floquet"),
    Row("floquet_campbell rotor6, 4 speeds", "floquet"),
)


def _git(*args: str, cwd: Path) -> str:
    return subprocess.run(["git", "-C", str(cwd), *args], capture_output=True, text=True, check=True).stdout.strip()


@contextlib.contextmanager
def checkout(repo: Path, rev: str) -> Iterator[Path]:
    """The tree of ``rev`` in a temporary detached worktree of ``repo``, removed on exit."""
    path = Path(tempfile.mkdtemp(prefix="pinlin-base-"))
    _git("worktree", "add", "--detach", str(path), rev, cwd=repo)
    try:
        yield path
    finally:
        _git("worktree", "remove", "--force", str(path), cwd=repo)


def _revision(tree: Path) -> str:
    dirty = " + uncommitted changes" if _git("status", "--porcelain", "--untracked-files=no", cwd=tree) else ""
    subject = _git("log", "-1", "--format=%h %cs %s", cwd=tree)
    return (subject if len(subject) <= 60 else subject[:59] + "...") + dirty


class Worker:
    """A :mod:`._compare_worker` process on ``tree``'s pinlin, asked for one sample of a row at a time."""

    def __init__(self, tree: Path, busy: bool = False):
        env = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
        if not busy:  # one BLAS thread, as the other benchmarks; the busy row keeps the user's default
            env |= dict.fromkeys(THREAD_VARIABLES, "1")
        env["PYTHONPATH"] = os.pathsep.join((str(tree / "src"), str(ROOT)))
        env["PYTHONWARNINGS"] = "ignore::DeprecationWarning"
        self.tree, self.stderr = tree, tempfile.TemporaryFile("w+")
        self.process = subprocess.Popen([sys.executable, "-m", "benchmarks._compare_worker"], env=env, cwd=ROOT,
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=self.stderr, text=True)

    def sample(self, row: str) -> dict:
        """One sample of the row's call and baseline (or its error); RuntimeError if the worker died or
        imported another pinlin."""
        with contextlib.suppress(BrokenPipeError):  # a dead worker: its empty answer says so
            self.process.stdin.write(row + "\n")
            self.process.stdin.flush()
        line = self.process.stdout.readline()
        if not line:
            self.process.wait()
            self.stderr.seek(0)
            raise RuntimeError(f"worker on {self.tree} failed on {row!r}:\n{self.stderr.read()[-3000:]}")
        out = json.loads(line)
        if not Path(out["pinlin"]).resolve().is_relative_to((self.tree / "src").resolve()):
            raise RuntimeError(f"the worker on {self.tree} imported {out['pinlin']}")
        return out

    def close(self) -> None:
        with contextlib.suppress(BrokenPipeError):
            self.process.stdin.close()
        self.process.wait()
        self.stderr.close()


def measure(trees: dict[str, Path], rounds: int, processes: int) -> tuple[dict, dict]:
    """Per row and side, the samples, and the failures (row -> side -> error; a failed row has no samples).

    Row groups run one after the other, each with ``processes`` workers per side in turn (a process of
    its own shifts every sample a little: memory layout, hash seed); a round takes one sample of every
    row of the group from each side in turn, base first in even rounds and head first in odd ones
    (in one noise run the second sample of a pair ran 1-3 % faster: alternating cancels such an order effect).
    """
    samples: dict[str, dict[str, list[dict]]] = {r.name: {side: [] for side in trees} for r in ROWS}
    failures: dict[str, dict[str, str]] = {}

    def fail(row: str, side: str, error: str) -> None:
        failures.setdefault(row, {})[side] = error
        samples[row][side].clear()
        print(f"[compare] {row} failed on {side}:\n{error}", flush=True)

    for group in dict.fromkeys(r.group for r in ROWS):
        rows = [r for r in ROWS if r.group == group]
        busy = any(r.busy for r in rows)
        print(f"[compare] {group}: {rounds} rounds of {', '.join(r.name for r in rows)}", flush=True)
        with busy_core() if busy else contextlib.nullcontext():
            for _ in range(processes):
                workers = {side: Worker(tree, busy) for side, tree in trees.items()}
                try:
                    for k in range(rounds // processes):
                        order = list(workers.items())[:: 1 if k % 2 == 0 else -1]
                        for row, (side, worker) in itertools.product(rows, order):
                            if side in failures.get(row.name, {}):
                                continue
                            try:
                                out = worker.sample(row.name)
                            except RuntimeError as exc:  # the worker died: every row it has left fails
                                for r in rows:
                                    fail(r.name, side, str(exc))
                                continue
                            if "error" in out:
                                fail(row.name, side, out["error"])
                            else:
                                samples[row.name][side].append(out)
                finally:
                    for worker in workers.values():
                        worker.close()
    return samples, failures


def _median(samples: list[dict], clock: str = "thread") -> float:
    """Median time of the row's call [s]."""
    return statistics.median(s["call"][CLOCKS.index(clock)] for s in samples)


def _ratio(samples: list[dict], clock: str = "thread") -> float:
    """Median of call / baseline over the samples (each pair taken one after the other in one process)."""
    k = CLOCKS.index(clock)
    return statistics.median(s["call"][k] / s["baseline"][k] for s in samples)


def _paired(base: list[dict], head: list[dict], clock: str = "thread") -> list[float]:
    """head / base of every round (its two samples taken one after the other)."""
    k = CLOCKS.index(clock)
    return [h["call"][k] / b["call"][k] for b, h in zip(base, head)]


def median_interval(values: list[float]) -> tuple[float, float]:
    """A distribution-free 95 % interval of the median: the order statistics n/2 -+ 1.96 sqrt(n)/2."""
    v, half = sorted(values), 1.96 * math.sqrt(len(values)) / 2
    return v[max(math.floor(len(v) / 2 - half), 0)], v[min(math.ceil(len(v) / 2 + half), len(v) - 1)]


def _measured(samples: dict, name: str) -> bool:
    return all(samples[name].values())


def tables(samples: dict) -> tuple[list[Table], dict]:
    """The comparison table and a summary per row."""
    rows, summary = [], {}
    for row in ROWS:
        if not _measured(samples, row.name):
            rows.append([row.name, "-", "-", "failed (see the JSON's failures)", "-", "-", "-", row.baseline or "-", "-", "-"])
            continue
        base, head = samples[row.name]["base"], samples[row.name]["head"]
        for clock in CLOCKS if row.busy else CLOCKS[:1]:
            b, h, paired = _median(base, clock), _median(head, clock), _paired(base, head, clock)
            ratio, (low, high) = statistics.median(paired), median_interval(paired)
            rb, rh = (f"{_ratio(base, clock):.2f}", f"{_ratio(head, clock):.2f}") if row.baseline else ("-", "-")
            name = row.name + (f" ({clock} time)" if row.busy else "")
            rows.append([name, b * 1e3, h * 1e3, f"{ratio:.3f}", f"{low:.3f} - {high:.3f}", f"{h / b:.3f}",
                         "**yes**" if ratio > SLOWER else "no",
                         row.baseline or "-", rb, rh])
            summary[name] = {"clock": clock, "base [s]": b, "head [s]": h, "head / base": ratio,
                             "95 % interval": [low, high], "ratio of the medians": h / b,
                             "slower than 15 %": ratio > SLOWER}
    table = Table(
        "pinlin at the base revision against the head tree [ms per call, per point for linearize_many and the sweep]",
        ["row", "base", "head", "head / base", "95 % interval", "ratio of the medians", f"slower than {SLOWER - 1:.0%}?",
         "same-process baseline", "base / baseline", "head / baseline"],
        rows,
        note=("Thread CPU time unless said: medians of samples taken in turn from a base and a head process, "
              "one BLAS thread except the busy row. 'head / base': median over the rounds of the ratio of the two "
              "samples taken one after the other (flagged above 1.15), with a distribution-free 95 % interval of that "
              "median; '/ baseline': median of the ratios within a sample. "
              f"Load average at the end {load_average()} on {os.cpu_count()} CPUs (a shared machine)."),
    )
    return [table], summary


def targets(report: Report, samples: dict, rows: dict) -> None:
    """The targets: no row slower, and the absolute ones decided on the head side; unmeasured rows skipped."""
    ratios = {name: v["head / base"] for name, v in rows.items() if v["clock"] == "thread"}
    if ratios:
        worst = max(ratios, key=ratios.get)
        report.target(31, f"no row more than {SLOWER - 1:.0%} slower than base (thread CPU time)",
                      f"slowest: {worst} {ratios[worst]:.3f}", max(ratios.values()) <= SLOWER,
                      "the base revision, samples in turn")
    for robot in ("ur5", "panda", "solo12", "talos"):
        name = f"linearize_many {robot}"
        if _measured(samples, name):
            s = samples[name]
            h, b = _ratio(s["head"]), _ratio(s["base"])
            report.target(31, f"linearize_many per point at most {FLOOR_TARGET:g}x the Pinocchio floor: {robot}",
                          f"{h:.2f}x (base {b:.2f}x)", bool(h <= FLOOR_TARGET), f"{s['head'][0]['info']['floor']}, thread CPU")
    single = "modal_analysis talos_full_v2"
    if not _measured(samples, single):
        return
    s = samples[single]
    h, b = _ratio(s["head"]), _ratio(s["base"])
    report.target(31, f"modal_analysis at most {EIG_TARGET:g}x eig(left=True): talos_full_v2", f"{h:.2f}x (base {b:.2f}x)",
                  bool(h <= EIG_TARGET), "scipy.linalg.eig(A, B, left=True), thread CPU")
    if not _measured(samples, BUSY_ROW):
        return
    busy, one = samples[BUSY_ROW], {side: _median(s[side]) for side in s}
    by = {clock: {side: _median(busy[side], clock) / one[side] for side in busy} for clock in CLOCKS}
    report.target(31, f"default BLAS threads, core 1 busy: modal_analysis at most {BUSY_TARGET:g}x its single-thread "
                  "time: talos_full_v2", f"{by['thread']['head']:.2f}x by thread CPU, {by['wall']['head']:.2f}x by wall "
                  f"(base {by['thread']['base']:.2f}x, {by['wall']['base']:.2f}x)", bool(by["thread"]["head"] <= BUSY_TARGET),
                  "modal_analysis with OPENBLAS_NUM_THREADS=1, thread CPU")


def compare(base: str, head: Path, quick: bool = False) -> tuple[Report, dict]:
    """Measure every row on ``base`` (a revision of ``head``'s repository) and on the tree ``head``.

    Returns the report and the raw results: the rows' medians, every sample and the failures.
    """
    rounds, processes = QUICK if quick else FULL
    t0 = time.perf_counter()
    with checkout(head, base) as base_tree:
        revisions = {"base": f"{base} = {_revision(base_tree)}", "head": f"{head} at {_revision(head)}"}
        samples, failures = measure({"base": base_tree, "head": head}, rounds, processes)
    tabs, rows = tables(samples)
    summary = {**revisions, "rounds": f"{rounds} (samples per row and side, taken in turn), from {processes} processes per side",
               "rows slower than 15 %": ", ".join(k for k, v in rows.items() if v["slower than 15 %"]) or "none",
               "failed": ", ".join(f"{row} on {side}" for row, sides in failures.items() for side in sides) or "none"}
    report = Report("compare", tabs, summary, text=__doc__.split("\n\n")[2])
    targets(report, samples, rows)
    report.elapsed = time.perf_counter() - t0
    return report, {"rows": rows, "samples": samples, "failures": failures}


def _parse(argv):
    p = argparse.ArgumentParser(prog="python -m benchmarks.bench_compare", description=__doc__.splitlines()[0])
    p.add_argument("--base", required=True, help="git revision to compare against (e.g. 86bc0a5)")
    p.add_argument("--head", type=Path, default=ROOT, help="the tree measured as head (default: this working tree)")
    p.add_argument("--quick", action="store_true", help=f"{QUICK[0]} rounds instead of {FULL[0]} (a smoke run)")
    p.add_argument("--name", default="compare", help="results/<name>.md and .json (default: compare)")
    return p.parse_args(argv)


def compact(samples: dict) -> dict:
    """The samples per row and side as [thread, wall] pairs in microseconds (4 digits), with the pinlin imported."""
    def us(pair):
        return None if pair is None else [float(f"{t * 1e6:.4g}") for t in pair]

    return {row: {side: {"pinlin": s[0]["pinlin"], "info": s[0]["info"], "call [us]": [us(x["call"]) for x in s],
                         "baseline [us]": [us(x["baseline"]) for x in s]} for side, s in sides.items() if s}
            for row, sides in samples.items()}


def main(argv=None) -> int:
    args = _parse(sys.argv[1:] if argv is None else argv)
    report, raw = compare(args.base, args.head.resolve(), args.quick)
    report.name = args.name + ("_quick" if args.quick else "")
    path = write_report(report).with_suffix(".json")
    extra = {"rows": raw["rows"], "failures": raw["failures"], "samples": f"{report.name}_samples.json"}
    path.write_text(json.dumps(json.loads(path.read_text(encoding="utf-8")) | extra, indent=2), encoding="utf-8")
    samples = path.with_name(extra["samples"])
    samples.write_text(json.dumps(compact(raw["samples"]), separators=(",", ":")) + "\n", encoding="utf-8")
    print(report.markdown())
    print(f"[compare] {report.elapsed:.0f} s, written to {path.with_suffix('.md')}, {path} and {samples}", flush=True)
    return 1 if raw["failures"] else 0


if __name__ == "__main__":
    raise SystemExit(main())
