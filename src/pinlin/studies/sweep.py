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
which points finish; the values come back in grid order.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Executor
from typing import Any, TextIO

import numpy as np

from ..errors import ParameterError
from .progress import PROGRESS_MIN_POINTS, PROGRESS_WIDTH, progress_bar
from .scheduling import function_name, run_points
from .sweep_result import SweepFailure, SweepResult

__all__ = ["sweep", "SweepResult", "SweepFailure", "PROGRESS_MIN_POINTS", "PROGRESS_WIDTH"]


def _points(grid) -> tuple[tuple[str, ...], list[dict], tuple[int, ...], dict]:
    if isinstance(grid, Mapping):
        if not grid:
            raise ParameterError("grid", "no parameters to sweep")
        names = tuple(grid)
        axes = {}
        for name in names:
            values = grid[name]
            if isinstance(values, (str, bytes)) or not isinstance(values, (Sequence, np.ndarray)):
                raise ParameterError(f"grid[{name!r}]", f"expected a sequence of values, got {values!r}")
            if len(values) == 0:
                raise ParameterError(f"grid[{name!r}]", "has no values")
            axes[name] = np.asarray(values)
        points = [dict(zip(names, combo)) for combo in itertools.product(*(grid[n] for n in names))]
        return names, points, tuple(len(grid[n]) for n in names), axes
    if isinstance(grid, (str, bytes)) or not isinstance(grid, Sequence) or not grid:
        raise ParameterError("grid", "expected a mapping name -> values, or a non-empty sequence of dicts")
    points = []
    for i, point in enumerate(grid):
        if not isinstance(point, Mapping):
            raise ParameterError(f"grid[{i}]", f"expected a dict of parameters, got {point!r}")
        points.append(dict(point))
    names = tuple(dict.fromkeys(k for p in points for k in p))
    return names, points, (len(points),), {}


def sweep(
    function: Callable[..., Any],
    grid: Mapping[str, Sequence] | Sequence[Mapping[str, Any]],
    *,
    executor: Executor | None = None,
    progress: bool | str | None = None,
    stream: TextIO | None = None,
    on_error: str = "raise",
    callback: Callable[[int, dict, Any], None] | None = None,
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

    Returns
    -------
    SweepResult
        ``error`` is the largest headline error of the values that are pinlin
        results (None when none is).

    Raises
    ------
    ParameterError
        An empty or malformed grid, a ``function`` or ``callback`` that is not
        callable, an executor without ``submit``, an unknown ``on_error`` or ``progress``.
    MissingDependencyError
        ``progress="tqdm"`` without tqdm installed.
    PinlinError
        Whatever ``function`` raised at the first failing point, with
        ``on_error="raise"``.
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
    names, points, shape, axes = _points(grid)
    bar = progress_bar(len(points), progress, stream)

    def report(index: int, item) -> None:
        if bar is not None:
            bar.update(1)
        if callback is not None:
            callback(index, points[index], item[0])

    try:
        items = run_points(function, points, executor, report, on_error)
    finally:
        if bar is not None:
            bar.close()
    where = "in this process" if executor is None else f"on a {type(executor).__name__}"
    kind = "grid" if axes else "list"
    method = f"{function_name(function)}(**point) at {len(points)} points of a {kind} over {', '.join(names)}, {where}"
    return SweepResult(
        names,
        points,
        [value for value, _, _ in items],
        shape,
        axes,
        time.perf_counter() - t0,
        method,
        tuple(error for _, error, _ in items),
        tuple(elapsed for _, _, elapsed in items),
    )
