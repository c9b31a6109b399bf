"""What a sweep returns: the values in grid order (:class:`SweepResult`) and its failed points (:class:`SweepFailure`).

Both follow the result convention (docs/conventions.md): ``elapsed`` [s],
``method``, ``error`` and ``to_dict()``.  A failure survives a process pool
or a cluster: its exception is pickled with its attributes and rebuilt
without calling its constructor again.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..errors import ParameterError, PinlinError
from ..extras import import_pandas
from ..results import Result

__all__ = ["SweepResult", "SweepFailure"]


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

    Examples
    --------
    A massless point fails (a singular mass matrix); ``on_error="record"`` keeps it:

    >>> def omega(m):
    ...     return pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices([[m]], None, [[4.0]]))
    >>> result = pinlin.sweep(omega, {"m": [1.0, 0.0]}, on_error="record")
    >>> failure = result.failures[0]
    >>> failure.point, type(failure.exception).__name__, failure.exception.joints
    ({'m': 0.0}, 'SingularMassError', ('x1',))
    """

    point: Mapping[str, Any]
    exception: PinlinError
    method: str = ""
    elapsed: float = 0.0

    error: ClassVar[None] = None

    def __repr__(self) -> str:
        return f"SweepFailure({dict(self.point)}, {type(self.exception).__name__}: {self.exception})"

    def to_dict(self) -> dict[str, Any]:
        """The failure as JSON-serializable data; the exception as its type name and message."""
        out = super().to_dict()
        out["exception"] = {"type": type(self.exception).__name__, "message": str(self.exception)}
        return out


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

    Examples
    --------
    >>> result = pinlin.sweep(lambda m, k: np.sqrt(k / m), {"m": [1.0, 4.0], "k": [1.0, 4.0, 9.0]})
    >>> result.names, result.shape
    (('m', 'k'), (2, 3))
    >>> result.collect()  # one axis per name, the last varying fastest
    array([[1. , 2. , 3. ],
           [0.5, 1. , 1.5]])
    >>> result.error is None  # plain numbers carry no error figure
    True
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

    def to_pandas(self, extract: Callable[[Any], Any] | None = None):
        """One row per point, in grid order: the parameters, ``value``, ``error``, ``elapsed`` and ``failure``.

        Parameters
        ----------
        extract : callable or None
            ``value`` is ``extract(point_value)`` (e.g. ``lambda modes: modes.natural_frequency[0]``);
            None keeps the value itself.  Failed points have no ``value`` (None; NaN in a float column) and ``failure``
            ``"<ExceptionType>: <message>"`` (else None, NaN in pandas).  ``error`` and ``elapsed`` [s] are
            :attr:`point_errors` and :attr:`point_elapsed` (NaN where a point has no error figure).

        Raises
        ------
        MissingDependencyError
            pandas is not installed (``pip install 'pinlin[pandas]'``).

        Examples
        --------
        >>> result = pinlin.sweep(lambda m, k: np.sqrt(k / m), {"m": [1.0, 4.0], "k": [1.0, 4.0]})
        >>> df = result.to_pandas()
        >>> list(df.columns)
        ['m', 'k', 'value', 'error', 'elapsed', 'failure']
        >>> print(df[["m", "k", "value"]])
             m    k  value
        0  1.0  1.0    1.0
        1  1.0  4.0    2.0
        2  4.0  1.0    0.5
        3  4.0  4.0    1.0
        """
        pd = import_pandas()
        rows = []
        errors = self.point_errors or (None,) * len(self.points)
        times = self.point_elapsed or (np.nan,) * len(self.points)
        for point, value, error, elapsed in zip(self.points, self.values, errors, times):
            failed = isinstance(value, SweepFailure)
            rows.append({
                **point,
                "value": None if failed else (extract(value) if extract is not None else value),
                "error": np.nan if error is None else float(error),
                "elapsed": float(elapsed),
                "failure": f"{type(value.exception).__name__}: {value.exception}" if failed else None,
            })
        return pd.DataFrame.from_records(rows, columns=[*self.names, "value", "error", "elapsed", "failure"])

    def collect(self, extract: Callable[[Any], Any] | None = None, fill=np.nan) -> np.ndarray:
        """Stack ``extract(value)`` over the points into an array of shape ``shape + value shape``.

        Failed points are filled with ``fill``.

        Raises
        ------
        ParameterError
            Every point failed, or two points gave values of different shapes.

        Examples
        --------
        A massless point fails (``on_error="record"`` keeps it) and is filled with NaN:

        >>> def modes(m):
        ...     return pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices([[m]], None, [[4.0]]))
        >>> result = pinlin.sweep(modes, {"m": [1.0, 4.0, 0.0]}, on_error="record")
        >>> np.round(result.collect(lambda modes: modes.natural_frequency[0]), 6)
        array([ 2.,  1., nan])
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
