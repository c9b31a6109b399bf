"""Parameter sweeps behind root loci, stability maps and Campbell diagrams.

:func:`sweep` evaluates a function at every point of a parameter grid, in order,
on any :class:`concurrent.futures.Executor`: none (in this process), a thread or
process pool, or a cluster executor with the same interface (a Dask
``Client.get_executor()``, for instance).  The results do not depend on the
executor: each point is computed by the same function from the same arguments,
and the figures the sweep keeps about each point (its value's headline error,
its run time, its failure) are taken where the point ran, before its value
travels back (a process pool pickles values, which may drop figures).
"""

from __future__ import annotations

import itertools
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Executor, Future
from dataclasses import dataclass, field
from typing import Any, ClassVar, TextIO

import numpy as np

from ..errors import ParameterError, PinlinError
from ..results import Result

__all__ = ["sweep", "SweepResult", "SweepFailure", "PROGRESS_MIN_POINTS", "PROGRESS_WIDTH"]

#: A progress bar is shown by default only above this many points: shorter sweeps finish before one helps.
PROGRESS_MIN_POINTS = 20
#: Characters of the progress bar: fits an 80-column terminal with the counts and times beside it.
PROGRESS_WIDTH = 30


def _rebuild_exception(cls: type, args: tuple, state: dict) -> BaseException:
    """An exception restored without calling its ``__init__`` (whose signature may differ from ``args``)."""
    exc = cls.__new__(cls)
    exc.args = args
    exc.__dict__.update(state)
    return exc


@dataclass(frozen=True, repr=False, eq=False)
class SweepFailure(Result):
    """A point whose evaluation raised a :class:`~pinlin.PinlinError` (with ``on_error="record"``).

    Attributes
    ----------
    point : dict
        The parameters of the point.
    exception : PinlinError
        What the function raised (it survives a process pool: pickled with its
        attributes, without calling its constructor again).
    method : str
        The function and the exception type, e.g. ``"pendulum(**point) raised ParameterError"``.
    elapsed : float
        Wall time [s] of the failed call, measured where it ran.
    error : None
        A failed point computed no value, so it has no error figure.
    """

    point: Mapping[str, Any]
    exception: PinlinError
    method: str = ""
    elapsed: float = 0.0

    error: ClassVar[None] = None

    def __repr__(self) -> str:
        return f"SweepFailure({dict(self.point)}, {type(self.exception).__name__}: {self.exception})"

    def __reduce__(self):
        exc = self.exception
        rebuilt = (_rebuild_exception, (type(exc), exc.args, dict(exc.__dict__)))
        return (_rebuild_failure, (dict(self.point), rebuilt, self.method, self.elapsed))

    def to_dict(self) -> dict[str, Any]:
        """The failure as JSON-serializable data; the exception as its type name and message."""
        out = super().to_dict()
        out["exception"] = {"type": type(self.exception).__name__, "message": str(self.exception)}
        return out


def _rebuild_failure(point, rebuilt, method, elapsed) -> SweepFailure:
    function, args = rebuilt
    return SweepFailure(point, function(*args), method, elapsed)


