"""Eigenvalues in the complex plane: the spectrum of one system, and root loci over a parameter.

Conventions (docs/conventions.md): lambda [1/s] in the complex plane, Im lambda
read as [rad/s]; the imaginary axis, where stability is decided, is drawn.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..studies.tracking import track_modes
from .style import GREY, MID_GREY, POINT_SIZE, REAL_AXIS_LW, TRACE_LW, complex_plane_labels, new_axes, pyplot

__all__ = ["eigenvalue_map", "root_locus", "KIND_STYLE", "AXIS_MARGIN", "MIN_REAL_SPAN_FRACTION"]

#: Marker and colour of each mode kind (exactly :data:`pinlin.spectral.MODE_KINDS`) in eigenvalue maps.
KIND_STYLE = {
    "underdamped": ("o", "#264653"),
    "undamped": ("D", "#e9c46a"),
    "overdamped": ("s", "#2a9d8f"),
    "rigid_body": ("x", "#6c757d"),
    "unstable": ("^", "#e63946"),
}
#: Marker and colour of plain eigenvalues (no mode kinds given).
_PLAIN_STYLE = ("o", "#264653")

#: Axis limits reach this factor beyond the outermost eigenvalue, so markers are not cut at the frame.
AXIS_MARGIN = 1.15
#: The real axis of an eigenvalue map spans at least this fraction of the largest |lambda|, so the
#: error bars of an undamped spectrum (~1e-14) do not set the scale.
MIN_REAL_SPAN_FRACTION = 0.1


def eigenvalue_map(modes, ax=None, *, error_bars: bool = True, title: bool = True):
    """Eigenvalues lambda [1/s] in the complex plane, marked by mode kind, with their error bounds.

    Parameters
    ----------
    modes : Modes or array_like
        A :func:`pinlin.modal_analysis` result (uses ``kind``, ``error_bound``
        and ``stability`` when present) or plain eigenvalues.
    ax : matplotlib Axes, optional
        Where to draw; a new figure by default.
    error_bars : bool
        Draw each eigenvalue's error bound [1/s] as a horizontal bar (its distance
        to the imaginary axis is what a stability verdict must beat, theory: error figures).
    title : bool
        Title the axes with the stability verdict, when ``modes`` has one.

    Returns
    -------
    matplotlib Axes

    Raises
    ------
    ParameterError
        Non-finite eigenvalues.
    MissingDependencyError
        matplotlib is not installed.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), np.diag([1.0, 4.0]))
    >>> ax = pinlin.plot.eigenvalue_map(pinlin.modal_analysis(sys))
    >>> print(ax.get_xlabel())
    Re $\\lambda$ [1/s]
    """
    lam = np.asarray(getattr(modes, "eigenvalues", modes), dtype=complex).ravel()
    if not np.all(np.isfinite(lam)):
        raise ParameterError("eigenvalues", "has non-finite values")
    ax = new_axes(ax)
    kinds = tuple(getattr(modes, "kind", ("eigenvalue",) * lam.size))
    for kind in dict.fromkeys(kinds):
        sel = np.array([k == kind for k in kinds])
        marker, color = KIND_STYLE.get(kind, _PLAIN_STYLE)
        ax.scatter(lam[sel].real, lam[sel].imag, marker=marker, color=color, label=kind.replace("_", " "), zorder=3)
    bound = getattr(modes, "error_bound", None)
    if error_bars and bound is not None:
        ax.errorbar(lam.real, lam.imag, xerr=np.asarray(bound, float), fmt="none", ecolor=MID_GREY, lw=TRACE_LW, zorder=2)
    ax.axhline(0.0, color="k", lw=REAL_AXIS_LW)
    span = max(AXIS_MARGIN * np.abs(lam.real).max(initial=0.0), MIN_REAL_SPAN_FRACTION * np.abs(lam).max(initial=0.0))
    span = span or 1.0  # all eigenvalues at 0: any symmetric window shows them
    ax.set_xlim(min(-span, AXIS_MARGIN * lam.real.min(initial=0.0)), max(span, AXIS_MARGIN * lam.real.max(initial=0.0)))
    complex_plane_labels(ax)
    stability = getattr(modes, "stability", None)
    if title and stability is not None:
        ax.set_title(str(stability.kind).replace("_", " "))
    ax.legend(loc="best", fontsize="small")
    return ax


def root_locus(parameter, eigenvalues, ax=None, *, vectors=None, label: str = "parameter", cmap: str = "viridis"):
    """Eigenvalues lambda [1/s] traced over a parameter, each mode followed by its shape.

    Parameters
    ----------
    parameter : (steps,) array_like
        The parameter's values, one per step.
    eigenvalues : (steps, m) array_like
        Eigenvalues [1/s] at each step, in any order (they are tracked).
    ax : matplotlib Axes, optional
        Where to draw; a new figure by default.
    vectors : (steps, n, m) array_like, optional
        Mode shapes for :func:`pinlin.studies.track_modes`; without them modes
        are matched by eigenvalue distance.
    label : str
        Name of the parameter (colour bar).
    cmap : str
        matplotlib colour map of the parameter.

    Returns
    -------
    matplotlib Axes

    Raises
    ------
    ParameterError
        Shapes that do not agree (``parameter`` and the steps, eigenvalues and
        vectors), non-finite values.
    MissingDependencyError
        matplotlib is not installed.

    Examples
    --------
    >>> damping = [0.0, 0.5, 1.0]
    >>> eigenvalues = [pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices(
    ...     np.eye(2), c * np.eye(2), np.diag([1.0, 4.0]))).eigenvalues for c in damping]
    >>> ax = pinlin.plot.root_locus(damping, eigenvalues, label="damping [N s/m]")
    >>> print(ax.get_xlabel())
    Re $\\lambda$ [1/s]
    """
    plt = pyplot()
    ax = new_axes(ax)
    p = np.asarray(parameter, dtype=float)
    tracked = track_modes(eigenvalues, vectors)
    if p.shape != (tracked.eigenvalues.shape[0],):
        raise ParameterError("parameter", f"expected {tracked.eigenvalues.shape[0]} values, got shape {p.shape}")
    lam = tracked.eigenvalues
    for j in range(lam.shape[1]):
        ax.plot(lam[:, j].real, lam[:, j].imag, color=GREY, lw=TRACE_LW, zorder=1)
    points = ax.scatter(lam.real.ravel(), lam.imag.ravel(), c=np.repeat(p, lam.shape[1]), cmap=cmap, s=POINT_SIZE,
                        zorder=2)
    plt.colorbar(points, ax=ax, label=label)
    complex_plane_labels(ax)
    return ax
