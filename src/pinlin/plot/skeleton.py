"""The kinematic tree as a stick figure, and a mode's motion of it.

A :class:`Skeleton` fixes what a stick figure shows of a scene (independent of
the configuration): the world origin, every joint origin, a few frame origins
(the ends of links, the frames elements and constraints attach to, the frames
that carry wrenches), and the segments joining each point to its parent joint.
Its geometry at a configuration q comes from Pinocchio's forward kinematics in
the calling thread's workspace (:func:`pinlin.model.evaluation.workspace`),
never from a ``Data`` of its own.

:func:`mode_motion` moves it along a mode (theory: spectrum, constraints): with the
mode's joint displacement e (``sys.basis @ z`` with constraints, z itself
without; complex for damped and gyroscopic modes), normalized so that its
largest entry is 1, the configuration at phase theta [rad] is

.. math::

    q(\\theta) = q_0 \\oplus a \\, \\mathrm{Re}(e \\, e^{i\\theta})

(``pin.integrate``), so every coordinate moves with its own phase.  The
amplitude a [rad or m] is the largest joint displacement.  The picture is the
linear mode carried to a finite amplitude: closed loops open by O(a^2).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..errors import ParameterError
from ..model.evaluation import workspace

__all__ = ["Skeleton", "ModeMotion", "mode_motion", "MODE_AMPLITUDE_FRACTION"]

#: With ``scale=None`` the largest point of the stick figure moves this fraction of the figure's size
#: (first-order estimate): large enough to see, small enough that the finite-amplitude picture stays
#: close to the linear mode it shows.
MODE_AMPLITUDE_FRACTION = 0.1
#: Joint kinds whose origin is not tied to the world by a fixed link: no segment joins them to the world.
_FLOATING_JOINTS = ("JointModelFreeFlyer", "JointModelPlanar")


def _attached_frames(scene) -> list[str]:
    """Frames that elements and constraints attach to (``frame`` and a frame ``target``)."""
    out = []
    for item in tuple(scene.elements) + tuple(scene.constraints):
        for attr in ("frame", "target"):
            name = getattr(item, attr, None)
            if isinstance(name, str):
                out.append(name)
    return out


def _link_ends(model) -> list[str]:
    """Body frames away from their joint's origin (link ends, tools), one per distinct place."""
    out, seen = [], set()
    for frame in model.frames:
        if frame.type != pin.FrameType.BODY or not np.any(frame.placement.translation):
            continue
        key = (frame.parentJoint, tuple(np.round(frame.placement.translation, 12)))
        if key not in seen:
            seen.add(key)
            out.append(frame.name)
    return out


class Skeleton:
    """What a stick figure of a scene draws: points and the segments joining them.

    Points, in order: the world origin (index 0), the origin of every joint
    (index = Pinocchio joint id), then the frames in :attr:`frame_names`.

    Parameters
    ----------
    scene : Scene
    frames : sequence of str, optional
        Frames drawn besides the joints; default: the ends of links (body frames
        away from their joint's origin) and the frames that elements and
        constraints attach to.  The frames that carry wrenches are always drawn.

    Raises
    ------
    FrameNotFoundError
        An unknown frame name.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> skeleton = pinlin.plot.Skeleton(pinlin.Scene(robot))
    >>> skeleton.positions(np.zeros(2)).shape
    (4, 3)
    """

    def __init__(self, scene, frames: Sequence[str] | None = None):
        model = scene.model
        self.scene = scene
        self.wrench_names = tuple(dict.fromkeys(e.frame for e in scene.wrenches))
        chosen = _link_ends(model) + _attached_frames(scene) if frames is None else list(frames)
        self.frame_names = tuple(dict.fromkeys(list(chosen) + list(self.wrench_names)))
        self.frame_ids = tuple(scene.robot.frame_id(name) for name in self.frame_names)
        self.joint_names = tuple(model.names[j] for j in range(1, model.njoints))
        nj = model.njoints
        segments = [
            (model.parents[j], j)
            for j in range(1, nj)
            if model.parents[j] or model.joints[j].shortname() not in _FLOATING_JOINTS
        ]
        segments += [(model.frames[f].parentJoint, nj + i) for i, f in enumerate(self.frame_ids)]
        #: (segments, 2) indices of the points each segment joins.
        self.segments = np.array(segments, dtype=int).reshape(-1, 2)
        #: Indices of the joint origins, the drawn frames and the frames carrying wrenches among the points.
        self.joint_points = np.arange(1, nj)
        self.frame_points = nj + np.arange(len(self.frame_ids))
        self.wrench_points = np.array([nj + self.frame_names.index(w) for w in self.wrench_names], dtype=int)

    @property
    def size(self) -> int:
        """Number of points."""
        return self.scene.model.njoints + len(self.frame_ids)

    def positions(self, q: np.ndarray) -> np.ndarray:
        """World positions [m] of the points at configuration q, (points, 3).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> skeleton = pinlin.plot.Skeleton(pinlin.Scene(robot))
        >>> np.round(skeleton.positions(np.zeros(2))[-1], 6)
        array([ 0. ,  0. , -1.2])
        """
        model = self.scene.model
        data = workspace(self.scene).data
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)
        joints = [data.oMi[j].translation for j in range(model.njoints)]
        return np.array(joints + [data.oMf[f].translation for f in self.frame_ids]).reshape(-1, 3)

    def jacobians(self, q: np.ndarray) -> np.ndarray:
        """Linear velocity Jacobians [m per unit of v] of the points, world axes, (points, 3, nv).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> skeleton = pinlin.plot.Skeleton(pinlin.Scene(robot))
        >>> skeleton.jacobians(np.zeros(2)).shape  # (points, 3, nv)
        (4, 3, 2)
        """
        model = self.scene.model
        data = workspace(self.scene).data
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
        out = np.zeros((self.size, 3, model.nv))
        for j in range(1, model.njoints):
            out[j] = np.reshape(pin.getJointJacobian(model, data, j, frame), (6, model.nv))[:3]
        for i, f in enumerate(self.frame_ids):
            out[model.njoints + i] = np.reshape(pin.getFrameJacobian(model, data, f, frame), (6, model.nv))[:3]
        return out


