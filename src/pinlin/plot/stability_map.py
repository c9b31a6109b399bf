"""The stability map: verdicts over a grid of two parameters and the exact boundary over them (theory: boundaries).

matplotlib is imported only when a map is drawn (:func:`pinlin.plot.style.pyplot`); the verdict
colours are :data:`pinlin.plot.style.VERDICT_COLORS`.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from .style import VERDICT_COLORS, pyplot

__all__ = ["stability_map", "BOUNDARY_STYLE"]

#: How the boundary curve is drawn: a dark line through the points, which are marked.
BOUNDARY_STYLE = {"color": "#1d3557", "lw": 1.5, "marker": "o", "ms": 3.5, "zorder": 4}



def _verdict_grid(ax, x, y, kinds):
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    names = list(VERDICT_COLORS)
    k = np.asarray(kinds, dtype=object)
    if k.shape != (y.size, x.size):
        raise ParameterError("kinds", f"expected shape {(y.size, x.size)} (len(y), len(x)), got {k.shape}")
    unknown = {str(v) for v in k.ravel()} - set(names)
    if unknown:
        raise ParameterError("kinds", f"unknown verdicts {sorted(unknown)}; expected {names}")
    codes = np.vectorize(names.index)(k.astype(str)).astype(float)
    # one colour per verdict code: bins centred on the integers 0 .. len(names) - 1
    cmap = ListedColormap(list(VERDICT_COLORS.values()))
    ax.pcolormesh(x, y, codes, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5, shading="nearest")
    return [Patch(color=VERDICT_COLORS[n], label=n.replace("_", " ")) for n in names if np.any(k == n)]


def stability_map(x=None, y=None, kinds=None, ax=None, *, boundary=None, p1_axis: str = "x",
                  xlabel: str | None = None, ylabel: str | None = None, label: str = "boundary",
                  error_bars: bool = True):
    """Stability verdicts over a two-parameter grid, and a boundary curve over them.

    Parameters
    ----------
    x : (nx,) array_like, optional
    y : (ny,) array_like, optional
    kinds : (ny, nx) array_like of str, optional
        Verdict kinds (``modes.stability.kind``) at the grid points; omit x, y and
        kinds to draw the boundary alone.
    ax : matplotlib Axes, optional
    boundary : StabilityBoundary, optional
        From :func:`pinlin.stability_boundary`: p2*(p1) drawn as a line through its
        points (those not found are left out), with error bars of its error bounds.
    p1_axis : {"x", "y"}
        The axis of the boundary's first parameter p1 (the other carries p2*).
    xlabel, ylabel : str, optional
    label : str
        Legend label of the boundary.
    error_bars : bool
        Draw each point's error bound (usually far below the line width).

    Returns
    -------
    matplotlib Axes

    Raises
    ------
    MissingDependencyError
        matplotlib is not installed.
    ParameterError
        ``kinds`` of the wrong shape or with an unknown verdict; only some of x,
        y, kinds given; nothing to draw; a bad ``p1_axis``.

    Examples
    --------
    >>> kinds = [["asymptotically_stable", "flutter"], ["divergence", "flutter"]]
    >>> ax = pinlin.plot.stability_map([0.0, 1.0], [0.0, 1.0], kinds, xlabel="p1", ylabel="p2")
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('p1', 'p2')
    """
    given = [v is not None for v in (x, y, kinds)]
    if any(given) and not all(given):
        raise ParameterError("x, y, kinds", "give all three (a verdict grid) or none of them")
    if not any(given) and boundary is None:
        raise ParameterError("boundary", "nothing to draw: give a verdict grid (x, y, kinds), a boundary, or both")
    if p1_axis not in ("x", "y"):
        raise ParameterError("p1_axis", f"expected 'x' or 'y', got {p1_axis!r}")
    plt = pyplot()
    if ax is None:
        _, ax = plt.subplots()
    handles = []
    if kinds is not None:
        handles += _verdict_grid(ax, np.asarray(x, dtype=float), np.asarray(y, dtype=float), kinds)
    if boundary is not None:
        ok = np.asarray(boundary.found, dtype=bool)
        p1, p2, err = (np.asarray(boundary.p1)[ok], np.asarray(boundary.p2)[ok],
                       np.asarray(boundary.error_bound)[ok])
        xs, ys = (p1, p2) if p1_axis == "x" else (p2, p1)
        (line,) = ax.plot(xs, ys, label=label, **BOUNDARY_STYLE)
        if error_bars:
            bars = {"yerr": err} if p1_axis == "x" else {"xerr": err}
            ax.errorbar(xs, ys, fmt="none", ecolor=BOUNDARY_STYLE["color"], elinewidth=0.8, **bars)
        handles.append(line)
    ax.legend(handles=handles, loc="best", fontsize="small")
    default = ("x", "y") if boundary is None else ("p1", "p2") if p1_axis == "x" else ("p2", "p1")
    ax.set(xlabel=xlabel or default[0], ylabel=ylabel or default[1])
    return ax
