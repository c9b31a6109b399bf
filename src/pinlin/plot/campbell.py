"""Campbell diagrams: damped frequencies against spin speed, modes followed by their shapes.

Conventions (docs/conventions.md): speeds and frequencies [rad/s]; a point is
marked unstable only when Re lambda exceeds both rounding (:data:`UNSTABLE_RTOL`)
and the eigenvalue's own error bound, when given.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import ParameterError
from ..studies.tracking import one_per_conjugate_pair, track_modes
from .style import AXIS_LW, CURVE_LW, POINT_SIZE, VERDICT_COLORS, new_axes

__all__ = ["campbell", "UNSTABLE_RTOL"]

#: Default of ``campbell(rtol=...)``: Re lambda below this fraction of the step's largest |lambda| is
#: rounding of an undamped spectrum (~1e-16 |lambda|), not instability.
UNSTABLE_RTOL = 1e-9


def campbell(speed, eigenvalues, ax=None, *, vectors=None, orders: Sequence[float] = (1.0,),
             label: str = "spin speed [rad/s]", error_bounds=None, rtol: float = UNSTABLE_RTOL):
    """Campbell diagram: damped frequencies |Im lambda| [rad/s] against spin speed.

    Modes are followed by their shapes (:func:`pinlin.studies.track_modes`),
    so crossing frequencies cross instead of veering falsely; points whose
    Re lambda is positive beyond rounding (unstable) are marked in red.
    Straight lines show the excitation orders k * speed.

    One member of each complex conjugate pair of tracked modes is drawn
    (:func:`pinlin.studies.tracking.one_per_conjugate_pair`), so a whirl branch
    whose frequency passes through zero (lambda = i (omega_0 - speed) of a
    rotating ring, theory: rotating ring) is drawn as a V instead of being dropped.

    Parameters
    ----------
    speed : (steps,) array_like
        Spin speed [rad/s].
    eigenvalues : (steps, m) array_like
        Eigenvalues [1/s] at each speed, in any order (they are tracked).
    ax : matplotlib Axes, optional
        Where to draw; a new figure by default.
    vectors : (steps, n, m) array_like, optional
        Mode shapes for the tracking; without them modes are matched by eigenvalue distance.
    orders : sequence of float
        Excitation orders drawn as lines k * speed.
    label : str
        Label of the speed axis.
    error_bounds : (steps, m) array_like, optional
        Error bounds [1/s] of the eigenvalues (``modes.error_bound`` of each
        step, in the same order as ``eigenvalues``): a point is marked unstable
        only when Re lambda exceeds its bound.
    rtol : float
        Re lambda must also exceed rtol times the step's largest |lambda| to be
        marked (see :data:`UNSTABLE_RTOL`).

    Returns
    -------
    matplotlib Axes

    Raises
    ------
    ParameterError
        ``speed`` or ``error_bounds`` not matching the eigenvalues, a negative or
        non-finite ``rtol``, non-finite eigenvalues or vectors.
    MissingDependencyError
        matplotlib is not installed.

    Examples
    --------
    >>> speed = [0.0, 1.0, 2.0]
    >>> eigenvalues = [pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices(
    ...     np.eye(2), np.zeros((2, 2)), np.diag([1.0, 4.0]) + w * np.eye(2))).eigenvalues for w in speed]
    >>> ax = pinlin.plot.campbell(speed, eigenvalues)
    >>> ax.get_xlabel()
    'spin speed [rad/s]'
    """
    ax = new_axes(ax)
    w = np.asarray(speed, dtype=float)
    tracked = track_modes(eigenvalues, vectors)
    lam = tracked.eigenvalues
    if w.shape != (lam.shape[0],):
        raise ParameterError("speed", f"expected {lam.shape[0]} values, got shape {w.shape}")
    if not (np.isfinite(rtol) and rtol >= 0):
        raise ParameterError("rtol", f"must be >= 0, got {rtol!r}")
    threshold = np.broadcast_to(rtol * np.abs(lam).max(axis=1, keepdims=True), lam.shape)
    if error_bounds is not None:
        bounds = np.asarray(error_bounds, dtype=float)
        if bounds.shape != lam.shape:
            raise ParameterError("error_bounds", f"expected shape {lam.shape} (like eigenvalues), got {bounds.shape}")
        threshold = np.maximum(threshold, np.take_along_axis(bounds, tracked.order, axis=1))
    keep = one_per_conjugate_pair(lam) or list(range(lam.shape[1]))
    for j in keep:
        ax.plot(w, np.abs(lam[:, j].imag), lw=CURVE_LW)
    unstable = lam[:, keep].real > threshold[:, keep]
    if np.any(unstable):
        ws = np.broadcast_to(w[:, None], unstable.shape)
        ax.scatter(ws[unstable], np.abs(lam[:, keep].imag)[unstable], color=VERDICT_COLORS["flutter"], s=POINT_SIZE,
                   zorder=3, label="Re $\\lambda$ > 0")
        ax.legend(loc="best", fontsize="small")
    for k in orders:
        ax.plot(w, k * w, color="k", ls="--", lw=AXIS_LW)
    ax.set(xlabel=label, ylabel="damped frequency |Im $\\lambda$| [rad/s]")
    return ax