@dataclass(frozen=True, repr=False, eq=False)
class SweepResult(Result):
    """Values of a function over a parameter grid, in grid order.

    Attributes
    ----------
    names : tuple of str
        Parameter names.
    points : list of dict
        Every point, in order (the last name varies fastest for a grid).
    values : list
        ``function(**point)`` for each point, or a :class:`SweepFailure`.
    shape : tuple of int
        Grid shape (one axis per name), or ``(len(points),)`` for an explicit list.
    axes : dict of str to ndarray
        The values along each axis of a grid.
    elapsed : float
        Wall time [s] of the whole sweep.
    method : str
        The function, the number of points and where they ran.
    point_errors : tuple of float or None
        Per point, the headline ``.error`` of its value when the value is a
        pinlin result (:class:`pinlin.results.Result`), else None; None for a
        failed point.
    point_elapsed : tuple of float
        Per point, the wall time [s] of its call, measured where it ran.
    error : float or None
        The largest of ``point_errors`` (each in the meaning its result type
        documents, relative unless documented otherwise; NaN if one of them is
        NaN); None when no value carries an error figure (the function returned
        plain arrays or numbers, or every point failed).
    """

    names: tuple[str, ...]
    points: list[dict[str, Any]]
    values: list[Any]
    shape: tuple[int, ...]
    axes: dict[str, np.ndarray] = field(default_factory=dict)
    elapsed: float = 0.0
    method: str = ""
    point_errors: tuple[float | None, ...] = ()
    point_elapsed: tuple[float, ...] = ()

    @property
    def error(self) -> float | None:
        figures = [e for e in self.point_errors if e is not None]
        return float(np.max(figures)) if figures else None

    @property
    def failures(self) -> list[SweepFailure]:
        """The failed points (``on_error="record"``), in grid order."""
        return [v for v in self.values if isinstance(v, SweepFailure)]

    def __repr__(self) -> str:
        if self.axes:
            grid = " x ".join(f"{name}[{len(values)}]" for name, values in self.axes.items())
        else:
            grid = f"list over {', '.join(self.names)}"
        error = "none" if self.error is None else f"{self.error:.2e}"
        return (
            f"SweepResult({len(self.points)} points, {grid}, {len(self.failures)} failed, "
            f"error={error}, elapsed={self.elapsed:.3g} s)"
        )

    def to_dict(self) -> dict[str, Any]:
        """The sweep as JSON-serializable data: every point's value through its own ``to_dict`` when it has one."""
        out = super().to_dict()
        out["failures"] = len(self.failures)
        return out

    def collect(self, extract: Callable[[Any], Any] | None = None, fill=np.nan) -> np.ndarray:
        """Stack ``extract(value)`` over the points into an array of shape ``shape + value shape``.

        Failed points are filled with ``fill``.

        Raises
        ------
        ParameterError
            Every point failed, or two points gave values of different shapes.
        """
        extract = extract or (lambda v: v)
        items = [None if isinstance(v, SweepFailure) else np.asarray(extract(v)) for v in self.values]
        template = next((x for x in items if x is not None), None)
        if template is None:
            raise ParameterError("collect", "every point of the sweep failed; nothing to collect")
        out = np.full((len(items),) + template.shape, fill, dtype=np.result_type(template.dtype, type(fill)))
        for i, x in enumerate(items):
            if x is not None:
                if x.shape != template.shape:
                    raise ParameterError(
                        "collect", f"point {i} gave shape {x.shape}, the first gave {template.shape}"
                    )
                out[i] = x
        return out.reshape(self.shape + template.shape)


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


class _Progress:
    """A dependency-free text progress bar on a stream (stderr by default)."""

    def __init__(self, total: int, stream: TextIO | None, enabled: bool):
        self.total, self.stream, self.enabled = total, stream or sys.stderr, enabled
        self.done = 0
        self.t0 = time.perf_counter()

    def step(self) -> None:
        self.done += 1
        if not self.enabled:
            return
        filled = int(PROGRESS_WIDTH * self.done / self.total)
        elapsed = time.perf_counter() - self.t0
        eta = elapsed / self.done * (self.total - self.done)
        self.stream.write(
            f"\rsweep [{'#' * filled}{'.' * (PROGRESS_WIDTH - filled)}] {self.done}/{self.total} "
            f"{elapsed:.1f} s elapsed, ~{eta:.1f} s left"
        )
        if self.done == self.total:
            self.stream.write("\n")
        self.stream.flush()


def _headline_error(value) -> float | None:
    """The ``.error`` of a pinlin result as a float; None for anything else."""
    if not isinstance(value, Result) or isinstance(value, SweepFailure):
        return None
    error = getattr(value, "error", None)
    if isinstance(error, (bool, np.bool_)) or not isinstance(error, (int, float, np.integer, np.floating)):
        return None
    return float(error)


def _name(function: Callable) -> str:
    return getattr(function, "__qualname__", None) or getattr(function, "__name__", None) or repr(function)


