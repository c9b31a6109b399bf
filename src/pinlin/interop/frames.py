"""Frame inputs and outputs at the operating point: wrench columns of B and frame rows of C.

At the operating point q0 of a system linearized from a scene, a deviation x
of the coordinates moves the origin of frame f by

.. math::  \\delta p = J_f(q_0)\\, T\\, x,  \\qquad \\delta\\dot p = J_f(q_0)\\, T\\, \\dot x

with J_f the linear rows of the frame Jacobian in world-aligned axes
(LOCAL_WORLD_ALIGNED) on the free joint velocities, and T the map from the
system's coordinates to them: the identity, or ``sys.basis`` for a constrained
system (joint velocities = basis @ z).  A wrench w at f enters as the
generalized force ``T^T Q`` with ``Q = J^T w`` (:func:`pinlin.generalized_force`).

With prescribed joints that move (``Scene(prescribed=...)`` at a nonzero
speed), a frame carried by them moves too, and its world-axes quantities would
be time-periodic: each frame signal is recomputed with every moving prescribed
joint advanced by :data:`~pinlin.linearization.linearize.PERIODIC_TEST_ANGLES`,
and refused (:class:`~pinlin.TimePeriodicError`) when it changes, as
:func:`pinlin.linearize` does for the matrices.  For outputs, the frame origin
must moreover not move with those joints (``J_f`` has no column on them), or
its velocity would have a term in ``(dJ/dq) v0`` that the constant model lacks.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..errors import InputError, ParameterError, TimePeriodicError
from ..linearization.linearize import PERIODIC_TEST_ANGLES, generalized_force
from ..model.evaluation import Evaluation
from ..model.scene import Scene
from ..numerics.norms import fro
from .signal_names import Signal

__all__ = ["OperatingPoint", "system_basis"]



def system_basis(sys, scene: Scene) -> np.ndarray:
    """T: free joint velocities = T @ (the system's coordinate rates), (n_free, n).

    The identity when ``sys`` has no ``basis`` attribute (or it is None), after
    checking that ``sys`` has the scene's coordinates; else ``sys.basis`` with
    nv or n_free rows (rows of prescribed joints dropped).

    Raises
    ------
    InputError
        ``sys`` was not linearized from ``scene`` (other coordinates or basis shape).

    Examples
    --------
    >>> from pinlin.interop.frames import system_basis
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> system_basis(sys, scene)  # an open tree: its coordinates are the joints'
    array([[1., 0.],
           [0., 1.]])
    """
    basis = getattr(sys, "basis", None)
    nfree = len(scene.free_dofs)
    if basis is None:
        if tuple(sys.dof_names) != tuple(scene.dof_names):
            raise InputError(
                f"the system's coordinates {list(sys.dof_names)} are not the scene's {list(scene.dof_names)}: "
                f"pass the scene the system was linearized from"
            )
        return np.eye(nfree)
    basis = np.asarray(basis, dtype=float)
    if basis.ndim != 2 or basis.shape[1] != sys.n or basis.shape[0] not in (scene.model.nv, nfree):
        raise InputError(
            f"sys.basis has shape {basis.shape}; expected ({scene.model.nv} or {nfree}, {sys.n}) "
            f"for this scene: pass the scene the system was linearized from"
        )
    return basis[scene.free_dofs] if basis.shape[0] == scene.model.nv and nfree != scene.model.nv else basis


class OperatingPoint:
    """The scene's kinematics at ``sys.q``, giving the B columns and C rows of frame signals.

    Parameters
    ----------
    sys : LinearizedSystem
        Linearized from ``scene`` (``sys.q`` set).
    scene : Scene
    periodic_tol : float
        Largest relative change of a frame signal's row or column when a moving
        prescribed joint is advanced (see the module docstring).

    Raises
    ------
    ParameterError
        ``scene`` is not a Scene.
    InputError
        ``sys`` has no operating point or does not belong to ``scene``.
    ConfigurationError
        ``sys.q`` does not fit the scene's robot.

    Examples
    --------
    Hanging straight down, the tip (1.2 m below the base) moves in -x for positive joint angles:

    >>> from pinlin.interop import parse_inputs, parse_outputs
    >>> from pinlin.interop.frames import OperatingPoint
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> point = OperatingPoint(sys, scene, periodic_tol=1e-9)
    >>> point.output_row(parse_outputs("position:tip:x", sys.dof_names)[0])
    array([-1.2, -0.5])
    >>> point.input_column(parse_inputs("dead:tip:fx", sys.dof_names)[0])
    array([-1.2, -0.5])
    """

    def __init__(self, sys, scene: Scene, periodic_tol: float):
        if not isinstance(scene, Scene):
            raise ParameterError(
                "scene", f"expected the pinlin.Scene the system was linearized from, got {scene!r}"
            )
        if sys.q is None:
            raise InputError(
                "this system has no operating point (sys.q is None: built from matrices); frame inputs and "
                "outputs need a system from pinlin.linearize and its scene"
            )
        self.scene = scene
        self.T = system_basis(sys, scene)
        self.q = scene.check_configuration(sys.q, "sys.q")
        self.periodic_tol = periodic_tol
        #: Prescribed joints that move: (name, velocity index).
        self.moving = [
            (name, scene.robot.joint(name).idx_v) for name, speed in scene.prescribed.items() if speed != 0
        ]
        self._jacobians: dict[tuple[str, str | None, float, pin.ReferenceFrame], np.ndarray] = {}

    def _configuration(self, joint: str | None, offset: float) -> np.ndarray:
        if joint is None:
            return self.q
        dq = np.zeros(self.scene.model.nv)
        dq[self.scene.robot.joint(joint).idx_v] = offset
        return pin.integrate(self.scene.model, self.q, dq)

    def _jacobian(
        self,
        frame: str,
        joint: str | None = None,
        offset: float = 0.0,
        reference: pin.ReferenceFrame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED,
    ) -> np.ndarray:
        """Frame Jacobian (6, nv) at q0, or with prescribed ``joint`` advanced by ``offset``.

        Each comes from a fresh :class:`Evaluation` and is kept as a copy: evaluations share
        the thread's Pinocchio data, so an earlier one must not be read after a later one ran.
        """
        key = (frame, joint, offset, reference)
        if key not in self._jacobians:
            fid = self.scene.robot.frame_id(frame)
            ev = Evaluation(self.scene, self._configuration(joint, offset), self.scene.v0)
            self._jacobians[key] = np.array(ev.frame_jacobian(fid, reference))
        return self._jacobians[key]

    def _check_invariant(self, signal: Signal, value: np.ndarray, compute, scale: float) -> None:
        """Refuse a frame signal that changes, relative to ``scale``, when a moving prescribed joint advances."""
        scale = max(scale, np.finfo(float).tiny)
        for joint, _ in self.moving:
            for offset in PERIODIC_TEST_ANGLES:
                change = fro(compute(joint, offset) - value) / scale
                if change > self.periodic_tol:
                    raise TimePeriodicError(
                        f"signal {signal.name!r} depends on the position of prescribed joint {joint!r} "
                        f"(relative change {change:.2e} when it advances by {offset}): with its prescribed velocity "
                        f"it is time-periodic; use a frame the prescribed joint does not carry, a follower "
                        f"wrench, or the coordinates",
                        joint=joint,
                        variation=change,
                    )

    def output_row(self, signal: Signal) -> np.ndarray:
        """Row of C on the coordinates (position) or the rates (velocity) for a frame output, (n,).

        Raises
        ------
        FrameNotFoundError
            The frame is not in the robot.
        TimePeriodicError
            The frame moves with a prescribed joint (see the module docstring).
        """
        free = self.scene.free_dofs
        J = self._jacobian(signal.target)[:3]
        for joint, idx in self.moving:
            carried = np.linalg.norm(J[:, idx]) / max(fro(J), np.finfo(float).tiny)
            if carried > self.periodic_tol:
                raise TimePeriodicError(
                    f"frame {signal.target!r} is carried around by prescribed joint {joint!r} "
                    f"(|dp/d{joint}| / |J| = {carried:.2e}): its world-axes position and velocity are "
                    f"time-periodic; use a frame the prescribed joint does not carry, or the coordinates",
                    joint=joint,
                    variation=carried,
                )
        rows = J[:, free] @ self.T
        self._check_invariant(
            signal,
            rows,
            lambda j, o: self._jacobian(signal.target, j, o)[:3, free] @ self.T,
            scale=fro(rows),
        )
        return rows[signal.index]

    def input_column(self, signal: Signal) -> np.ndarray:
        """Generalized force of the signal's unit wrench on the system's coordinates, ``T^T Q`` (n,).

        Raises
        ------
        FrameNotFoundError
            The frame is not in the robot.
        TimePeriodicError
            The force changes with the position of a moving prescribed joint.
        """
        column = self.T.T @ generalized_force(self.scene, self.q, signal.wrench)
        if self.moving:
            # the size of J^T w for any direction of w: the forces' own scale, also when this one vanishes
            J = self._jacobian(signal.target, reference=pin.ReferenceFrame.LOCAL)
            wrench = np.concatenate([signal.wrench.force, signal.wrench.torque])
            self._check_invariant(
                signal,
                column,
                lambda j, o: (
                    self.T.T @ generalized_force(self.scene, self._configuration(j, o), signal.wrench)
                ),
                scale=max(fro(column), fro(J[:, self.scene.free_dofs] @ self.T) * fro(wrench)),
            )
        return column
