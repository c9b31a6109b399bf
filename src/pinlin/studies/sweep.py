"""Parameter sweeps behind root loci, stability maps and Campbell diagrams.

:func:`sweep` evaluates a function at every point of a parameter grid, in order,
on any :class:`concurrent.futures.Executor`: none (in this process), a thread or
process pool, or a cluster executor with the same interface (a Dask
``Client.get_executor()``, for instance).  The results do not depend on the
executor: each point is computed by the same function from the same arguments.
"""

from __future__ import annotations

import itertools
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Executor, Future
from dataclasses import dataclass, field
from typing import Any, TextIO

import numpy as np

from ..errors import ParameterError, PinlinError

__all__ = ["sweep", "SweepResult", "SweepFailure"]


@dataclass(frozen=True)
class SweepFailure:
    """A point whose evaluation raised a :class:`~pinlin.PinlinError` (with ``on_error="record"``)."""

    point: Mapping[str, Any]
    error: PinlinError

    def __repr__(self) -> str:
        return f"SweepFailure({dict(self.point)}, {type(self.error).__name__}: {self.error})"


@dataclass(frozen=True)
class SweepResult:
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
        Wall time [s].
    """

    names: tuple[str, ...]
    points: list[dict[str, Any]]
    values: list[Any]
    shape: tuple[int, ...]
    axes: dict[str, np.ndarray] = field(default_factory=dict)
    elapsed: float = 0.0

    @property
    def failures(self) -> list[SweepFailure]:
        return [v for v in self.values if isinstance(v, SweepFailure)]

    def collect(self, extract: Callable[[Any], Any] | None = None, fill=np.nan) -> np.ndarray:
        """Stack ``extract(value)`` over the points into an array of shape ``shape + value shape``.

        Failed points are filled with ``fill``.
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
        width = 30
        filled = int(width * self.done / self.total)
        elapsed = time.perf_counter() - self.t0
        eta = elapsed / self.done * (self.total - self.done)
        self.stream.write(
            f"\rsweep [{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} "
            f"{elapsed:.1f} s elapsed, ~{eta:.1f} s left"
        )
        if self.done == self.total:
            self.stream.write("\n")
        self.stream.flush()


def _call(function: Callable, point: dict, on_error: str):
    try:
        return function(**point)
    except PinlinError as exc:
        if on_error == "record":
            return SweepFailure(point, exc)
        raise


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
        Results come back in grid order whatever the completion order.
    progress : bool, optional
        Show a text progress bar; default: only for more than 20 points.
    stream : text stream, optional
        Where the progress bar goes (default stderr).
    on_error : {"raise", "record"}
        What a :class:`~pinlin.PinlinError` at one point does: stop the sweep,
        or become a :class:`SweepFailure` in ``values`` (for maps that cross the
        edge of where a scene is defined).

    Returns
    -------
    SweepResult

    Raises
    ------
    ParameterError
        An empty or malformed grid, an executor without ``submit``, an unknown
        ``on_error``.
    """
    t0 = time.perf_counter()
    if not callable(function):
        raise ParameterError("function", f"expected a callable, got {function!r}")
    if on_error not in ("raise", "record"):
        raise ParameterError("on_error", f"expected 'raise' or 'record', got {on_error!r}")
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise ParameterError("executor", f"expected a concurrent.futures.Executor, got {executor!r}")
    names, points, shape, axes = _points(grid)
    bar = _Progress(len(points), stream, len(points) > 20 if progress is None else bool(progress))
    values: list[Any] = [None] * len(points)
    if executor is None:
        for i, point in enumerate(points):
            values[i] = _call(function, point, on_error)
            bar.step()
    else:
        futures: list[Future] = [executor.submit(_call, function, point, on_error) for point in points]
        try:
            for i, future in enumerate(futures):
                values[i] = future.result()
                bar.step()
        finally:
            for future in futures:
                future.cancel()
    return SweepResult(names, points, values, shape, axes, time.perf_counter() - t0)
