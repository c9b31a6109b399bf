"""What every pinlin figure shares: the matplotlib import, axes creation, colours and line widths.

matplotlib is an optional extra (``pip install 'pinlin[plot]'``): it is imported
when a figure is drawn, never when :mod:`pinlin.plot` is imported, and its
absence raises :class:`~pinlin.errors.MissingDependencyError`.
"""

from __future__ import annotations

from ..errors import MissingDependencyError

__all__ = ["VERDICT_COLORS", "pyplot", "new_axes", "complex_plane_labels"]

#: Colours of the stability verdicts in maps and eigenvalue plots (the one palette).
VERDICT_COLORS = {
    "asymptotically_stable": "#2a9d8f",
    "marginally_stable": "#8ecae6",
    "divergence": "#f4a261",
    "flutter": "#e63946",
    "undecided": "#adb5bd",
}
#: Colours of reference geometry (traces, the equilibrium of a mode shape), error bars, drawn shapes.
GREY, MID_GREY, DARK = "#adb5bd", "#6c757d", "#264653"
#: Colour of the frames that carry wrenches in mode shapes (the load is what makes those scenes interesting).
WRENCH_COLOR = "#e63946"
#: Line widths: the imaginary axis (the stability boundary), the real axis, thin traces, curves.
AXIS_LW, REAL_AXIS_LW, TRACE_LW, CURVE_LW = 0.8, 0.4, 1.0, 1.5
#: Marker size of sampled points (root loci, unstable Campbell points).
POINT_SIZE = 12


def pyplot():
    """``matplotlib.pyplot``, or :class:`~pinlin.errors.MissingDependencyError` naming the extra.

    Raises
    ------
    MissingDependencyError
        matplotlib is not installed.
    """
    try:
        import matplotlib.pyplot as plt
    except ImportError as exc:  # pragma: no cover - exercised only without the extra
        raise MissingDependencyError("pinlin.plot needs matplotlib: pip install 'pinlin[plot]'") from exc
    return plt


def new_axes(ax=None):
    """``ax``, or the axes of a new pyplot figure.

    Raises
    ------
    MissingDependencyError
        matplotlib is not installed.
    """
    if ax is None:
        _, ax = pyplot().subplots()
    return ax


def complex_plane_labels(ax) -> None:
    """The imaginary axis (the stability boundary) and the axis labels of a lambda plane [1/s]."""
    ax.axvline(0.0, color="k", lw=AXIS_LW)
    ax.set(xlabel="Re $\\lambda$ [1/s]", ylabel="Im $\\lambda$ [rad/s]")
