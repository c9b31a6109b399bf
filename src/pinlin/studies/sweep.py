"""Parameter sweeps behind root loci, stability maps and Campbell diagrams.

:func:`sweep` evaluates a function at every point of a parameter grid on any
:class:`concurrent.futures.Executor`: none (in this process), a thread or
process pool, or a cluster executor with the same interface (a Dask
``Client.get_executor()``, :class:`~pinlin.studies.RayExecutor` for Ray).
The results do not depend on the executor: each point is computed by the same
function from the same arguments, and the figures the sweep keeps about each
point (its value's headline error, its run time, its failure) are taken where
the point ran, before its value travels back (a process pool pickles values,
which may drop figures).  Progress (a bar, a callback) follows the order in
which points finish; the values come back in grid order.  On an executor the
points are submitted in chunks (several points per task, :func:`chunk_size_for`),
so that submitting and pickling cost little against the points themselves.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Executor
from typing import Any, TextIO

import numpy as np

from ..errors import ParameterError, SweepTimeoutError
from .grid import MAX_POINTS, grid_points
from .progress import PROGRESS_MIN_POINTS, PROGRESS_WIDTH, progress_bar
from .scheduling import call_point, function_name, run_points
from .sweep_result import SweepFailure, SweepResult

__all__ = [
    "sweep",
    "SweepResult",
    "SweepFailure",
    "SweepTimeoutError",
    "chunk_size_for",
    "CHUNKS_PER_WORKER",
    "MAX_POINTS",
    "PROGRESS_MIN_POINTS",
    "PROGRESS_WIDTH",
]


#: Chunks per worker of the automatic chunk size: uneven point costs leave a worker at most
#: about one chunk (an eighth of its share) behind the others, while the cost of submitting
#: and pickling tasks falls by the chunk size.
CHUNKS_PER_WORKER = 8


def _workers(executor) -> int:
    """The number of workers an executor runs at once (its ``_max_workers``, a Dask client's threads)."""
    for name in ("_max_workers", "max_workers"):
        value = getattr(executor, name, None)
        if isinstance(value, int) and value > 0:
            return value
    client = getattr(executor, "_client", None)  # Dask's ClientExecutor
    nthreads = getattr(client, "nthreads", None)
    if callable(nthreads):
        try:
            return max(1, int(sum(nthreads().values())))
        except (TypeError, ValueError, AttributeError, OSError):
            pass  # an executor that cannot say: the machine's processors below
    return os.cpu_count() or 1


def chunk_size_for(points: int, executor: Executor, chunk_size: int | None = None) -> int:
    """Points per submitted task: ``chunk_size`` when given, else ceil(points / (workers * CHUNKS_PER_WORKER)).

    Raises
    ------
    ParameterError
        ``chunk_size`` is not a positive integer.

    Examples
    --------
    >>> from concurrent.futures import ThreadPoolExecutor
    >>> from pinlin.studies.sweep import chunk_size_for
    >>> with ThreadPoolExecutor(max_workers=2) as executor:
    ...     chunk_size_for(100, executor), chunk_size_for(100, executor, chunk_size=10)
    (7, 10)
    """
    if chunk_size is not None:
        if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
            raise ParameterError("chunk_size", f"expected a positive integer, got {chunk_size!r}")
        return int(chunk_size)
    return max(1, -(-points // (_workers(executor) * CHUNKS_PER_WORKER)))


def _call_chunk(function: Callable, points: list, stop_on_error: bool) -> list:
    """Each point of a chunk as :func:`~pinlin.studies.scheduling.call_point` gives it, where the chunk runs.

    With ``stop_on_error`` the first failure is raised (the chunk fails as one
    task, so the scheduler cancels the chunks after it, as it does points).
    """
    out = []
    for point in points:
        item = call_point(function, point)
        if stop_on_error and isinstance(item[0], SweepFailure):
            raise item[0].exception
        out.append(item)
    return out


def _run_chunks(function, points, executor, size, report, on_error, timeout) -> list:
    """:func:`run_points` over chunks of ``size`` points; items and reports per point, in grid order."""
    starts = range(0, len(points), size)
    chunks = [{"function": function, "points": points[i : i + size], "stop_on_error": on_error == "raise"}
              for i in starts]

    def chunk_report(index: int, item) -> None:
        for j, point_item in enumerate(item[0]):
            report(index * size + j, point_item)

    try:
        done = run_points(_call_chunk, chunks, executor, chunk_report, on_error, timeout)
    except SweepTimeoutError as exc:  # name the points, not the chunks
        pending = [i for chunk in exc.pending for i in range(chunk * size, min((chunk + 1) * size, len(points)))]
        raise SweepTimeoutError(timeout, pending, [points[i] for i in pending]) from None
    return [point_item for chunk_items, _, _ in done for point_item in chunk_items]


def sweep(
    function: Callable[..., Any],
    grid: Mapping[str, Sequence] | Sequence[Mapping[str, Any]],
    *,
    executor: Executor | None = None,
    progress: bool | str | None = None,
    stream: TextIO | None = None,
    on_error: str = "raise",
    callback: Callable[[int, dict, Any], None] | None = None,
    chunk_size: int | None = None,
    max_points: int | None = MAX_POINTS,
    timeout: float | None = None,
) -> SweepResult:
    """Evaluate ``function(**point)`` at every point of a parameter grid.

    Parameters
    ----------
    function : callable
        Builds and analyses one scene from keyword parameters and returns what is
        to be kept (eigenvalues, a verdict, a result object).  For a process
        pool or a cluster it must be picklable: a module-level function.
    grid : mapping of str to sequence, or sequence of dicts
        A mapping gives the Cartesian product of its axes (the last name varies
        fastest); a sequence gives the points themselves.
    executor : concurrent.futures.Executor, optional
        Where to run the points: None runs them here, one after the other; a
        ``ThreadPoolExecutor``, a ``ProcessPoolExecutor``, a Dask
        ``Client.get_executor()``, a :class:`~pinlin.studies.RayExecutor` or any
        object with the Executor interface (``submit`` returning
        ``concurrent.futures.Future``) runs them there.  Results come back in
        grid order whatever the completion order, and do not depend on the executor.
    progress : bool, "text" or "tqdm", optional
        A progress bar advanced as points finish (in completion order): True uses
        tqdm when installed, else a text bar; ``"text"`` or ``"tqdm"`` chooses;
        default: a bar only for more than :data:`PROGRESS_MIN_POINTS` points.
    stream : text stream, optional
        Where the progress bar goes (default stderr).
    on_error : {"raise", "record"}
        What a :class:`~pinlin.PinlinError` at one point does: stop the sweep
        (the first failing point in grid order raises its exception here; the
        points after it are cancelled), or become a :class:`SweepFailure` in
        ``values`` (for maps that cross the edge of where a scene is defined).
    callback : callable, optional
        ``callback(index, point, value)``, called in this thread as each point
        finishes, in completion order (``index`` into ``points``; ``value`` a
        :class:`SweepFailure` for a recorded failure).  What it raises stops the
        sweep and propagates.
    chunk_size : int, optional
        Points per task submitted to the executor (default: chosen from the number
        of points and the executor's workers, :func:`chunk_size_for`, 1 for short
        sweeps).  Fewer, larger tasks cost less submission and pickling; progress
        and callbacks then advance a chunk at a time (its points in grid order).
    max_points : int or None
        Most points the grid may have (default :data:`MAX_POINTS`, the command
        line's cap), checked before any point is built or run: a grid is iterated
        lazily, so a mistyped grid of 10^9 points is refused at once.  None: no cap.
    timeout : float, optional
        Seconds to wait on an executor for all points to finish (default: no
        limit).  Points still unfinished then are cancelled and
        :class:`~pinlin.studies.SweepTimeoutError` names them.  Ignored without
        an executor (the points run here, one after the other).

    Returns
    -------
    SweepResult
        ``error`` is the largest headline error of the values that are pinlin
        results (None when none is).

    Raises
    ------
    ParameterError
        An empty or malformed grid, a ``function`` or ``callback`` that is not
        callable, an executor without ``submit``, an unknown ``on_error`` or ``progress``,
        a ``chunk_size`` that is not a positive integer, a parameter name that is
        not a string, more than ``max_points`` points, a ``timeout`` that is not
        a positive number, an executor whose ``submit`` returns something other
        than a ``concurrent.futures.Future``.
    SweepTimeoutError
        Points not finished within ``timeout`` seconds (``.pending``, ``.points``).
    MissingDependencyError
        ``progress="tqdm"`` without tqdm installed.
    PinlinError
        Whatever ``function`` raised at the first failing point, with
        ``on_error="raise"``.

    Examples
    --------
    The natural frequency of x'' m + 4 x = 0 over the mass:

    >>> def omega(m):
    ...     sys = pinlin.LinearizedSystem.from_matrices([[m]], None, [[4.0]])
    ...     return float(np.max(pinlin.modal_analysis(sys).eigenvalues.imag))
    >>> result = pinlin.sweep(omega, {"m": [1.0, 4.0, 16.0]})
    >>> np.round(result.collect(), 6), result.points[1]
    (array([2. , 1. , 0.5]), {'m': 4.0})
    """
    t0 = time.perf_counter()
    if not callable(function):
        raise ParameterError("function", f"expected a callable, got {function!r}")
    if callback is not None and not callable(callback):
        raise ParameterError("callback", f"expected a callable (index, point, value), got {callback!r}")
    if on_error not in ("raise", "record"):
        raise ParameterError("on_error", f"expected 'raise' or 'record', got {on_error!r}")
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise ParameterError("executor", f"expected a concurrent.futures.Executor, got {executor!r}")
    if timeout is not None and (isinstance(timeout, bool) or not isinstance(timeout, (int, float, np.integer, np.floating))
                                or not timeout > 0 or not np.isfinite(timeout)):
        raise ParameterError("timeout", f"expected a positive number of seconds or None, got {timeout!r}")
    names, points, shape, axes = grid_points(grid, max_points)
    bar = progress_bar(len(points), progress, stream)

    def report(index: int, item) -> None:
        if bar is not None:
            bar.update(1)
        if callback is not None:
            callback(index, points[index], item[0])

    size = 1 if executor is None else chunk_size_for(len(points), executor, chunk_size)
    try:
        if size == 1:
            items = run_points(function, points, executor, report, on_error, timeout)
        else:
            items = _run_chunks(function, points, executor, size, report, on_error, timeout)
    finally:
        if bar is not None:
            bar.close()
    where = "in this process" if executor is None else f"on a {type(executor).__name__}"
    if size > 1:
        where += f" in chunks of {size} points"
    kind = "grid" if axes else "list"
    method = f"{function_name(function)}(**point) at {len(points)} points of a {kind} over {', '.join(names)}, {where}"
    return SweepResult(
        names,
        list(points),
        [value for value, _, _ in items],
        shape,
        axes,
        time.perf_counter() - t0,
        method,
        tuple(error for _, error, _ in items),
        tuple(elapsed for _, _, elapsed in items),
    )
