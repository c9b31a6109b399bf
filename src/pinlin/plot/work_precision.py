"""Work-precision diagrams: error against run time, one line per method (the benchmarks' figure)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import ParameterError
from .style import new_axes

__all__ = ["work_precision"]


def work_precision(results: Mapping[str, tuple[Sequence[float], Sequence[float]]], ax=None):
    """Error against run time [s], log-log, one line per method.

    Parameters
    ----------
    results : mapping of label to (times [s], errors)
        Errors of zero are drawn at the smallest positive float (log axes).
    ax : matplotlib Axes, optional
        Where to draw; a new figure by default.

    Returns
    -------
    matplotlib Axes

    Raises
    ------
    ParameterError
        No results, or times and errors of different shapes.
    MissingDependencyError
        matplotlib is not installed.

    Examples
    --------
    >>> ax = pinlin.plot.work_precision({"eig": ([1e-3, 2e-3], [1e-12, 1e-14])})
    >>> ax.get_xscale(), ax.get_yscale()
    ('log', 'log')
    """
    ax = new_axes(ax)
    if not results:
        raise ParameterError("results", "nothing to plot")
    for label, (times, errors) in results.items():
        t = np.asarray(times, dtype=float)
        e = np.asarray(errors, dtype=float)
        if t.shape != e.shape:
            raise ParameterError(f"results[{label!r}]", f"times {t.shape} and errors {e.shape} differ in shape")
        ax.loglog(t, np.maximum(e, np.finfo(float).tiny), "o-", label=label)
    ax.set(xlabel="run time [s]", ylabel="error")
    ax.legend(loc="best", fontsize="small")
    return ax