@dataclass(frozen=True)
class ModeMotion:
    """A stick figure at the operating point and moved along a mode at given phases.

    Attributes
    ----------
    skeleton : Skeleton
    rest : (points, 3) ndarray
        Positions [m] at the operating point.
    positions : (phases, points, 3) ndarray
        Positions [m] at each phase.
    configurations : (phases, nq) ndarray
        The configurations q(theta) drawn.
    phases : (phases,) ndarray
        theta [rad].
    shape : (nv,) complex ndarray
        The normalized joint displacement e (largest entry 1), zero on prescribed joints.
    scale : float
        The amplitude a [rad or m]: the largest joint displacement.
    eigenvalue : complex or None
        lambda [1/s] of the mode, when it was given by its index.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot)
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> motion = pinlin.plot.mode_motion(scene, sys, 0, [0.0, np.pi / 2])
    >>> np.round(motion.rest, 6) + 0.0
    array([[ 0. ,  0. ,  0. ],
           [ 0. ,  0. ,  0. ],
           [ 0. ,  0. , -0.7],
           [ 0. ,  0. , -1.2]])
    """

    skeleton: Skeleton
    rest: np.ndarray
    positions: np.ndarray
    configurations: np.ndarray
    phases: np.ndarray
    shape: np.ndarray
    scale: float
    eigenvalue: complex | None

    def title(self) -> str:
        """A one-line description: the eigenvalue when known, and the amplitude.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> scene = pinlin.Scene(robot)
        >>> sys = pinlin.linearize(scene, np.zeros(2))
        >>> print(pinlin.plot.mode_motion(scene, sys, 0, [0.0]).title())
        $\\lambda$ = 0 + 3.472i 1/s, amplitude 0.084
        """
        amplitude = f"amplitude {self.scale:.3g}"
        if self.eigenvalue is None:
            return f"mode shape, {amplitude}"
        lam = self.eigenvalue
        return f"$\\lambda$ = {lam.real:.4g} {'+' if lam.imag >= 0 else '-'} {abs(lam.imag):.4g}i 1/s, {amplitude}"


def _mode_vector(sys, mode, modes) -> tuple[np.ndarray, complex | None]:
    """The mode's coordinates z (n,) and its eigenvalue (None for a given vector)."""
    if isinstance(mode, (int, np.integer)) and not isinstance(mode, (bool, np.bool_)):
        if modes is None:
            from ..spectral import modal_analysis

            modes = modal_analysis(sys)
        count = len(modes.eigenvalues)
        if np.shape(modes.right)[0] != sys.n:
            raise ParameterError("modes", f"has vectors of length {np.shape(modes.right)[0]}, the system has n = {sys.n}")
        if not -count <= int(mode) < count:
            raise ParameterError("mode", f"expected an index into modes.eigenvalues, 0 to {count - 1} "
                                 f"(or -{count} to -1 from the end, as in Python), got {mode}")
        return np.asarray(modes.right)[:, int(mode)], complex(modes.eigenvalues[int(mode)])
    z = np.asarray(mode)
    if z.shape != (sys.n,) or not np.issubdtype(z.dtype, np.number) or not np.all(np.isfinite(z)):
        raise ParameterError("mode", f"expected an index or {sys.n} finite values (the coordinates), got shape {z.shape}")
    if not np.any(z):
        raise ParameterError("mode", "is zero: no motion to draw")
    return z.astype(complex), None


