"""Worker of ``bench_compare``: rows timed with whichever pinlin ``PYTHONPATH`` imports.

Run as ``python -m benchmarks._compare_worker`` with one row name per line on
standard input; answers each with one JSON line: the pinlin file imported, the
row's call and its same-process baseline (None if the row has none), each one
sample of thread CPU and wall time [s per call, per point where the row says so],
or the traceback of a row that raised.
The first request of a row builds it and sets its loop counts
(:func:`common.loops_for`, thread CPU time); every later request takes one more
sample of each, so that the parent can alternate two workers sample by sample.
Only public calls of pinlin are timed (the base revision of a comparison has
the same public names); renamed keywords warn DeprecationWarning, silenced here.
"""

from __future__ import annotations

import json
import sys
import time
import traceback
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

warnings.simplefilter("ignore", DeprecationWarning)

import numpy as np  # noqa: E402
import scipy.linalg as sla  # noqa: E402

import pinlin  # noqa: E402

from .common import loops_for  # noqa: E402

#: Configurations per ``linearize_many`` call (the same equilibrium repeated); its time is reported per point.
POINTS = 100
#: Joint stiffnesses [N m/rad] of the sweep row (bench_spectral.sweep_point on the panda).
SWEEP_STIFFNESS = tuple(np.geomspace(30.0, 3000.0, 8))
#: Drive speeds [rad/s] of the Campbell row (the rotor of bench_floquet).
CAMPBELL_SPEEDS = (19.0, 21.0, 23.0, 25.0)


@dataclass(frozen=True)
class Timed:
    """What a row times: ``call`` (divided by ``per``), the ``baseline`` of the same process (or None)."""

    call: Callable[[], object]
    baseline: Callable[[], object] | None = None
    per: int = 1
    info: dict = field(default_factory=dict)


# The benchmark modules are imported by the builders that use them: a module that does not import
# with one side's pinlin fails its own rows only.


def _linearize_many(case_builder: str) -> Timed:
    from . import bench_linearize

    case = getattr(bench_linearize, case_builder)()
    scene, q, balancing = case.scene, case.q, case.balancing
    calls = pinlin.linearize(scene, q, balancing=balancing).calls
    qs = np.tile(q, (POINTS, 1))
    return Timed(lambda: pinlin.linearize_many(scene, qs, balancing=balancing),
                 bench_linearize.pinocchio_floor(scene, q, calls), POINTS, {"floor": " + ".join(calls), "n": case.scene.n})


def _modal(case: str) -> Timed:
    from . import bench_clusters, bench_spectral

    sys_ = bench_clusters.CASES[case]()
    A, B = bench_clusters.companion_pencil(sys_.M, sys_.C, sys_.K)
    return Timed(lambda: bench_spectral.analyse(sys_), lambda: sla.eig(A, B, left=True), info={"n": sys_.n})


def _sweep() -> Timed:
    from . import bench_spectral

    grid = {"k": np.array(SWEEP_STIFFNESS)}
    return Timed(lambda: pinlin.sweep(bench_spectral.sweep_point, grid, progress=False), per=len(SWEEP_STIFFNESS))


def _floquet(name: str) -> Timed:
    from . import bench_floquet

    scene = bench_floquet.rotor_scene() if name == "rotor6" else bench_floquet.chain_scene(6, bench_floquet.HEAVY_DAMPING)
    _, analyse = bench_floquet.floquet_call(scene)
    return Timed(analyse, info={"n": scene.n})


def _campbell() -> Timed:
    from . import bench_floquet

    def at(speed: float) -> pinlin.FloquetAnalysis:
        return bench_floquet.floquet_call(bench_floquet.rotor_scene(speed))[1]()

    return Timed(lambda: pinlin.floquet_campbell(at, CAMPBELL_SPEEDS), info={"speeds": list(CAMPBELL_SPEEDS)})


#: Builders of the rows by name: the names of ``bench_compare.ROWS``.
BUILDERS: dict[str, Callable[[], Timed]] = {
    "linearize_many ur5": lambda: _linearize_many("ur5_case"),
    "linearize_many panda": lambda: _linearize_many("panda_case"),
    "linearize_many solo12": lambda: _linearize_many("solo_case"),
    "linearize_many talos": lambda: _linearize_many("talos_case"),
    "sweep panda": _sweep,
    "modal_analysis talos_full_v2": lambda: _modal("talos_full_v2"),
    "modal_analysis 8-branch chain": lambda: _modal("8-branch chain"),
    "modal_analysis talos_full_v2, default threads, core 1 busy": lambda: _modal("talos_full_v2"),
    "floquet_analysis rotor6": lambda: _floquet("rotor6"),
    "floquet_analysis chain6": lambda: _floquet("chain6"),
    "floquet_campbell rotor6, 4 speeds": _campbell,
}


def sample(fn: Callable[[], object], loops: int) -> tuple[float, float]:
    """Thread CPU and wall time [s] per call of ``fn``, over ``loops`` calls."""
    c0, t0 = time.thread_time(), time.perf_counter()
    for _ in range(loops):
        fn()
    return (time.thread_time() - c0) / loops, (time.perf_counter() - t0) / loops


def serve(requests, out) -> None:
    """Answer each row name read from ``requests`` with one sample of its call and baseline, a JSON line on ``out``.

    A row that raises is answered with its traceback (``"error"``) instead; the other rows go on.
    """
    rows: dict[str, tuple[Timed, list[int]]] = {}
    for line in requests:
        name = line.strip()
        try:
            if name not in rows:
                timed = BUILDERS[name]()
                fns = [timed.call] + ([timed.baseline] if timed.baseline is not None else [])
                rows[name] = timed, [loops_for(fn, min_time=0.01, clock=time.thread_time) for fn in fns]
            timed, loops = rows[name]
            call = [t / timed.per for t in sample(timed.call, loops[0])]
            base = sample(timed.baseline, loops[1]) if timed.baseline is not None else None
            answer = {"row": name, "pinlin": pinlin.__file__, "info": timed.info, "call": call, "baseline": base}
        except Exception:  # noqa: BLE001 - reported to the parent, which marks the row failed on this side
            answer = {"row": name, "pinlin": pinlin.__file__, "error": traceback.format_exc(limit=-8)}
        out.write(json.dumps(answer) + "\n")
        out.flush()


if __name__ == "__main__":
    serve(sys.stdin, sys.stdout)