def _call(function: Callable, point: dict) -> tuple[Any, float | None, float]:
    """``function(**point)`` with its figures taken here, where it ran: (value or failure, error, elapsed [s])."""
    t0 = time.perf_counter()
    try:
        value = function(**point)
    except PinlinError as exc:
        elapsed = time.perf_counter() - t0
        return SweepFailure(point, exc, f"{_name(function)}(**point) raised {type(exc).__name__}", elapsed), None, elapsed
    return value, _headline_error(value), time.perf_counter() - t0


def _run(function: Callable, points: list[dict], executor: Executor | None, bar: _Progress, on_error: str) -> list:
    """The (value, error, elapsed) of every point, in grid order; the first failure raised with ``on_error="raise"``."""
    out: list = []

    def keep(item) -> None:
        if on_error == "raise" and isinstance(item[0], SweepFailure):
            raise item[0].exception
        out.append(item)
        bar.step()

    if executor is None:
        for point in points:
            keep(_call(function, point))
        return out
    futures: list[Future] = [executor.submit(_call, function, point) for point in points]
    try:
        for future in futures:
            keep(future.result())
    finally:
        for future in futures:
            future.cancel()
    return out


def sweep(
    function: Callable[..., Any],
    grid: Mapping[str, Sequence] | Sequence[Mapping[str, Any]],
    *,
    executor: Executor | None = None,
    progress: bool | None = None,
    stream: TextIO | None = None,
    on_error: str = "raise",
) -> SweepResult:
    """Evaluate ``function(**point)`` at every point of a parameter grid.

    Parameters
    ----------
    function : callable
        Builds and analyses one scene from keyword parameters and returns what is
        to be kept (eigenvalues, a verdict, a result object).  For a process
        pool it must be picklable: a module-level function.
    grid : mapping of str to sequence, or sequence of dicts
        A mapping gives the Cartesian product of its axes (the last name varies
        fastest); a sequence gives the points themselves.
    executor : concurrent.futures.Executor, optional
        Where to run the points: None runs them here, one after the other; a
        ``ThreadPoolExecutor``, a ``ProcessPoolExecutor`` or any object with the
        Executor interface (``submit`` returning futures) runs them there.
        Results come back in grid order whatever the completion order, and do
        not depend on the executor.
    progress : bool, optional
        Show a text progress bar; default: only for more than
        :data:`PROGRESS_MIN_POINTS` points.
    stream : text stream, optional
        Where the progress bar goes (default stderr).
    on_error : {"raise", "record"}
        What a :class:`~pinlin.PinlinError` at one point does: stop the sweep
        (the first failing point in grid order raises its exception here), or
        become a :class:`SweepFailure` in ``values`` (for maps that cross the
        edge of where a scene is defined).

    Returns
    -------
    SweepResult
        ``error`` is the largest headline error of the values that are pinlin
        results (None when none is).

    Raises
    ------
    ParameterError
        An empty or malformed grid, a ``function`` that is not callable, an
        executor without ``submit``, an unknown ``on_error``.
    PinlinError
        Whatever ``function`` raised at the first failing point, with
        ``on_error="raise"``.
    """
    t0 = time.perf_counter()
    if not callable(function):
        raise ParameterError("function", f"expected a callable, got {function!r}")
    if on_error not in ("raise", "record"):
        raise ParameterError("on_error", f"expected 'raise' or 'record', got {on_error!r}")
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise ParameterError("executor", f"expected a concurrent.futures.Executor, got {executor!r}")
    names, points, shape, axes = _points(grid)
    enabled = len(points) > PROGRESS_MIN_POINTS if progress is None else bool(progress)
    items = _run(function, points, executor, _Progress(len(points), stream, enabled), on_error)
    where = "in this process" if executor is None else f"on a {type(executor).__name__}"
    kind = "grid" if axes else "list"
    method = f"{_name(function)}(**point) at {len(points)} points of a {kind} over {', '.join(names)}, {where}"
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