def _joint_shape(scene, sys, z: np.ndarray) -> np.ndarray:
    """e (nv,): the mode on all joints, normalized to largest entry 1 (zero on prescribed joints)."""
    basis = getattr(sys, "basis", None)
    if basis is None:
        if sys.n != scene.n or (sys.dof_names and tuple(sys.dof_names) != tuple(scene.dof_names)):
            raise ParameterError("sys", f"has coordinates {list(sys.dof_names)}, the scene {list(scene.dof_names)}")
        free = z
    else:
        if np.shape(basis)[0] != scene.n:
            raise ParameterError("sys", f"has a basis of {np.shape(basis)[0]} rows, the scene has {scene.n} free dofs")
        free = np.asarray(basis) @ z
    if not np.any(free):
        raise ParameterError("mode", "moves no joint")
    e = np.zeros(scene.model.nv, dtype=complex)
    e[scene.free_dofs] = free / free[np.argmax(np.abs(free))]
    return e


def _auto_scale(skeleton: Skeleton, q0: np.ndarray, rest: np.ndarray, e: np.ndarray, fraction: float) -> float:
    """a such that the fastest point moves ``fraction`` of the figure's size (first order)."""
    size = float(np.linalg.norm(rest.max(axis=0) - rest.min(axis=0)))
    speed = float(np.max(np.linalg.norm(skeleton.jacobians(q0) @ e, axis=1)))
    if size == 0.0 or speed <= np.finfo(float).tiny:
        raise ParameterError("scale", "the mode moves none of the drawn points (or the figure is a single point); "
                                      "give scale= [rad or m] or frames= to draw")
    return fraction * size / speed


def mode_motion(scene, sys, mode, phases, *, scale: float | None = None, frames: Sequence[str] | None = None,
                modes=None, q=None, fraction: float = MODE_AMPLITUDE_FRACTION) -> ModeMotion:
    """The stick figure of ``scene`` at the operating point and moved along a mode at ``phases``.

    .. math::  q(\\theta) = q_0 \\oplus a \\, \\mathrm{Re}(e \\, e^{i\\theta}), \\quad e = B z / (B z)_{max}

    (B = ``sys.basis`` with constraints, else the identity; theory: spectrum, constraints.)

    Parameters
    ----------
    scene : Scene
        The scene ``sys`` was linearized from.
    sys : LinearizedSystem
    mode : int or (n,) array_like
        An index into ``modes.eigenvalues`` (Modes order, 0-based: row ``mode + 1``
        of ``modes.table()``; a negative index counts from the end, as in
        Python), or a mode shape on the coordinates (complex allowed).
    phases : (k,) array_like
        theta [rad] of each drawing.
    scale : float, optional
        The amplitude a [rad or m] of the largest joint displacement; default: the
        fastest point moves ``fraction`` of the figure's size.
    frames : sequence of str, optional
        Frames drawn besides the joints (see :class:`Skeleton`).
    modes : Modes, optional
        ``modal_analysis(sys)``, when already computed (used for an index ``mode``).
    q : (nq,) array_like, optional
        The operating point; default ``sys.q``.
    fraction : float
        See ``scale`` and :data:`MODE_AMPLITUDE_FRACTION`.

    Returns
    -------
    ModeMotion

    Raises
    ------
    ParameterError
        A ``mode`` index out of range or a vector of the wrong size, a system
        that does not belong to the scene, no operating point, non-finite
        phases, a scale that is not positive, a mode that moves no drawn point.
    ConfigurationError
        ``q`` of the wrong size or not finite.
    FrameNotFoundError
        An unknown frame name.
    ModelTooLargeError
        The calling thread's Pinocchio workspace for the scene would not fit in memory.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot)
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> motion = pinlin.plot.mode_motion(scene, sys, 0, [0.0, np.pi / 2])
    >>> motion.positions.shape  # (phases, points, 3)
    (2, 4, 3)
    """
    q0 = getattr(sys, "q", None) if q is None else q
    if q0 is None:
        raise ParameterError("q", "the system has no operating point (built from matrices): pass q=")
    q0 = scene.check_configuration(q0)
    theta = np.atleast_1d(np.asarray(phases, dtype=float))
    if theta.ndim != 1 or not np.all(np.isfinite(theta)):
        raise ParameterError("phases", f"expected finite phases [rad] in a 1-D array, got {phases!r}")
    if not (np.isfinite(fraction) and fraction > 0):
        raise ParameterError("fraction", f"must be positive and finite, got {fraction!r}")
    z, lam = _mode_vector(sys, mode, modes)
    e = _joint_shape(scene, sys, z)
    skeleton = Skeleton(scene, frames)
    rest = skeleton.positions(q0)
    if scale is None:
        scale = _auto_scale(skeleton, q0, rest, e, fraction)
    elif not (np.isfinite(scale) and scale > 0):
        raise ParameterError("scale", f"must be positive and finite, got {scale!r}")
    model = scene.model
    configs = np.array([pin.integrate(model, q0, scale * np.real(e * np.exp(1j * t))) for t in theta])
    positions = np.array([skeleton.positions(c) for c in configs])
    return ModeMotion(skeleton, rest, positions, configs, theta, e, float(scale), lam)
