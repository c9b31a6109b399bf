"""The figure of ``pinlin analyze --plot``: eigenvalue map and driving-point frequency responses."""

from __future__ import annotations

import numpy as np

from ..errors import MissingDependencyError, ParameterError
from ..linearization.system import LinearizedSystem

__all__ = ["write_plot", "MAX_RESPONSE_DOFS", "FREQUENCY_DECADES", "FREQUENCY_POINTS", "ZERO_FREQUENCY_RTOL"]

#: Driving-point responses drawn for at most this many coordinates (more would crowd one axes pair).
MAX_RESPONSE_DOFS = 4
#: The frequency grid reaches this factor below the lowest and above the highest natural frequency,
#: a decade on each side, so every resonance shows its flanks.
FREQUENCY_DECADES = 10.0
#: Points of the logarithmic frequency grid: resolves resonance peaks of damping ratios down to ~1e-3.
FREQUENCY_POINTS = 600
#: Natural frequencies below this fraction of the largest (at least 1 rad/s) are rigid-body modes
#: (|lam| ~ rounding): they do not set the lower end of the grid.
ZERO_FREQUENCY_RTOL = 1e-9
#: Figure size [in]: the eigenvalue map and the stacked magnitude and phase side by side.
_FIGSIZE = (11, 4.5)


def _frequency_grid(modes) -> np.ndarray:
    """omega [rad/s]: from a decade below the lowest to a decade above the highest nonzero |lam|."""
    mags = np.abs(modes.eigenvalues)
    mags = mags[mags > ZERO_FREQUENCY_RTOL * max(mags.max(), 1.0)]
    lo, hi = (mags.min(), mags.max()) if mags.size else (1.0, 1.0)
    return np.logspace(np.log10(lo / FREQUENCY_DECADES), np.log10(hi * FREQUENCY_DECADES), FREQUENCY_POINTS)


def write_plot(path: str, sys_: LinearizedSystem, modes) -> None:
    """Eigenvalue map and driving-point frequency responses (up to four coordinates) into one figure file.

    Parameters
    ----------
    path : str
        Image file; its suffix picks the format (png, pdf, svg, ...).
    sys_ : LinearizedSystem
    modes : Modes
        ``pinlin.modal_analysis(sys_)``.

    Raises
    ------
    MissingDependencyError
        matplotlib is not installed.
    ParameterError
        The file cannot be written (named ``--plot``, the option that gave it).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> sys = pinlin.linearize(pinlin.Scene(robot), np.zeros(2))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "modes.png"
    ...     pinlin.report.write_plot(str(path), sys, pinlin.modal_analysis(sys))
    ...     path.stat().st_size > 0
    True
    """
    try:
        # a Figure without pyplot: no global backend switch, nothing left open in a user's session
        from matplotlib.figure import Figure
    except ImportError:
        raise MissingDependencyError("--plot needs matplotlib: pip install 'pinlin[plot]'") from None
    from .. import plot
    from ..frf import frequency_response

    fig = Figure(figsize=_FIGSIZE)
    grid = fig.add_gridspec(2, 2, width_ratios=(1, 1.2))
    plot.eigenvalue_map(modes, fig.add_subplot(grid[:, 0]))
    dofs = list(range(min(sys_.n, MAX_RESPONSE_DOFS)))
    resp = frequency_response(sys_, _frequency_grid(modes), inputs=dofs, outputs=dofs)
    axes = (fig.add_subplot(grid[0, 1]), fig.add_subplot(grid[1, 1]))
    for k, name in enumerate(sys_.dof_names[: len(dofs)]):
        plot.frequency_response(resp, axes, output=k, input=k, label=f"H[{name}, {name}]")
    fig.suptitle(f"{sys_.n} coordinates: {modes.stability.kind.replace('_', ' ')}")
    fig.tight_layout()
    try:
        fig.savefig(path)
    except OSError as exc:
        raise ParameterError("--plot", f"cannot write {path}: {exc}") from None
