"""One BLAS thread for small dense kernels.

OpenBLAS starts as many threads as there are cores and uses them from small
sizes on.  For the matrices of a modal analysis of a robot (n up to a few
hundred) the threads gain little on an idle machine and lose a great deal on a
busy one: a thread that waits for a core spins, and the calling thread waits
for it (talos_full_v2, n = 44: 16 ms alone, 0.5-1.3 s with a second process on
one of two cores).  :func:`small_kernels` runs a block with one BLAS thread,
through threadpoolctl (the library scikit-learn uses for exactly this), with
its controller built once per process (building one inspects every loaded
shared library: about 0.8 ms; entering and leaving the limit then costs about
4 us).

The limit is process-wide (OpenBLAS has one thread count) and is applied on
the main thread only: OpenBLAS 0.3.31 ignores a raise of the count requested
from another thread after the main thread lowered it, so a count lowered and
restored there could stay at one for the rest of the process (measured; see
tests/numerics/test_blas_threads.py).  Blocks nest; the outermost restores the counts
it found.  BLAS calls of other Python threads made meanwhile also run on one
thread; results do not change (OpenBLAS partitions the output of a product
among its threads, not its sums: results are bitwise those of the threaded
call, which tests/golden and tests/numerics/test_blas_threads.py check).
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["SMALL_KERNEL_ORDER", "small_kernels", "blas_threads"]

#: Largest order n of a quadratic eigenproblem whose analysis runs on one BLAS
#: thread.  Its largest dense kernel is the QZ of the 2n companion pencil.  On
#: this project's 2-core machine under a load of 3-3.6 (benchmarks/notes/spectral.md)
#: two threads gave modal_analysis of a 100-link chain 35 ms against 42 ms wall
#: (more CPU: 33 against 30 ms) and of a 200-link chain 1009 ms against 662 ms.
SMALL_KERNEL_ORDER = 200

_depth = 0
_saved: list[tuple[object, int]] = []


@functools.cache
def _blas_libraries() -> tuple:
    """threadpoolctl's controllers of the BLAS libraries loaded (numpy's and scipy's OpenBLAS), built once."""
    import scipy.linalg  # noqa: F401  (its BLAS must be loaded before the libraries are listed)
    from threadpoolctl import ThreadpoolController

    return tuple(lib for lib in ThreadpoolController().lib_controllers if lib.user_api == "blas")


def blas_threads() -> tuple[int, ...]:
    """The thread count of each loaded BLAS library, as they are now."""
    return tuple(lib.get_num_threads() for lib in _blas_libraries())


@contextmanager
def small_kernels(order: int) -> Iterator[None]:
    """Run the block with one BLAS thread when ``order`` <= :data:`SMALL_KERNEL_ORDER` (else unchanged).

    On a thread other than the main one the block runs unchanged (see the module doc).

    Parameters
    ----------
    order : int
        The size n of the problem whose kernels the block runs.
    """
    global _depth
    if order > SMALL_KERNEL_ORDER or threading.current_thread() is not threading.main_thread():
        yield
        return
    if _depth == 0:
        _saved[:] = [(lib, lib.get_num_threads()) for lib in _blas_libraries()]
        for lib, count in _saved:
            if count != 1:
                lib.set_num_threads(1)
    _depth += 1
    try:
        yield
    finally:
        _depth -= 1
        if _depth == 0:
            for lib, count in _saved:
                if count != 1:
                    lib.set_num_threads(count)
            _saved.clear()
