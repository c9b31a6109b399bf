"""The figure of ``pinlin sweep --plot``: root locus and tracked modes, or a stability map.

One parameter: the root locus (:func:`pinlin.plot.root_locus`) beside Re lam of
the tracked modes against the parameter and their damped frequencies |Im lam|
(a Campbell diagram, :func:`pinlin.plot.campbell`, when the parameter is a
spin speed), each verdict change's exact boundary a vertical line.  Two
parameters: the verdicts over the grid (:func:`pinlin.plot.stability_map`) and
the boundaries found along the first parameter.
"""

from __future__ import annotations

import numpy as np

from ...errors import MissingDependencyError, ParameterError
from .run import SweepOutcome

__all__ = ["write_sweep_plot", "FIGSIZE"]

#: Figure size [in]: the root locus and the stacked tracked modes side by side.
FIGSIZE = (12, 5)
#: Axis limits reach this factor beyond the outermost real part, so markers are not cut at the frame.
_MARGIN = 1.15
#: Style of the lines that mark the exact boundaries.
_BOUNDARY_STYLE = {"color": "#e63946", "ls": "--", "lw": 1.0}


def _label(p) -> str:
    return f"{p.path} [{p.unit}]" if p.unit else p.path


def _boundaries(outcome: SweepOutcome) -> list[float]:
    return [c.boundary.value for c in outcome.changes if c.boundary is not None]


def _real_span(lam: np.ndarray, fraction: float) -> float:
    """Half-width of a real-part axis: the data's, but at least ``fraction`` of the largest |lam|
    (so rounding-level real parts of an undamped spectrum do not set the scale)."""
    return max(float(np.abs(lam.real).max()), fraction * float(np.abs(lam).max())) * _MARGIN or 1.0


def _one_parameter(fig, outcome: SweepOutcome) -> None:
    from ... import plot

    p = outcome.plan.parameters[0]
    tracked, values = outcome.tracked, outcome.tracked_values
    lam = tracked.eigenvalues
    span = _real_span(lam, plot.MIN_REAL_SPAN_FRACTION)
    grid = fig.add_gridspec(2, 2, width_ratios=(1, 1.2))
    locus = fig.add_subplot(grid[:, 0])
    plot.root_locus(values, lam, locus, vectors=tracked.vectors, label=_label(p))
    locus.set_xlim(-span, span)
    top, bottom = fig.add_subplot(grid[0, 1]), fig.add_subplot(grid[1, 1])
    top.plot(values, lam.real, lw=1.2)
    top.axhline(0.0, color="k", lw=0.8)
    top.set(ylabel="Re $\\lambda$ [1/s]", ylim=(-span, span))
    if p.target == "prescribed" and p.unit == "rad/s":
        plot.campbell(values, lam, bottom, vectors=tracked.vectors, label=_label(p))
    else:
        bottom.plot(values, np.abs(lam.imag), lw=1.2)
        bottom.set(xlabel=_label(p), ylabel="|Im $\\lambda$| [rad/s]")
    for ax in (top, bottom):
        for value in _boundaries(outcome):
            ax.axvline(value, **_BOUNDARY_STYLE)


def _two_parameters(fig, outcome: SweepOutcome) -> None:
    from ... import plot

    p1, p2 = outcome.plan.parameters
    ax = fig.add_subplot()
    kinds = outcome.verdicts.T.astype(str)
    failed = kinds == "failed"
    kinds[failed] = "undecided"  # a verdict map has no colour for "no verdict": said in the title
    plot.stability_map(p1.values, p2.values, kinds, ax, xlabel=_label(p1), ylabel=_label(p2))
    if failed.any():
        ax.set_title(f"{int(failed.sum())} failed point(s) drawn as undecided (see the text report)",
                     fontsize="small")
    found = [(c.boundary.value, c.second) for c in outcome.changes if c.boundary is not None]
    if found:
        xs, ys = zip(*found)
        (points,) = ax.plot(xs, ys, "o", color="k", mec="w", ms=6, label="exact boundary")
        verdicts = ax.get_legend()  # the verdict colours of stability_map, kept beside the boundary
        handles = list(verdicts.legend_handles) if verdicts is not None else []
        ax.legend(handles=[*handles, points], loc="best", fontsize="small")


def write_sweep_plot(path: str, outcome: SweepOutcome) -> None:
    """Draw the sweep into one figure file (format from the suffix).

    Parameters
    ----------
    path : str
    outcome : SweepOutcome

    Raises
    ------
    MissingDependencyError
        matplotlib is not installed.
    ParameterError
        Nothing to draw (every point failed), or the file cannot be written
        (named ``--plot``, the option that gave it).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from pinlin.report.sweep.figure import write_sweep_plot
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sweep.png"
    >>> write_sweep_plot(str(path), run_sweep(plan))
    >>> path.stat().st_size > 0
    True
    """
    try:
        import matplotlib.pyplot as plt
    except ImportError:
        raise MissingDependencyError("--plot needs matplotlib: pip install 'pinlin[plot]'") from None
    one = len(outcome.plan.parameters) == 1
    if one and outcome.tracked is None or not one and np.all(outcome.verdicts == "failed"):
        raise ParameterError("--plot", "every point of the sweep failed: nothing to draw")
    # a pyplot figure (closed below): plot functions that reach for the current figure find this one
    fig = plt.figure(figsize=FIGSIZE)
    try:
        (_one_parameter if one else _two_parameters)(fig, outcome)
        fig.suptitle(f"{outcome.plan.spec.scene.robot.name}: sweep of {outcome.plan.parameters[0].path}")
        fig.tight_layout()
        fig.savefig(path)
    except OSError as exc:
        raise ParameterError("--plot", f"cannot write {path}: {exc}") from None
    finally:
        plt.close(fig)
