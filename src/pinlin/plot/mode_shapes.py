"""Mode shapes as stick figures: the kinematic tree at the operating point and moved along a mode.

:func:`mode_shape` draws the tree (:class:`~pinlin.plot.skeleton.Skeleton`:
joint origins, links, link ends and the frames that carry wrenches; no meshes)
in 3-D or projected on a plane of two world axes, at rest (grey, dashed) and
moved along a mode at a few phases; :func:`chain_mode_shape` is the older,
simpler drawing of a planar chain along a given shape.  Positions are [m],
amplitudes [rad or m], phases [rad] in the call and [deg] in the legend.
Kinematics run in the calling thread's workspace.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from ..errors import ParameterError
from ..model.evaluation import workspace
from .skeleton import MODE_AMPLITUDE_FRACTION, ModeMotion, Skeleton, mode_motion
from .style import DARK, GREY, WRENCH_COLOR, new_axes, pyplot

__all__ = ["mode_shape", "chain_mode_shape", "StickArtists", "DEFAULT_PHASES", "PHASE_CMAP", "LIMIT_MARGIN"]

#: Phases [rad] drawn by :func:`mode_shape`: a quarter cycle apart, so a complex mode's travelling
#: motion shows as well as a standing one.
DEFAULT_PHASES = (0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi)
#: Colour map of the phases in :func:`mode_shape` (sampled up to 0.85: its lightest yellow is hard to see).
PHASE_CMAP = "viridis"
#: Axis limits reach this fraction of the drawing's size beyond its outermost point.
LIMIT_MARGIN = 0.08


def plane_axes(plane: str | None) -> tuple[int, int] | None:
    """The indices of a plane's two world axes (``"xz"`` -> (0, 2)); None for 3-D.

    Raises
    ------
    ParameterError
        Not two different letters of x, y, z.
    """
    if plane is None:
        return None
    if not isinstance(plane, str) or len(plane) != 2 or not set(plane) <= set("xyz") or plane[0] == plane[1]:
        raise ParameterError("plane", f"expected two of x, y, z (such as 'xz') or None for 3-D, got {plane!r}")
    return "xyz".index(plane[0]), "xyz".index(plane[1])


def prepare_axes(ax, plane: str | None, figure=None):
    """``ax`` checked against ``plane``, or new axes (3-D when ``plane`` is None) on ``figure`` or a pyplot figure.

    Raises
    ------
    ParameterError
        A 2-D ``ax`` without a plane, or a 3-D one with a plane.
    """
    if ax is None:
        fig = figure if figure is not None else pyplot().figure()
        return fig.add_subplot(projection="3d" if plane is None else None)
    is_3d = hasattr(ax, "zaxis")
    if is_3d != (plane is None):
        raise ParameterError("ax", "3-D axes (projection='3d') go with plane=None, 2-D axes with a plane such as 'xz'")
    return ax


class StickArtists:
    """The artists of one stick figure: links, joint origins, frames and wrench frames, updatable.

    Each artist carries a ``gid`` ``"{prefix}-links"``, ``"{prefix}-joints"``,
    ``"{prefix}-frames"`` (when frames are drawn) and ``"{prefix}-wrenches"``
    (when the scene has wrenches), so that figures can be inspected.

    Parameters
    ----------
    ax : matplotlib Axes (2-D or 3-D)
    skeleton : Skeleton
    points : (points, 3) ndarray
        Initial positions [m].
    plane : tuple of int or None
        World axes of a 2-D drawing; None for 3-D.
    prefix : str
        Start of the artists' ``gid``.
    color : str or tuple
        Colour of links and joints.
    label : str, optional
        Legend entry of the links.
    linestyle : str
        Of the links.
    """

    def __init__(self, ax, skeleton: Skeleton, points: np.ndarray, plane, prefix: str, color,
                 label: str | None = None, linestyle: str = "-"):
        self.ax, self.skeleton, self.plane = ax, skeleton, plane
        if plane is None:
            from mpl_toolkits.mplot3d.art3d import Line3DCollection

            self.links = Line3DCollection(self._segments(points), colors=[color], linestyles=linestyle, label=label)
            ax.add_collection3d(self.links)
        else:
            from matplotlib.collections import LineCollection

            self.links = LineCollection(self._segments(points), colors=[color], linestyles=linestyle, label=label)
            ax.add_collection(self.links)
        self.links.set_gid(f"{prefix}-links")
        self.markers = {"joints": self._points(points, skeleton.joint_points, "o", color, prefix, "joints")}
        if skeleton.frame_points.size:
            self.markers["frames"] = self._points(points, skeleton.frame_points, ".", color, prefix, "frames")
        if skeleton.wrench_points.size:
            self.markers["wrenches"] = self._points(points, skeleton.wrench_points, "^", WRENCH_COLOR, prefix,
                                                    "wrenches")

    def _coords(self, points: np.ndarray) -> np.ndarray:
        return points if self.plane is None else points[:, list(self.plane)]

    def _segments(self, points: np.ndarray) -> np.ndarray:
        return self._coords(points)[self.skeleton.segments]

    def _points(self, points, index, marker, color, prefix, name):
        xyz = self._coords(points[index]).T
        (line,) = self.ax.plot(*xyz, marker=marker, ls="none", color=color, gid=f"{prefix}-{name}")
        return line

    @property
    def artists(self) -> list:
        """The links collection and the marker lines."""
        return [self.links, *self.markers.values()]

    def update(self, points: np.ndarray) -> list:
        """Move every artist to ``points`` (points, 3) [m]; returns the artists."""
        self.links.set_segments(self._segments(points))
        index = {"joints": self.skeleton.joint_points, "frames": self.skeleton.frame_points,
                 "wrenches": self.skeleton.wrench_points}
        for name, line in self.markers.items():
            xyz = self._coords(points[index[name]]).T
            if self.plane is None:
                line.set_data_3d(*xyz)
            else:
                line.set_data(*xyz)
        return self.artists


def set_limits(ax, points: np.ndarray, plane, labels: bool = True) -> None:
    """Equal-aspect limits around ``points`` (..., 3) [m] with :data:`LIMIT_MARGIN`, and axis labels."""
    flat = points.reshape(-1, 3)
    low, high = flat.min(axis=0), flat.max(axis=0)
    half = 0.5 * max(float(np.max(high - low)), np.finfo(float).eps) * (1 + 2 * LIMIT_MARGIN)
    mid = 0.5 * (low + high)
    names = "xyz"
    if plane is None:
        ax.set(xlim=(mid[0] - half, mid[0] + half), ylim=(mid[1] - half, mid[1] + half),
               zlim=(mid[2] - half, mid[2] + half))
        ax.set_box_aspect((1, 1, 1))
        if labels:
            ax.set(xlabel="x [m]", ylabel="y [m]", zlabel="z [m]")
        return
    i, j = plane
    ax.set(xlim=(mid[i] - half, mid[i] + half), ylim=(mid[j] - half, mid[j] + half))
    ax.set_aspect("equal", adjustable="box")
    if labels:
        ax.set(xlabel=f"{names[i]} [m]", ylabel=f"{names[j]} [m]")


def mode_shape(scene, sys, mode, ax=None, *, phases: Sequence[float] = DEFAULT_PHASES, scale: float | None = None,
               plane: str | None = None, frames: Sequence[str] | None = None, modes=None, q=None,
               fraction: float = MODE_AMPLITUDE_FRACTION):
    """The kinematic tree at the operating point (grey) and moved along a mode at a few phases.

    Each phase theta [rad] draws the configuration

    .. math::  q(\\theta) = q_0 \\oplus a \\, \\mathrm{Re}(e \\, e^{i\\theta})

    with e the mode on all joints (``sys.basis @ z`` with constraints), largest
    entry 1: a complex mode (damped, gyroscopic) moves every coordinate with its
    own phase (theory: spectrum, constraints; :func:`~pinlin.plot.skeleton.mode_motion`).

    Parameters
    ----------
    scene : Scene
        The scene ``sys`` was linearized from.
    sys : LinearizedSystem
    mode : int or (n,) array_like
        An index into ``modes.eigenvalues`` (0-based; row ``mode + 1`` of
        ``modes.table()``) or a mode shape on the coordinates (complex allowed).
    ax : matplotlib Axes, optional
        3-D axes without ``plane``, 2-D axes with one; new axes by default.
    phases : sequence of float
        theta [rad] of the drawings (:data:`DEFAULT_PHASES`).
    scale : float, optional
        Amplitude a [rad or m] of the largest joint displacement; default: the
        fastest point moves ``fraction`` of the figure's size.
    plane : str, optional
        Two world axes to project on, such as ``"xz"``; None draws in 3-D.
    frames : sequence of str, optional
        Frames drawn besides the joints (default: link ends and the frames
        elements attach to); the frames carrying wrenches are always drawn (red triangles).
    modes : Modes, optional
        ``modal_analysis(sys)`` when already computed.
    q : (nq,) array_like, optional
        The operating point; default ``sys.q``.
    fraction : float
        See ``scale`` (:data:`~pinlin.plot.skeleton.MODE_AMPLITUDE_FRACTION`).

    Returns
    -------
    matplotlib Axes

    Raises
    ------
    ParameterError
        A bad ``plane``, ``ax`` of the wrong kind for it, a bad ``mode``, ``scale``
        or ``phases``, a system that does not belong to the scene or has no operating point.
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
    >>> ax = pinlin.plot.mode_shape(scene, sys, 0)
    >>> type(ax).__name__
    'Axes3D'
    """
    axes = plane_axes(plane)
    motion: ModeMotion = mode_motion(scene, sys, mode, phases, scale=scale, frames=frames, modes=modes, q=q,
                                     fraction=fraction)
    ax = prepare_axes(ax, plane)
    StickArtists(ax, motion.skeleton, motion.rest, axes, "rest", GREY, label="operating point", linestyle="--")
    colors = pyplot().get_cmap(PHASE_CMAP)(np.linspace(0.0, 0.85, len(motion.phases)))
    for theta, points, color in zip(motion.phases, motion.positions, colors):
        StickArtists(ax, motion.skeleton, points, axes, "mode", color, label=f"{np.degrees(theta):.0f} deg")
    set_limits(ax, np.concatenate([motion.rest[None], motion.positions]), axes)
    ax.set_title(motion.title(), fontsize="medium")
    ax.legend(loc="best", fontsize="small")
    return ax


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
    ax : matplotlib Axes, optional
        Where to draw; a new figure by default.
    scale : float
        The largest coordinate displacement [rad or m].
    plane : str
        The two world axes to draw, for example ``"xz"`` for chains swinging about y.
    frames : sequence of str, optional
        Frames joined by the drawn polyline; default: every joint frame in model
        order and ``tip`` when the model has it.

    Returns
    -------
    matplotlib Axes

    Raises
    ------
    ParameterError
        A ``plane`` that is not two of x, y, z; a mode of the wrong size.
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
    >>> modes = pinlin.modal_analysis(sys)
    >>> ax = pinlin.plot.chain_mode_shape(scene, np.zeros(2), modes.right[:, 0])
    >>> type(ax).__name__
    'Axes'
    """
    ax = new_axes(ax)
    axes = list(plane_axes(plane) or ())
    if not axes:
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
    ax.plot(rest[:, 0], rest[:, 1], "o--", color=GREY, label="equilibrium")
    ax.plot(moved[:, 0], moved[:, 1], "o-", color=DARK, label="mode")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set(xlabel=f"{plane[0]} [m]", ylabel=f"{plane[1]} [m]")
    return ax
