"""Frequency responses: magnitude (log-log) and phase [deg] of one output, for one input or a load pattern.

Conventions (docs/conventions.md): omega [rad/s]; ``magnitude`` and ``phase``
[rad] in python-control's axis order (outputs, inputs, frequencies); phases in
degrees on the plot axis only.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from .style import pyplot

__all__ = ["frequency_response"]


def frequency_response(resp, axes=None, *, output: int = 0, input=0, label: str | None = None):
    """Magnitude (log-log) and phase [deg] of one output of a frequency response, for one input or a load pattern.

    Parameters
    ----------
    resp : object with ``omega`` (f,) [rad/s], ``magnitude`` and ``phase`` [rad] (outputs, inputs, f)
        A :func:`pinlin.frequency_response` result (python-control's axis order).
    axes : pair of Axes, optional
        Magnitude and phase axes; a new figure with two stacked axes by default.
    output : int
        Index of the output (into ``resp``'s outputs).
    input : int or (n_inputs,) array_like
        Index of the input, or weights w of all inputs: the curve is then
        sum_j H[output, j] w_j, the response to the load pattern w (a
        generalized force from :func:`pinlin.generalized_force`, say).
    label : str, optional
        Legend entry.

    Returns
    -------
    tuple of matplotlib Axes
        The magnitude and phase axes.

    Raises
    ------
    ParameterError
        Weights whose length is not the number of inputs, or not finite.
    MissingDependencyError
        matplotlib is not installed.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), np.diag([1.0, 4.0]))
    >>> axes = pinlin.plot.frequency_response(pinlin.frequency_response(sys, np.linspace(0.1, 5.0, 50)))
    >>> len(axes)  # magnitude and phase
    2
    """
    plt = pyplot()
    omega = np.asarray(resp.omega, dtype=float)
    weights = np.asarray(input)
    if weights.ndim == 0:
        mag, phase = np.asarray(resp.magnitude)[output, int(input)], np.asarray(resp.phase)[output, int(input)]
    else:
        H = getattr(resp, "response", None)
        H = np.asarray(resp.magnitude) * np.exp(1j * np.asarray(resp.phase)) if H is None else np.asarray(H)
        if weights.shape != (H.shape[1],) or not np.all(np.isfinite(weights)):
            raise ParameterError("input", f"expected an index or {H.shape[1]} finite weights (one per input), got {weights!r}")
        h = weights @ H[output]
        mag, phase = np.abs(h), np.angle(h)
    if axes is None:
        _, axes = plt.subplots(2, 1, sharex=True)
    ax_mag, ax_phase = axes
    ax_mag.loglog(omega, mag, label=label)
    ax_phase.semilogx(omega, np.degrees(np.unwrap(phase)), label=label)
    ax_mag.set_ylabel("|H|")
    ax_phase.set_ylabel("phase [deg]")
    ax_phase.set_xlabel("$\\omega$ [rad/s]")
    if label:
        ax_mag.legend(loc="best", fontsize="small")
    return axes
