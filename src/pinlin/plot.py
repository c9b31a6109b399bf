"""Plots of spectra, loci, Campbell diagrams, stability maps, responses and chain modes.

matplotlib is an optional extra (``pip install 'pinlin[plot]'``).  Every function
takes an optional ``ax`` (or ``axes``) to draw into and returns it, so plots
compose into the user's own figures; without matplotlib each raises
:class:`~pinlin.errors.MissingDependencyError`.  Conventions (docs/conventions.md): lambda
[1/s] in the complex plane, frequencies omega [rad/s], phases in degrees.  No
function here runs Pinocchio in a ``Data`` of its own making: kinematics go
through the calling thread's workspace (:func:`pinlin.linearization.workspace.workspace`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pinocchio as pin

from .errors import MissingDependencyError, ParameterError
from .linearization.workspace import workspace
from .studies.tracking import one_per_conjugate_pair, track_modes

__all__ = [
    "eigenvalue_map", "root_locus", "campbell", "stability_map", "frequency_response", "chain_mode_shape",
    "work_precision", "VERDICT_COLORS", "KIND_STYLE", "AXIS_MARGIN", "MIN_REAL_SPAN_FRACTION", "UNSTABLE_RTOL",
]

#: Colours of the stability verdicts in maps and eigenvalue plots.
VERDICT_COLORS = {
    "asymptotically_stable": "#2a9d8f",
    "marginally_stable": "#8ecae6",
    "divergence": "#f4a261",
    "flutter": "#e63946",
    "undecided": "#adb5bd",
}

#: Marker and colour of each mode kind (exactly :data:`pinlin.spectral.MODE_KINDS`) in eigenvalue maps.
KIND_STYLE = {
    "underdamped": ("o", "#264653"),
    "overdamped": ("s", "#2a9d8f"),
    "rigid_body": ("x", "#6c757d"),
    "unstable": ("^", "#e63946"),
}
#: Marker and colour of plain eigenvalues (no mode kinds given).
_PLAIN_STYLE = ("o", "#264653")
#: Colours of reference geometry (traces, the equilibrium of a mode shape), error bars, drawn shapes.
_GREY, _MID_GREY, _DARK = "#adb5bd", "#6c757d", "#264653"
#: Line widths: the imaginary axis (the stability boundary), the real axis, thin traces, curves.
_AXIS_LW, _REAL_AXIS_LW, _TRACE_LW, _CURVE_LW = 0.8, 0.4, 1.0, 1.5
#: Marker size of sampled points (root loci, unstable Campbell points).
_POINT_SIZE = 12

#: Axis limits reach this factor beyond the outermost eigenvalue, so markers are not cut at the frame.
AXIS_MARGIN = 1.15
#: The real axis of an eigenvalue map spans at least this fraction of the largest |lambda|, so the
#: error bars of an undamped spectrum (~1e-14) do not set the scale.
MIN_REAL_SPAN_FRACTION = 0.1
#: Default of ``campbell(rtol=...)``: Re lambda below this fraction of the step's largest |lambda| is
#: rounding of an undamped spectrum (~1e-16 |lambda|), not instability.
UNSTABLE_RTOL = 1e-9


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as exc:  # pragma: no cover - exercised only without the extra
        raise MissingDependencyError("pinlin.plot needs matplotlib: pip install 'pinlin[plot]'") from exc
    return plt


def _ax(ax):
    if ax is None:
        _, ax = _pyplot().subplots()
    return ax


def _complex_plane_labels(ax) -> None:
    ax.axvline(0.0, color="k", lw=_AXIS_LW)
    ax.set(xlabel="Re $\\lambda$ [1/s]", ylabel="Im $\\lambda$ [rad/s]")


def eigenvalue_map(modes, ax=None, *, error_bars: bool = True, title: bool = True):
    """Eigenvalues lambda [1/s] in the complex plane, marked by mode kind, with their error bounds.

    Parameters
    ----------
    modes : Modes or array_like
        A :func:`pinlin.modal_analysis` result (uses ``kind``, ``error_bound``
        and ``stability`` when present) or plain eigenvalues.
    error_bars : bool
        Draw each eigenvalue's error bound [1/s] as a horizontal bar (its distance
        to the imaginary axis is what a stability verdict must beat).
    title : bool
        Title the axes with the stability verdict, when ``modes`` has one.

    Raises
    ------
    ParameterError
        Non-finite eigenvalues.
    """
    lam = np.asarray(getattr(modes, "eigenvalues", modes), dtype=complex).ravel()
    if not np.all(np.isfinite(lam)):
        raise ParameterError("eigenvalues", "has non-finite values")
    ax = _ax(ax)
    kinds = tuple(getattr(modes, "kind", ("eigenvalue",) * lam.size))
    for kind in dict.fromkeys(kinds):
        sel = np.array([k == kind for k in kinds])
        marker, color = KIND_STYLE.get(kind, _PLAIN_STYLE)
        ax.scatter(lam[sel].real, lam[sel].imag, marker=marker, color=color, label=kind.replace("_", " "), zorder=3)
    bound = getattr(modes, "error_bound", None)
    if error_bars and bound is not None:
        ax.errorbar(lam.real, lam.imag, xerr=np.asarray(bound, float), fmt="none", ecolor=_MID_GREY, lw=_TRACE_LW, zorder=2)
    ax.axhline(0.0, color="k", lw=_REAL_AXIS_LW)
    span = max(AXIS_MARGIN * np.abs(lam.real).max(initial=0.0), MIN_REAL_SPAN_FRACTION * np.abs(lam).max(initial=0.0))
    span = span or 1.0  # all eigenvalues at 0: any symmetric window shows them
    ax.set_xlim(min(-span, AXIS_MARGIN * lam.real.min(initial=0.0)), max(span, AXIS_MARGIN * lam.real.max(initial=0.0)))
    _complex_plane_labels(ax)
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
    eigenvalues : (steps, m) array_like
    vectors : (steps, n, m) array_like, optional
        Mode shapes for :func:`pinlin.studies.track_modes`; without them modes
        are matched by eigenvalue distance.
    label : str
        Name of the parameter (colour bar).
    cmap : str
        matplotlib colour map of the parameter.

    Raises
    ------
    ParameterError
        Shapes that do not agree (``parameter`` and the steps, eigenvalues and
        vectors), non-finite values.
    """
    plt = _pyplot()
    ax = _ax(ax)
    p = np.asarray(parameter, dtype=float)
    tracked = track_modes(eigenvalues, vectors)
    if p.shape != (tracked.eigenvalues.shape[0],):
        raise ParameterError("parameter", f"expected {tracked.eigenvalues.shape[0]} values, got shape {p.shape}")
    lam = tracked.eigenvalues
    for j in range(lam.shape[1]):
        ax.plot(lam[:, j].real, lam[:, j].imag, color=_GREY, lw=_TRACE_LW, zorder=1)
    points = ax.scatter(lam.real.ravel(), lam.imag.ravel(), c=np.repeat(p, lam.shape[1]), cmap=cmap, s=_POINT_SIZE,
                        zorder=2)
    plt.colorbar(points, ax=ax, label=label)
    _complex_plane_labels(ax)
    return ax


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
    rotating ring) is drawn as a V instead of being dropped.

    Parameters
    ----------
    speed : (steps,) array_like
        Spin speed [rad/s].
    eigenvalues : (steps, m) array_like
    vectors : (steps, n, m) array_like, optional
        Mode shapes for the tracking; without them modes are matched by eigenvalue distance.
    orders : sequence of float
        Excitation orders drawn as lines k * speed.
    error_bounds : (steps, m) array_like, optional
        Error bounds [1/s] of the eigenvalues (``modes.error_bound`` of each
        step, in the same order as ``eigenvalues``): a point is marked unstable
        only when Re lambda exceeds its bound.
    rtol : float
        Re lambda must also exceed rtol times the step's largest |lambda| to be
        marked (see :data:`UNSTABLE_RTOL`).

    Raises
    ------
    ParameterError
        ``speed`` or ``error_bounds`` not matching the eigenvalues, a negative or
        non-finite ``rtol``, non-finite eigenvalues or vectors.
    """
    ax = _ax(ax)
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
        ax.plot(w, np.abs(lam[:, j].imag), lw=_CURVE_LW)
    unstable = lam[:, keep].real > threshold[:, keep]
    if np.any(unstable):
        ws = np.broadcast_to(w[:, None], unstable.shape)
        ax.scatter(ws[unstable], np.abs(lam[:, keep].imag)[unstable], color=VERDICT_COLORS["flutter"], s=_POINT_SIZE,
                   zorder=3, label="Re $\\lambda$ > 0")
        ax.legend(loc="best", fontsize="small")
    for k in orders:
        ax.plot(w, k * w, color="k", ls="--", lw=_AXIS_LW)
    ax.set(xlabel=label, ylabel="damped frequency |Im $\\lambda$| [rad/s]")
    return ax


def stability_map(x, y, kinds, ax=None, *, xlabel: str = "x", ylabel: str = "y"):
    """Stability verdicts over a two-parameter grid.

    Parameters
    ----------
    x : (nx,) array_like
    y : (ny,) array_like
    kinds : (ny, nx) array_like of str
        Verdict kinds (``modes.stability.kind``, one of :data:`VERDICT_COLORS`) at each grid point.

    Raises
    ------
    ParameterError
        ``kinds`` of the wrong shape or with an unknown verdict.
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    ax = _ax(ax)
    names = list(VERDICT_COLORS)
    k = np.asarray(kinds, dtype=object)
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if k.shape != (y.size, x.size):
        raise ParameterError("kinds", f"expected shape {(y.size, x.size)} (len(y), len(x)), got {k.shape}")
    unknown = {str(v) for v in k.ravel()} - set(names)
    if unknown:
        raise ParameterError("kinds", f"unknown verdicts {sorted(unknown)}; expected {names}")
    codes = np.vectorize(names.index)(k.astype(str)).astype(float)
    # one colour per verdict code: bins centred on the integers 0 .. len(names) - 1
    cmap = ListedColormap(list(VERDICT_COLORS.values()))
    ax.pcolormesh(x, y, codes, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5, shading="nearest")
    patches = [Patch(color=VERDICT_COLORS[n], label=n.replace("_", " ")) for n in names if np.any(k == n)]
    ax.legend(handles=patches, loc="best", fontsize="small")
    ax.set(xlabel=xlabel, ylabel=ylabel)
    return ax


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

    Raises
    ------
    ParameterError
        Weights whose length is not the number of inputs, or not finite.
    """
    plt = _pyplot()
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


def chain_mode_shape(scene, q, mode, ax=None, *, scale: float = 0.2, plane: str = "xz", frames: Sequence[str] | None = None):
    """A planar chain at q and displaced along a mode shape; positions in [m].

    Parameters
    ----------
    scene : Scene
    q : (nq,) array_like
        The operating point.
    mode : (n,) array_like
        A mode shape on the free coordinates (complex allowed: its phase is
        turned so that the largest entry is real, its real part drawn,
        normalized to unit largest entry, times ``scale`` [rad or m]).
    plane : str
        The two world axes to draw, for example ``"xz"`` for chains swinging about y.
    frames : sequence of str, optional
        Frames joined by the drawn polyline; default: every joint frame in model
        order and ``tip`` when the model has it.

    Raises
    ------
    ParameterError
        A ``plane`` that is not two of x, y, z; a mode of the wrong size.
    ConfigurationError
        ``q`` of the wrong size or not finite.
    FrameNotFoundError
        An unknown frame name.
    ModelTooLargeError
        The calling thread's Pinocchio workspace for the scene would not fit in memory.
    """
    ax = _ax(ax)
    axes = ["xyz".index(c) for c in plane if c in "xyz"]
    if len(axes) != 2 or len(plane) != 2:
        raise ParameterError("plane", f"expected two of x, y, z, got {plane!r}")
    model = scene.model
    q = scene.check_configuration(q)
    x = np.asarray(mode)
    if x.shape != (scene.n,):
        raise ParameterError("mode", f"expected {scene.n} values (the free coordinates), got shape {x.shape}")
    real = np.real(x * np.exp(-1j * np.angle(x[np.argmax(np.abs(x))])))
    dv = np.zeros(model.nv)
    dv[scene.free_dofs] = scale * real / max(np.abs(real).max(), np.finfo(float).tiny)
    names = list(frames) if frames is not None else [model.names[j] for j in range(1, model.njoints)] + (
        ["tip"] if model.existFrame("tip") else []
    )
    ids = [scene.robot.frame_id(name) for name in names]
    data = workspace(scene).data  # behind the memory guard, owned by this thread

    def points(config):
        pin.framesForwardKinematics(model, data, config)
        return np.array([data.oMf[i].translation[axes] for i in ids])

    rest = points(q)
    moved = points(pin.integrate(model, q, dv))
    ax.plot(rest[:, 0], rest[:, 1], "o--", color=_GREY, label="equilibrium")
    ax.plot(moved[:, 0], moved[:, 1], "o-", color=_DARK, label="mode")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set(xlabel=f"{plane[0]} [m]", ylabel=f"{plane[1]} [m]")
    return ax


def work_precision(results: Mapping[str, tuple[Sequence[float], Sequence[float]]], ax=None):
    """Error against run time [s], log-log, one line per method.

    Parameters
    ----------
    results : mapping of label to (times [s], errors)
        Errors of zero are drawn at the smallest positive float (log axes).

    Raises
    ------
    ParameterError
        No results, or times and errors of different shapes.
    """
    ax = _ax(ax)
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
