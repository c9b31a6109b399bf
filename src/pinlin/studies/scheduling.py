"""Running the points of a sweep: here, or on any executor, taking each point's figures where it ran.

Each point is one call ``function(**point)`` wrapped by :func:`call_point`,
which measures the call and reads its value's headline error where the point
ran (before a process pool or a cluster pickles the value, which may drop
figures), and turns a :class:`~pinlin.PinlinError` into a
:class:`~pinlin.studies.SweepFailure`.  :func:`run_points` collects the points
in **completion order** (``concurrent.futures.as_completed``), so progress
reports never wait behind one slow early point, and returns them in grid order.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from concurrent.futures import CancelledError, Executor, Future, as_completed
from concurrent.futures import TimeoutError as FuturesTimeout
from typing import Any

import numpy as np

from ..errors import ParameterError, PinlinError, SweepTimeoutError
from ..results import Result
from .sweep_result import SweepFailure

__all__ = ["call_point", "run_points", "function_name"]

#: (value or failure, headline error or None, elapsed [s]) of one point.
Item = tuple[Any, "float | None", float]


def function_name(function: Callable) -> str:
    """The qualified name of a callable, for ``method`` strings.

    Examples
    --------
    >>> from pinlin.studies.scheduling import function_name
    >>> function_name(np.linalg.norm)
    'norm'
    """
    return getattr(function, "__qualname__", None) or getattr(function, "__name__", None) or repr(function)


def headline_error(value) -> float | None:
    """The ``.error`` of a pinlin result as a float; None for anything else."""
    if not isinstance(value, Result) or isinstance(value, SweepFailure):
        return None
    error = getattr(value, "error", None)
    if isinstance(error, (bool, np.bool_)) or not isinstance(error, (int, float, np.integer, np.floating)):
        return None
    return float(error)


def call_point(function: Callable, point: dict) -> Item:
    """``function(**point)`` with its figures taken here, where it ran: (value or failure, error, elapsed [s]).

    Examples
    --------
    >>> from pinlin.studies.scheduling import call_point
    >>> value, error, elapsed = call_point(lambda x: 2 * x, {"x": 3.0})
    >>> value, error
    (6.0, None)
    """
    t0 = time.perf_counter()
    try:
        value = function(**point)
    except PinlinError as exc:
        elapsed = time.perf_counter() - t0
        failure = SweepFailure(point, exc, f"{function_name(function)}(**point) raised {type(exc).__name__}", elapsed)
        return failure, None, elapsed
    return value, headline_error(value), time.perf_counter() - t0


def _serial(function, points, report, on_error) -> list[Item]:
    out = []
    for i, point in enumerate(points):
        item = call_point(function, point)
        if on_error == "raise" and isinstance(item[0], SweepFailure):
            raise item[0].exception
        out.append(item)
        report(i, item)
    return out


def _submit_all(function, points, executor) -> dict:
    futures = {}
    for i, point in enumerate(points):
        future = executor.submit(call_point, function, point)
        if not isinstance(future, Future):
            for other in futures:
                other.cancel()
            raise ParameterError("executor", f"its submit() returned {type(future).__name__} {future!r}, expected a "
                                 f"concurrent.futures.Future (the Executor interface)")
        futures[future] = i
    return futures


def _completed(futures: dict, timeout: float | None, points):
    """``as_completed`` that turns a timeout into a :class:`SweepTimeoutError` naming the points not finished."""
    try:
        yield from as_completed(futures, timeout=timeout)
    except FuturesTimeout:
        pending = sorted(i for future, i in futures.items() if not future.done())
        raise SweepTimeoutError(timeout, pending, [points[i] for i in pending]) from None


def run_points(function: Callable, points: list[dict], executor: Executor | None,
               report: Callable[[int, Item], None], on_error: str, timeout: float | None = None) -> list[Item]:
    """Every point's (value, error, elapsed), in grid order; ``report(index, item)`` in completion order.

    With ``on_error="raise"`` the failure raised is the first in grid order:
    once a point fails, the points after it are cancelled (those already
    running finish unreported), the points before it are awaited, and the
    earliest failure among them is raised.  A failed point is not reported.
    ``timeout`` [s] bounds the wait for all points on an executor.

    Raises
    ------
    PinlinError
        The first failure in grid order, with ``on_error="raise"``.
    ParameterError
        The executor's ``submit`` returned something that is not a ``concurrent.futures.Future``.
    SweepTimeoutError
        Points not finished after ``timeout`` seconds (cancelled unless already running).

    Examples
    --------
    >>> from pinlin.studies.scheduling import run_points
    >>> items = run_points(lambda x: 2 * x, [{"x": 1.0}, {"x": 2.0}], None, lambda i, item: None, "raise")
    >>> [value for value, error, elapsed in items]
    [2.0, 4.0]
    """
    if executor is None:
        return _serial(function, points, report, on_error)
    futures = _submit_all(function, points, executor)
    items: list[Item | None] = [None] * len(points)
    first = None  # index of the earliest failure so far (on_error="raise")
    waiting = 0  # points before it that have not finished
    try:
        for future in _completed(futures, timeout, points):
            i = futures[future]
            try:
                item = future.result()
            except CancelledError:
                continue
            items[i] = item
            if first is not None and i < first:
                waiting -= 1
            if on_error == "raise" and isinstance(item[0], SweepFailure) and (first is None or i < first):
                first = i
                for other, j in futures.items():
                    if j > first:
                        other.cancel()
                waiting = sum(items[j] is None for j in range(first))
            elif first is None or i < first:
                report(i, item)
            if first is not None and waiting == 0:
                break
    finally:
        for future in futures:
            future.cancel()
    if first is not None:
        raise items[first][0].exception
    return items
