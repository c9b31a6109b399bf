"""The Pinocchio workspace a computation owns, and the evaluation of one point in it.

A :class:`~pinlin.Scene` is an immutable description shared freely, Pinocchio's
``Model`` included.  Pinocchio's ``Data`` is the mutable workspace its algorithms
write into, so it must belong to one caller at a time (Pinocchio's Model/Data split).
:func:`workspace` gives each thread its own :class:`Workspace` per scene, created
on that thread's first use (behind the memory guard) and reused afterwards:
``createData`` costs about 35-40 us on a 9-joint arm and 40-48 ms on a 100-link
chain, 4x and 60-80x a whole linearization, so a fresh one per call would be the
slower choice (benchmarks/bench_workspace.py measures both).  Within one thread computations
run one after another, and each copies what it reads out of ``Data`` before the
next algorithm runs, so nested calls (a linearization inside a simulation's
callback) are safe too.
"""

from __future__ import annotations

import threading
import weakref
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

if TYPE_CHECKING:  # pragma: no cover
    from ..model.scene import Scene

__all__ = ["Workspace", "workspace", "Evaluation", "symmetric_from_upper"]


def symmetric_from_upper(a: np.ndarray, lower: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """A copy of ``a`` with its strictly lower triangle mirrored from the upper one.

    Pinocchio's C++ ``crba`` fills only the upper triangle of M (its Python
    binding may or may not mirror it, depending on the version).
    """
    a = np.array(a)
    a[lower] = a.T[lower]
    return a


class Workspace:
    """Pinocchio ``Data`` for one scene's model, owned by one thread.

    Parameters
    ----------
    scene : Scene
        The data are created for ``scene.model`` through the robot's memory guard.

    Raises
    ------
    ModelTooLargeError
        Pinocchio's data would not fit in the memory allowed.
    """

    __slots__ = ("model", "data", "lower", "__weakref__")

    def __init__(self, scene: Scene):
        self.model = scene.model
        self.data = scene.robot.create_data(scene.model, scene.memory_limit)
        #: Strict lower-triangle indices, for mirroring Pinocchio's upper-triangular M.
        self.lower = np.tril_indices(scene.model.nv, -1)


_local = threading.local()


def workspace(scene: Scene) -> Workspace:
    """The calling thread's workspace for ``scene``, created on its first use.

    The cache is keyed weakly on the scene, so a scene that is no longer used
    frees its workspaces; nothing is stored on the scene itself.

    Raises
    ------
    ModelTooLargeError
        Pinocchio's data would not fit in the memory allowed.
    """
    cache = getattr(_local, "cache", None)
    if cache is None:
        cache = _local.cache = weakref.WeakKeyDictionary()
    ws = cache.get(scene)
    if ws is None:
        ws = cache[scene] = Workspace(scene)
    return ws


class Evaluation:
    """Kinematic quantities at one (q, v), computed on first use and shared by the elements.

    Every Pinocchio algorithm run through :meth:`call` is logged in
    :attr:`calls`, so that a linearization can report (and tests can check)
    exactly which algorithms a scene triggered.

    Parameters
    ----------
    scene : Scene
    q : ndarray (nq,)
    v : ndarray (nv,)
    ws : Workspace, optional
        Where Pinocchio writes; default the calling thread's workspace.
    """

    def __init__(self, scene: Scene, q: np.ndarray, v: np.ndarray, ws: Workspace | None = None):
        ws = workspace(scene) if ws is None else ws
        self.scene = scene
        self.robot = scene.robot
        self.model = scene.model
        self.ws = ws
        self.data = ws.data
        self.q = q
        self.v = v
        self.free = scene.free_dofs
        #: True when v = 0: velocity-proportional forces vanish.
        self.at_rest = not v.any()
        self.calls: list[str] = []
        self._kinematics = False
        self._rotations: dict[int, np.ndarray] = {}
        self._jacobians: dict[tuple[int, pin.ReferenceFrame], np.ndarray] = {}
        self._mass: np.ndarray | None = None
        self._elastic: np.ndarray | None = None
        self._world_jacobian: np.ndarray | None = None
        self._positions: dict[tuple[int, ...], np.ndarray] = {}

    def call(self, name: str, algorithm, *args):
        """Run a Pinocchio algorithm and log its name."""
        self.calls.append(name)
        return algorithm(*args)

    def _ensure_kinematics(self) -> None:
        if not self._kinematics:
            self.call("computeJointJacobians", pin.computeJointJacobians, self.model, self.data, self.q)
            self.call("updateFramePlacements", pin.updateFramePlacements, self.model, self.data)
            self._kinematics = True

    def frame_placement(self, frame_id: int) -> pin.SE3:
        """World placement of a frame (a copy)."""
        self._ensure_kinematics()
        return pin.SE3(self.data.oMf[frame_id])

    def frame_position(self, frame_id: int) -> np.ndarray:
        """World position of a frame's origin (3,), a copy."""
        self._ensure_kinematics()
        return self.data.oMf[frame_id].translation.copy()

    def frame_rotation(self, frame_id: int) -> np.ndarray:
        """World orientation R of a frame (3 x 3): world vector = R @ local vector."""
        if frame_id not in self._rotations:
            self._ensure_kinematics()
            self._rotations[frame_id] = self.data.oMf[frame_id].rotation.copy()
        return self._rotations[frame_id]

    def frame_positions(self, frame_ids: tuple[int, ...]) -> np.ndarray:
        """World positions of several frames' origins (len(frame_ids) x 3), read-only.

        Computed once per evaluation for a given tuple of ids: an element group
        reading many frames in its force, stiffness and damping pays for one pass.
        """
        out = self._positions.get(frame_ids)
        if out is None:
            self._ensure_kinematics()
            oMf = self.data.oMf
            out = np.array([oMf[i].translation for i in frame_ids], dtype=float).reshape(-1, 3)
            out.flags.writeable = False
            self._positions[frame_ids] = out
        return out

    def world_jacobian(self) -> np.ndarray:
        """The Jacobian of the whole tree in world axes (6 x nv, linear rows first), read-only.

        Column k is the twist xi_k = (v_k, omega_k) of degree of freedom k: the
        angular velocity, and the linear velocity of the body point at the world
        origin (Pinocchio's ``data.J`` after ``computeJointJacobians``).  A body's
        Jacobian is these columns on its supporting joints, and a point p of it
        moves with v_k + omega_k x p: elements between many frames read this once
        instead of one frame Jacobian each (no extra Pinocchio call).
        """
        if self._world_jacobian is None:
            self._ensure_kinematics()
            J = np.array(self.data.J)
            J.flags.writeable = False
            self._world_jacobian = J
        return self._world_jacobian

    def frame_jacobian(self, frame_id: int, reference: pin.ReferenceFrame = pin.ReferenceFrame.LOCAL) -> np.ndarray:
        """Frame Jacobian (6 x nv, linear rows first), in the frame's own axes by default.

        ``reference=pin.LOCAL_WORLD_ALIGNED`` gives the velocity of the frame origin in
        world axes (the form of constraints and elements between frames); computed from
        the local Jacobian by rotating its rows, without another Pinocchio call.
        """
        key = (frame_id, reference)
        if key not in self._jacobians:
            local = self._jacobians.get((frame_id, pin.ReferenceFrame.LOCAL))
            if local is None:
                self._ensure_kinematics()
                local = np.array(pin.getFrameJacobian(self.model, self.data, frame_id, pin.ReferenceFrame.LOCAL))
                self._jacobians[(frame_id, pin.ReferenceFrame.LOCAL)] = local
            if reference == pin.ReferenceFrame.LOCAL_WORLD_ALIGNED:
                R = self.frame_rotation(frame_id)
                self._jacobians[key] = np.vstack([R @ local[:3], R @ local[3:]])
            elif reference != pin.ReferenceFrame.LOCAL:
                self._jacobians[key] = np.array(pin.getFrameJacobian(self.model, self.data, frame_id, reference))
        return self._jacobians[key]

    def world_aligned_jacobian(self, frame_id: int) -> np.ndarray:
        """Frame Jacobian in LOCAL_WORLD_ALIGNED axes (6 x nv): origin velocity and angular velocity, world axes.

        The same matrix as ``frame_jacobian(frame_id, pin.LOCAL_WORLD_ALIGNED)`` (and
        the same cache entry), read in one Pinocchio call: cheaper when the local
        Jacobian is not needed too (constraints, SPEC section 10).
        """
        key = (frame_id, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        J = self._jacobians.get(key)
        if J is None:
            self._ensure_kinematics()
            J = self._jacobians[key] = pin.getFrameJacobian(
                self.model, self.data, frame_id, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
            )
        return J

    def mass_matrix(self) -> np.ndarray:
        """The full mass matrix M(q) (nv x nv), exactly symmetric."""
        if self._mass is None:
            M = self.call("crba", pin.crba, self.model, self.data, self.q)
            self._mass = symmetric_from_upper(M, self.ws.lower)
        return self._mass

    def provide_mass_matrix(self, M: np.ndarray) -> None:
        """Hand over a mass matrix an algorithm already computed at this q (saves a crba)."""
        self._mass = M

    def elastic_stiffness(self) -> np.ndarray:
        """K_e: the stiffness of the scene's elastic elements (nv x nv), psd (Rayleigh's beta term).

        Each element class says what it contributes through
        :meth:`~pinlin.Element.add_elastic_stiffness`; gravity and loads are not elastic.
        """
        if self._elastic is None:
            K = np.zeros((self.model.nv, self.model.nv))
            for group in self.scene.groups:
                group.add_elastic_stiffness(self, K)
            self._elastic = K
        return self._elastic
