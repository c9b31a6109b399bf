"""Per-thread Pinocchio workspaces: ``linearize`` before and after, and the cost of a fresh Data.

Issue 10 moved Pinocchio's ``Data`` off the shared ``Scene`` into a workspace per
thread (:mod:`pinlin.model.evaluation`), created on a thread's first use
and reused.  Two questions, answered in one run:

1. Did it make ``linearize`` slower?  The code before the change (commit
   :data:`BASELINE_COMMIT`, extracted with ``git archive`` into a temporary
   directory) and the current code each run in a worker process of their own
   (``_workspace_worker.py``, the same script, PYTHONPATH choosing the
   version); samples alternate between the two, medians are compared.
2. Per-thread workspace, reused, or a fresh ``Data`` per call?  The current
   worker also times ``linearize`` with its thread's workspace cache emptied
   before every call, ``Workspace(scene)`` (memory guard + ``createData``),
   ``createData`` alone, and the per-call lookup ``workspace(scene)``.

Cases: the panda (springs and dampers on every joint, a follower wrench at the
hand, at its equilibrium) and a 100-link chain (springs, Rayleigh damping,
gravity, bent and held by balancing forces), also without Rayleigh damping:
between the two commits Rayleigh's elastic stiffness K_e went from a Python
loop over per-spring matrices to the elements' vectorized contributions, a
gain that has nothing to do with the workspace; the chain without Rayleigh
damping isolates the workspace change.  Both versions must give the same
matrices; the largest relative difference is reported.
"""

from __future__ import annotations

import io
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

import numpy as np

from .common import Table

#: The last commit with ``scene.data`` (one Pinocchio Data per scene, shared by every caller).
BASELINE_COMMIT = "f067b47"
REPO = Path(__file__).resolve().parents[1]
WORKER = Path(__file__).with_name("_workspace_worker.py")
CASES = ("panda", "chain100", "chain100 without Rayleigh")
#: Variants timed in the current code only (see _workspace_worker.py).
AFTER_ONLY = ("fresh", "workspace", "createData", "lookup")
#: Samples per (version, case, variant) in a full run: on a shared machine the medians of few
#: samples moved by 10 % between runs; the fastest sample, also reported, is steadier.
REPEATS = 21


