"""Worker of ``bench_clusters``: modal_analysis timed with the BLAS thread settings of its environment.

Run as ``python -m benchmarks._threads_worker CASE REPEATS`` in a process whose
environment does not set OPENBLAS_NUM_THREADS (the default a user has: one
thread per core); prints one JSON line: medians of interleaved samples of
``modal_analysis`` with pinlin's small-kernel limit and without it
(``SMALL_KERNEL_ORDER`` set below every n), wall and thread CPU time [s], and
the BLAS thread counts seen.
"""

from __future__ import annotations

import json
import statistics
import sys
import time

import pinlin.numerics.threads as threads
from pinlin.numerics.threads import SMALL_KERNEL_ORDER, blas_threads

from .bench_clusters import CASES, analyse


def main(case: str, repeats: int) -> dict:
    sys_ = CASES[case]()
    for _ in range(3):
        analyse(sys_)
    samples: dict[str, list[tuple[float, float]]] = {"limited": [], "threaded": []}
    for _ in range(repeats):
        for label, out in samples.items():
            threads.SMALL_KERNEL_ORDER = SMALL_KERNEL_ORDER if label == "limited" else -1
            t0, c0 = time.perf_counter(), time.thread_time()
            analyse(sys_)
            out.append((time.perf_counter() - t0, time.thread_time() - c0))
    threads.SMALL_KERNEL_ORDER = SMALL_KERNEL_ORDER
    result = {"case": case, "blas_threads": blas_threads()}
    for label, out in samples.items():
        result[f"{label}_wall"] = statistics.median(s[0] for s in out)
        result[f"{label}_thread"] = statistics.median(s[1] for s in out)
        result[f"{label}_wall_max"] = max(s[0] for s in out)
    return result


if __name__ == "__main__":
    print(json.dumps(main(sys.argv[1], int(sys.argv[2]))))
