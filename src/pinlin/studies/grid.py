"""The points of a sweep's grid, checked and counted before any is built (a
typo in a grid fails at once, not after hours of points).

A mapping ``name -> values`` stands for the Cartesian product of its axes.
:class:`GridPoints` gives its points by index without building the product, so
a grid's size is known (and refused above ``max_points``) at the cost of one
multiplication, however many points it would have: a typing error such as a
grid of 10^9 points is a :class:`~pinlin.ParameterError`, not a ``MemoryError``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import ParameterError

__all__ = ["GridPoints", "grid_points", "MAX_POINTS"]

#: Default largest number of points of a sweep (:func:`pinlin.sweep`'s ``max_points``, the
#: command line's cap): more is most often a typing error; pass ``max_points=`` to go further.
MAX_POINTS = 10_000


class GridPoints(Sequence):
    """The points of the Cartesian product of ``axes`` (the last name varies fastest), made on demand.

    Examples
    --------
    >>> from pinlin.studies.grid import GridPoints
    >>> points = GridPoints(("m", "k"), ([1.0, 2.0], [3.0, 4.0, 5.0]))
    >>> len(points), points[4], points[-1]
    (6, {'m': 2.0, 'k': 4.0}, {'m': 2.0, 'k': 5.0})
    """

    def __init__(self, names: tuple[str, ...], axes: tuple[Sequence, ...]):
        self.names = names
        self._axes = axes
        self._sizes = tuple(len(a) for a in axes)
        self._len = math.prod(self._sizes)

    def __len__(self) -> int:
        return self._len

    def _point(self, index: int) -> dict:
        values = []
        for axis, size in zip(reversed(self._axes), reversed(self._sizes)):
            index, k = divmod(index, size)
            values.append(axis[k])
        return dict(zip(self.names, reversed(values)))

    def __getitem__(self, index):
        if isinstance(index, slice):
            return [self._point(i) for i in range(*index.indices(self._len))]
        if index < 0:
            index += self._len
        if not 0 <= index < self._len:
            raise IndexError(f"point {index} of a grid of {self._len}")
        return self._point(index)


def _check_count(count: int, max_points: int | None) -> None:
    if max_points is not None and count > max_points:
        raise ParameterError("grid", f"has {count} points, more than max_points={max_points}: pass a larger "
                             f"max_points (or None) to sweep it anyway")


def _check_names(names) -> None:
    for name in names:
        if not isinstance(name, str):
            raise ParameterError("grid", f"expected parameter names that are strings (keyword arguments of the "
                                 f"function), got {name!r}")


def grid_points(grid, max_points: int | None = MAX_POINTS) -> tuple[tuple[str, ...], Sequence[dict], tuple[int, ...], dict]:
    """(names, points, shape, axes) of a grid: a mapping name -> values (its product) or a sequence of dicts.

    Raises
    ------
    ParameterError
        An empty or malformed grid, a parameter name that is not a string (the
        points are passed as keyword arguments), more than
        ``max_points`` points, a ``max_points`` that is not a positive integer or None.

    Examples
    --------
    >>> from pinlin.studies.grid import grid_points
    >>> names, points, shape, axes = grid_points({"m": [1.0, 2.0], "k": [3.0, 4.0, 5.0]})
    >>> names, shape, points[1], axes["k"]
    (('m', 'k'), (2, 3), {'m': 1.0, 'k': 4.0}, array([3., 4., 5.]))
    """
    if max_points is not None and (isinstance(max_points, bool) or not isinstance(max_points, (int, np.integer))
                                   or max_points < 1):
        raise ParameterError("max_points", f"expected a positive integer or None, got {max_points!r}")
    if isinstance(grid, Mapping):
        if not grid:
            raise ParameterError("grid", "no parameters to sweep")
        names = tuple(grid)
        _check_names(names)
        axes = {}
        for name in names:
            values = grid[name]
            if isinstance(values, (str, bytes)) or not isinstance(values, (Sequence, np.ndarray)):
                raise ParameterError(f"grid[{name!r}]", f"expected a sequence of values, got {values!r}")
            if len(values) == 0:
                raise ParameterError(f"grid[{name!r}]", "has no values")
            axes[name] = np.asarray(values)
        shape = tuple(len(grid[n]) for n in names)
        _check_count(math.prod(shape), max_points)
        return names, GridPoints(names, tuple(grid[n] for n in names)), shape, axes
    if isinstance(grid, (str, bytes)) or not isinstance(grid, Sequence) or not grid:
        raise ParameterError("grid", "expected a mapping name -> values, or a non-empty sequence of dicts")
    _check_count(len(grid), max_points)
    points = []
    for i, point in enumerate(grid):
        if not isinstance(point, Mapping):
            raise ParameterError(f"grid[{i}]", f"expected a dict of parameters, got {point!r}")
        _check_names(point)
        points.append(dict(point))
    names = tuple(dict.fromkeys(k for p in points for k in p))
    return names, points, (len(points),), {}
