"""Instructions per call of ``linearize`` and its baselines under valgrind callgrind.

Run under callgrind with instrumentation off at start::

    OPENBLAS_NUM_THREADS=1 valgrind --tool=callgrind --instr-atstart=no \\
        --callgrind-out-file=/tmp/cg.%p python -m benchmarks.callgrind_linearize [--baselines] [rows...]

For each row (double_pendulum, ur5, panda, solo12, talos, turntable) and each measured
function, instrumentation is switched on, counters zeroed (``callgrind_control -z``) and
dumped (``-d``) around N and 2N calls, and the difference divided by N: the control
calls cancel.  Cyclic GC is off in the window.  ``linearize`` and the floor: N = 20;
``linearize_many`` on 100 points: N = 2 (per point: divided by 100).  ``--baselines``
adds the Python lower bound and the leanest central differences (they do not depend on
pinlin's linearization code).  Prints one line per row; instruction counts are
independent of the machine's load.
"""

from __future__ import annotations

import gc
import glob
import os
import subprocess
import sys

import numpy as np
import pinocchio as pin

import pinlin
from pinlin.linearization.plan import plan_of

from .bench_linearize import (
    bare_differences,
    double_pendulum_case,
    panda_case,
    pinocchio_floor,
    solo_case,
    talos_case,
    turntable_case,
    ur5_case,
)

ROWS = {
    "double_pendulum": double_pendulum_case,
    "ur5": ur5_case,
    "panda": panda_case,
    "solo12": solo_case,
    "talos": talos_case,
    "turntable": turntable_case,
}


def _control(flag: str) -> None:
    subprocess.run(["callgrind_control", *flag.split(), str(os.getpid())], check=True, capture_output=True)


def _last_dump_instructions() -> int:
    """Ir of the newest dump file of this process."""
    files = glob.glob(f"/tmp/cg.{os.getpid()}.*")
    newest = max(files, key=lambda f: int(f.rsplit(".", 1)[1]))
    with open(newest) as fh:
        for line in fh:
            if line.startswith("summary:") or line.startswith("totals:"):
                return int(line.split()[1])
    raise RuntimeError(f"no totals in {newest}")


def instructions(run, n: int) -> float:
    """Instructions per call of ``run``: (count of 2n calls - count of n calls) / n."""
    for _ in range(3):
        run()
    counts = []
    _control("-i on")
    for calls in (n, 2 * n):
        gc.disable()
        _control("-z")
        for _ in range(calls):
            run()
        _control("-d")
        gc.enable()
        counts.append(_last_dump_instructions())
    _control("-i off")
    return (counts[1] - counts[0]) / n


def lower_bound(scene: pinlin.Scene, q: np.ndarray, calls) -> callable:
    """The cheapest Python function returning the floor's matrices from its Pinocchio calls.

    The derivative call, ``crba`` (at rest), the free block of each (copies), zero matrices
    for the rest, returned bare: no element, check, split, error figure or result object.
    """
    model = scene.model
    data = model.createData()
    block, n, names = plan_of(scene).block, plan_of(scene).n, scene.dof_names
    v0, zero, fext = scene.v0, np.zeros(model.nv), scene.constant_fext
    extra = () if fext is None else (fext,)
    if "computeRNEADerivatives" in calls:
        def run():
            dq, dv, Mu = pin.computeRNEADerivatives(model, data, q, v0, zero, *extra)
            return Mu[block].copy(), dv[block].copy(), dq[block].copy(), names, q.copy(), v0
        return run
    derivative = pin.computeStaticTorqueDerivatives if fext is not None else pin.computeGeneralizedGravityDerivatives

    def run():
        K = derivative(model, data, q, *extra)
        M = pin.crba(model, data, q)
        return M[block].copy(), np.zeros((n, n)), K[block].copy(), names, q.copy(), v0

    return run


def main(argv: list[str]) -> None:
    baselines = "--baselines" in argv
    rows = [a for a in argv if not a.startswith("--")] or list(ROWS)
    for name in rows:
        case = ROWS[name]()
        scene, q = case.scene, case.q
        sys_ = pinlin.linearize(scene, q, balancing=case.balancing)
        qs = np.tile(q, (100, 1))
        out = {
            "floor": instructions(pinocchio_floor(scene, q, sys_.calls), 20),
            "linearize": instructions(lambda: pinlin.linearize(scene, q, balancing=case.balancing), 20),
            "many100": instructions(lambda: pinlin.linearize_many(scene, qs, balancing=case.balancing), 2) / 100,
        }
        if baselines:
            out["lower"] = instructions(lower_bound(scene, q, sys_.calls), 20)
            out["fd"] = instructions(bare_differences(scene, q, 1e-5), 4 if name == "talos" else 10)
        print(name, " ".join(f"{k}={v / 1e3:.1f}k" for k, v in out.items()), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