class Worker:
    """A worker process running one version of pinlin; :meth:`ask` sends a command and returns the answer."""

    def __init__(self, src: Path):
        env = dict(os.environ, PYTHONPATH=str(src))
        self.proc = subprocess.Popen(
            [sys.executable, str(WORKER)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            env=env,
            cwd=src,
        )
        self.src = src

    def ask(self, **cmd) -> dict:
        self.proc.stdin.write(json.dumps(cmd) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f"worker for {self.src} exited (code {self.proc.poll()}) on {cmd}")
        out = json.loads(line)
        if "failed" in out:
            raise RuntimeError(f"worker for {self.src} failed on {cmd}: {out['failed']}")
        return out

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(timeout=60)


def baseline_source(directory: Path) -> Path:
    """``src`` of :data:`BASELINE_COMMIT`, extracted into ``directory`` (``git archive``: no change to the repository)."""
    out = subprocess.run(
        ["git", "-C", str(REPO), "archive", "--format=tar", BASELINE_COMMIT, "src"],
        capture_output=True,
        check=False,
    )
    if out.returncode != 0:
        raise RuntimeError(
            f"git archive {BASELINE_COMMIT} failed: {out.stderr.decode(errors='replace').strip()}"
        )
    with tarfile.open(fileobj=io.BytesIO(out.stdout)) as tar:
        tar.extractall(directory, filter="data")
    return directory / "src"


def _difference(a: dict, b: dict) -> float:
    """Largest relative Frobenius difference of M, D, G, S, N between two versions' results."""
    scale = max(np.linalg.norm(np.asarray(a[k])) for k in a)
    return max(float(np.linalg.norm(np.asarray(a[k]) - np.asarray(b[k]))) for k in a) / scale


def _timings(before: Worker, after: Worker, quick: bool) -> dict[tuple[str, str, str], list[float]]:
    """Samples [s per call] of (version, case, variant), taken in turn across versions and variants."""
    min_time = 0.01 if quick else 0.02
    repeats = 5 if quick else REPEATS
    plan = [(before, "before", c, "linearize") for c in CASES] + [
        (after, "after", c, "linearize") for c in CASES
    ]
    plan += [(after, "after", c, v) for c in CASES for v in AFTER_ONLY]
    loops = {
        key[1:]: key[0].ask(cmd="calibrate", case=key[2], variant=key[3], min_time=min_time)["loops"]
        for key in plan
    }
    samples: dict[tuple[str, str, str], list[float]] = {key[1:]: [] for key in plan}
    for _ in range(repeats):
        for worker, *key in plan:
            key = tuple(key)
            samples[key].append(
                worker.ask(cmd="sample", case=key[1], variant=key[2], loops=loops[key])["seconds"]
            )
    return samples


def workspace_section(quick: bool = False) -> tuple[Table | None, dict[str, str]]:
    """The before/after table and summary lines (or, without the baseline, a summary line saying why)."""
    with tempfile.TemporaryDirectory(prefix="pinlin_baseline_") as tmp:
        try:
            old_src = baseline_source(Path(tmp))
        except (RuntimeError, OSError, tarfile.TarError) as exc:
            return None, {"per-thread workspace": f"not measured: the baseline code is not available ({exc})"}
        before, after = Worker(old_src), Worker(REPO / "src")
        try:
            paths = before.ask(cmd="info")["pinlin"], after.ask(cmd="info")["pinlin"]
            if not paths[0].startswith(tmp) or not paths[1].startswith(str(REPO / "src")):
                raise RuntimeError(f"the workers imported the wrong pinlin: {paths}")
            same = {
                c: _difference(before.ask(cmd="result", case=c), after.ask(cmd="result", case=c))
                for c in CASES
            }
            n = {c: len(after.ask(cmd="result", case=c)["M"]) for c in CASES}
            t = _timings(before, after, quick)
        finally:
            before.close()
            after.close()
    med = {key: statistics.median(v) for key, v in t.items()}
    rows, ratios, fresh = [], [], []
    for c in CASES:
        b, a = med[("before", c, "linearize")], med[("after", c, "linearize")]
        fastest = min(t[("after", c, "linearize")]) / min(t[("before", c, "linearize")])
        f = med[("after", c, "fresh")]
        rows.append(
            [
                c,
                n[c],
                b * 1e6,
                a * 1e6,
                a / b,
                fastest,
                f * 1e6,
                f / a,
                med[("after", c, "workspace")] * 1e6,
                med[("after", c, "createData")] * 1e6,
                med[("after", c, "lookup")] * 1e6,
                same[c],
            ]
        )
        ratios.append(
            f"{c} (n = {n[c]}) {a / b:.2f}x ({b * 1e6:.0f} -> {a * 1e6:.0f} us; fastest samples {fastest:.2f}x)"
        )
        fresh.append(f"{c} {f / a:.1f}x")
    table = Table(
        f"Per-thread workspace: linearize before ({BASELINE_COMMIT}, Data on the scene) and after (Data per thread)",
        [
            "case",
            "n",
            "before: linearize [us]",
            "after: linearize [us]",
            "after / before (medians)",
            "after / before (fastest samples)",
            "after, fresh Data per call [us]",
            "fresh / reused",
            "Workspace(scene) [us]",
            "createData alone [us]",
            "workspace(scene) lookup [us]",
            "results: max relative difference after vs before",
        ],
        rows,
        note=(
            "Each version runs in a worker process of its own (benchmarks/_workspace_worker.py; the baseline is "
            f"`git archive {BASELINE_COMMIT} src` in a temporary directory); samples alternate between the versions "
            "and variants; times are medians over the repeats, and the ratio of the fastest samples is given too "
            "(background load on a shared machine slows some samples, never speeds one up). 'fresh Data per "
            "call': linearize with an empty workspace cache during each call (what creating the workspace per "
            "call would cost; the reused workspace is put back after it). Workspace(scene) = "
            "memory guard + createData; the lookup is the per-call price of the per-thread cache. The chain with "
            "Rayleigh damping also gained from K_e's vectorized assembly (same commits, unrelated to the "
            "workspace); the chain without it shows the workspace change alone."
        ),
    )
    summary = {
        "per-thread workspace": "linearize after / before the per-thread workspace: "
        + ", ".join(ratios)
        + "; a fresh Data per call would cost "
        + ", ".join(fresh)
        + " the reused workspace's time",
    }
    return table, summary


if __name__ == "__main__":
    table, summary = workspace_section(quick="--quick" in sys.argv)
    print(summary)
    if table is not None:
        print(table.markdown())
