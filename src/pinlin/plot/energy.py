"""Bar charts of a mode's energy distribution (:meth:`pinlin.Modes.energy`)."""

from __future__ import annotations

from ..errors import ParameterError
from ..spectral.energy import ModeEnergy
from .style import GREY, pyplot

__all__ = ["mode_energy", "ENERGY_COLORS"]

#: Bar colours of the three tables, and of negative shares (energy a row gives back).
ENERGY_COLORS = {"kinetic": "#264653", "strain": "#2a9d8f", "dissipation": "#e9c46a", "negative": "#e63946"}


def mode_energy(energy: ModeEnergy, axes=None):
    """Horizontal bars of the kinetic, strain and dissipation shares [%] of one mode.

    One axes per table, rows in the table's order (bodies, elements then gravity and
    the rest, dampers); a negative share is drawn to the left in red.  An empty table
    (no strain in a rigid-body mode, no damping) says "none".

    Parameters
    ----------
    energy : ModeEnergy
        ``modes.energy(k, scene)``.
    axes : sequence of 3 matplotlib Axes, optional
        Where to draw; a new figure with three panels by default.

    Returns
    -------
    list of matplotlib Axes
        The three axes (kinetic, strain, dissipation).

    Raises
    ------
    ParameterError
        ``energy`` is not a ModeEnergy, or ``axes`` is not three axes.
    MissingDependencyError
        matplotlib is not installed.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot)
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> energy = pinlin.modal_analysis(sys).energy(0, scene)
    >>> axes = pinlin.plot.mode_energy(energy)
    >>> len(axes)  # kinetic, strain, dissipation
    3
    """
    if not isinstance(energy, ModeEnergy):
        raise ParameterError("energy", f"expected a ModeEnergy (modes.energy(k, scene)), got {type(energy).__name__}")
    own = axes is None
    if own:
        _, axes = pyplot().subplots(1, 3, figsize=(11, 3.2), constrained_layout=True)
    axes = list(axes)
    if len(axes) != 3:
        raise ParameterError("axes", f"expected 3 axes (kinetic, strain, dissipation), got {len(axes)}")
    tables = (("kinetic", f"kinetic ({energy.by})", energy.kinetic),
              ("strain", "strain", energy.strain), ("dissipation", "dissipation", energy.dissipation))
    for ax, (key, title, shares) in zip(axes, tables):
        ax.set_title(title)
        if not shares:
            ax.text(0.5, 0.5, "none", ha="center", va="center", color=GREY, transform=ax.transAxes)
            ax.set_yticks([])
            continue
        names = list(shares)
        values = [100 * shares[name] + 0.0 for name in names]
        colors = [ENERGY_COLORS["negative"] if v < 0 else ENERGY_COLORS[key] for v in values]
        ax.barh(range(len(names)), values, color=colors)
        ax.set_yticks(range(len(names)), names)
        ax.invert_yaxis()
        ax.axvline(0.0, color=GREY, lw=0.8)
        ax.set_xlabel("share [%]")
    if own:  # a title for the figure made here; the caller's own figure keeps its title
        lam = energy.eigenvalue
        axes[0].figure.suptitle(f"mode {energy.index + 1}: {abs(lam):.4g} rad/s, lam = {lam.real + 0.0:.4g} "
                                f"{lam.imag + 0.0:+.4g}j")
    return axes
