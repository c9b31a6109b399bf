"""Instructions per call of ``modal_analysis`` and ``eig(left=True)`` under valgrind callgrind.

Run under callgrind with instrumentation off at start::

    OPENBLAS_NUM_THREADS=1 valgrind --tool=callgrind --instr-atstart=no \\
        --callgrind-out-file=/tmp/cg.%p python -m benchmarks.callgrind_modal [cases...]

Cases are names of :data:`benchmarks.bench_clusters.CASES` (default: the 8-branch chain and
talos_full_v2).  For each case: ``scipy.linalg.eig(A, B, left=True)`` of the companion pencil,
``modal_analysis`` (C and K formed afresh, as in ``bench_spectral.analyse``) and pinlin's
``dggev`` alone on the scaled companion pencil that modal_analysis factors; the same harness as
:mod:`benchmarks.callgrind_linearize` (counters zeroed and dumped around N and 2N calls,
differenced, GC off).  ``modal - dggev`` is the work around QZ: valgrind's emulated arithmetic
changes QZ's iteration count on exactly repeated spectra (the chain's QZ counts far more
instructions under callgrind than its thread time suggests), so that difference is the figure
that compares code changes outside LAPACK.
"""

from __future__ import annotations

import sys

import scipy.linalg as sla

from pinlin.spectral.problem import as_problem
from pinlin.spectral.qep import companion_pencil, dggev, scaled_companion

from .bench_clusters import CASES
from .bench_spectral import analyse
from .callgrind_linearize import instructions


def main(argv: list[str]) -> None:
    for name in argv or ["8-branch chain", "talos_full_v2"]:
        s = CASES[name]()
        A, B = companion_pencil(s.M, s.C, s.K)
        problem = as_problem(s)
        left = not problem.symmetric

        def qz():
            dggev(*scaled_companion(problem, problem.scaling), left=left)

        out = {
            "eig_left": instructions(lambda: sla.eig(A, B, left=True), 10),
            "modal": instructions(lambda: analyse(s), 10),
            "dggev": instructions(qz, 10),
        }
        out["modal-dggev"] = out["modal"] - out["dggev"]
        print(name, " ".join(f"{k}={v / 1e3:.1f}k" for k, v in out.items()), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
