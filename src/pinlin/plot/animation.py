"""A mode shape, animated: the stick figure moving through one cycle of a mode.

:func:`animate_mode` returns a :class:`matplotlib.animation.FuncAnimation`
that saves as a GIF through pillow (a dependency of matplotlib)::

    anim = pinlin.plot.animate_mode(scene, sys, 0)
    anim.save("mode1.gif", writer="pillow")

or plays in a notebook: ``IPython.display.HTML(anim.to_jshtml())``.  Frame k
shows phase theta_k = 2 pi k / n_frames [rad] of the motion of
:func:`~pinlin.plot.skeleton.mode_motion`, so a complex mode (damped,
gyroscopic) moves every coordinate with its own phase.  Without ``ax`` the
animation draws on a figure of its own, not registered with pyplot: nothing
is left open in an interactive session and a notebook shows only the animation.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import ParameterError
from .mode_shapes import StickArtists, plane_axes, prepare_axes, set_limits
from .skeleton import MODE_AMPLITUDE_FRACTION, mode_motion
from .style import DARK, GREY, pyplot

__all__ = ["animate_mode", "DEFAULT_FRAMES", "DEFAULT_DURATION", "FIGSIZE"]

#: Frames per cycle: smooth at the default speed, and a GIF of a few hundred kB at most.
DEFAULT_FRAMES = 24
#: Seconds per cycle: slow enough to follow the phase differences of a complex mode.
DEFAULT_DURATION = 2.0
#: Size [in] of the animation's own figure: square, as the drawing has equal axes.
FIGSIZE = (5.0, 5.0)


def animate_mode(scene, sys, mode, ax=None, *, n_frames: int = DEFAULT_FRAMES, duration: float = DEFAULT_DURATION,
                 scale: float | None = None, plane: str | None = None, frames: Sequence[str] | None = None,
                 modes=None, q=None, fraction: float = MODE_AMPLITUDE_FRACTION, dpi: float = 80.0):
    """One cycle of a mode as a matplotlib animation of the scene's stick figure.

    Frame k draws the configuration at phase theta_k = 2 pi k / ``n_frames``

    .. math::  q(\\theta_k) = q_0 \\oplus a \\, \\mathrm{Re}(e \\, e^{i\\theta_k})

    over the operating point (grey, dashed), with e the mode on all joints
    (``sys.basis @ z`` with constraints), largest entry 1 (theory: spectrum, constraints).

    Parameters
    ----------
    scene : Scene
        The scene ``sys`` was linearized from.
    sys : LinearizedSystem
    mode : int or (n,) array_like
        An index into ``modes.eigenvalues`` (0-based; row ``mode + 1`` of
        ``modes.table()``; -1 is the last, as in Python) or a mode shape on the coordinates (complex allowed).
    ax : matplotlib Axes, optional
        Draw here (3-D axes without ``plane``, 2-D with one); default: a figure of
        the animation's own, :data:`FIGSIZE` inches at ``dpi``.
    n_frames : int
        Frames per cycle (at least 2).
    duration : float
        Seconds [s] per cycle when played.
    scale : float, optional
        Amplitude a [rad or m] of the largest joint displacement; default: the
        fastest point moves ``fraction`` of the figure's size.
    plane : str, optional
        Two world axes to project on, such as ``"xz"``; None animates in 3-D.
    frames : sequence of str, optional
        Frames drawn besides the joints; those carrying wrenches always are.
    modes : Modes, optional
        ``modal_analysis(sys)`` when already computed.
    q : (nq,) array_like, optional
        The operating point; default ``sys.q``.
    fraction : float
        See ``scale``.
    dpi : float
        Resolution of the animation's own figure [dots per inch].

    Returns
    -------
    matplotlib.animation.FuncAnimation
        ``.save(path, writer="pillow")`` writes a GIF; ``.to_jshtml()`` embeds it in a notebook.

    Raises
    ------
    ParameterError
        ``n_frames`` below 2, a ``duration`` or ``dpi`` that is not positive, and
        everything :func:`~pinlin.plot.mode_shape` rejects.
    ConfigurationError
        ``q`` of the wrong size or not finite.
    FrameNotFoundError
        An unknown frame name.
    MissingDependencyError
        matplotlib is not installed.
    ModelTooLargeError
        The calling thread's Pinocchio workspace for the scene would not fit in memory.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot)
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> animation = pinlin.plot.animate_mode(scene, sys, 0, n_frames=4)
    >>> type(animation).__name__
    'FuncAnimation'
    """
    if isinstance(n_frames, bool) or not isinstance(n_frames, (int, np.integer)) or n_frames < 2:
        raise ParameterError("n_frames", f"expected an integer >= 2, got {n_frames!r}")
    for name, value in (("duration", duration), ("dpi", dpi)):
        if not (np.isfinite(value) and value > 0):
            raise ParameterError(name, f"must be positive and finite, got {value!r}")
    axes = plane_axes(plane)
    theta = 2 * np.pi * np.arange(n_frames) / n_frames
    motion = mode_motion(scene, sys, mode, theta, scale=scale, frames=frames, modes=modes, q=q, fraction=fraction)
    pyplot()  # the MissingDependencyError, before matplotlib's own modules are imported
    from matplotlib.animation import FuncAnimation
    from matplotlib.figure import Figure

    ax = prepare_axes(ax, plane, figure=Figure(figsize=FIGSIZE, dpi=dpi) if ax is None else None)
    StickArtists(ax, motion.skeleton, motion.rest, axes, "rest", GREY, label="operating point", linestyle="--")
    moving = StickArtists(ax, motion.skeleton, motion.positions[0], axes, "mode", DARK, label="mode")
    set_limits(ax, np.concatenate([motion.rest[None], motion.positions]), axes)
    ax.set_title(motion.title(), fontsize="medium")
    ax.legend(loc="upper right", fontsize="small")
    text = (ax.text2D if axes is None else ax.text)(0.02, 0.95, "", transform=ax.transAxes, gid="phase")

    def draw(k: int) -> list:
        text.set_text(f"phase {np.degrees(theta[k]):.0f} deg")
        return [*moving.update(motion.positions[k]), text]

    draw(0)
    return FuncAnimation(ax.figure, draw, frames=n_frames, interval=1000.0 * duration / n_frames, blit=False)
