"""The Pinocchio workspace a computation owns, and the evaluation of one point in it.

A :class:`~pinlin.Scene` is an immutable description shared freely, Pinocchio's
``Model`` included.  Pinocchio's ``Data`` is the mutable workspace its algorithms
write into, so it must belong to one caller at a time (Pinocchio's Model/Data split).
:func:`workspace` gives each thread its own :class:`Workspace` per robot (shared by
the robot's scenes, whose models differ only in gravity), created on that
thread's first use (behind the memory guard) and reused afterwards:
``createData`` costs 4x (9-joint arm) to 60-80x (100-link chain) a whole linearization,
so a fresh one per call would be the slower choice (benchmarks/bench_workspace.py).  Within one thread computations
run one after another, and each copies what it reads out of ``Data`` before the
next algorithm runs, so nested calls (a linearization inside a simulation's callback) are safe too.
"""

from __future__ import annotations

import functools
import operator
import threading
import weakref

import numpy as np
import pinocchio as pin

__all__ = ["Workspace", "workspace", "Evaluation", "symmetric_from_upper", "crba_is_symmetric", "live_view",
           "BatchPoints"]

#: ``data.oMf[i]`` costs about 1.1 us per frame (boost.python's proxy), ``data.oMf.tolist()``
#: about 0.05 us per frame of the model: reading at least one frame in this many, convert them all.
FRAME_LIST_RATIO = 16
_TRANSLATION = operator.attrgetter("translation")
_HOMOGENEOUS = operator.attrgetter("homogeneous")


def symmetric_from_upper(a: np.ndarray, ws: Workspace) -> np.ndarray:
    """A copy of ``a`` (C order) with its strictly lower triangle mirrored from the upper one.

    Pinocchio's C++ ``crba`` (and ``computeRNEADerivatives``' M) fill only the upper
    triangle of M.  The entries are ``np.where(ws.lower, a.T, a)``'s, bitwise; the
    mirror is one copy and one flat-index assignment (:attr:`Workspace.below` and
    :attr:`Workspace.above`), half the cost of ``np.where`` on a small matrix.
    """
    M = a.copy()  # C order: its flat view below is not a copy
    flat = M.reshape(-1)
    flat[ws.below] = flat[ws.above]
    return M


@functools.cache
def crba_is_symmetric() -> bool:
    """True when this Pinocchio's Python ``crba`` returns the whole symmetric M (a fresh array).

    Decided once per process on a two-link arm whose M has a nonzero coupling
    term, so that no per-call mirror (or copy) is made when the binding already
    gives both triangles, and the upper one is mirrored when it does not.
    """
    model = pin.Model()
    inertia = pin.Inertia(1.0, np.array([0.0, 0.0, -0.5]), np.diag([0.1, 0.1, 0.01]))
    parent = 0
    for k in range(2):
        placement = pin.SE3(np.eye(3), np.array([0.0, 0.0, -1.0 * k]))
        parent = model.addJoint(parent, pin.JointModelRY(), placement, f"j{k}")
        model.appendBodyToJoint(parent, inertia, pin.SE3.Identity())
    M = pin.crba(model, model.createData(), np.array([0.3, 0.4]))
    return bool(M[0, 1] != 0 and M[1, 0] == M[0, 1] and M.flags.owndata)


def live_view(data: pin.Data, name: str) -> tuple[np.ndarray, bool]:
    """(``getattr(data, name)``, whether that array follows every later pass): a loop reads it once.

    eigenpy hands out Data's vectors (``tau``, ``g``) as arrays on Data's own memory,
    which each algorithm rewrites in place, so one view read before a loop over points
    holds each pass's values after it (reading the attribute costs about as much as
    copying a small vector).  Decided by whether a second read shares its memory;
    when it does not (a binding that copies), read the attribute after each pass.
    """
    view = getattr(data, name)
    return view, bool(np.shares_memory(view, getattr(data, name)))


class Workspace:
    """Pinocchio ``Data`` for one robot's models (every scene of it), owned by one thread.

    Parameters
    ----------
    scene : Scene
        The data are created for ``scene.model`` through the robot's memory guard.

    Raises
    ------
    ModelTooLargeError
        Pinocchio's data would not fit in the memory allowed.
    """

    __slots__ = ("model", "data", "lower", "below", "above", "__weakref__")

    def __init__(self, scene):
        self.model = scene.model
        self.data = scene.robot.create_data(scene.model, scene.memory_limit)
        #: Mask of M's strict lower triangle, for mirroring Pinocchio's upper-triangular M in one pass.
        self.lower = np.tri(scene.model.nv, k=-1, dtype=bool)
        #: Flat indices of the strict lower triangle of an (nv x nv) C-order matrix, and of its mirror images.
        rows, cols = np.nonzero(self.lower)
        self.below = rows * scene.model.nv + cols
        self.above = cols * scene.model.nv + rows


_local = threading.local()


def workspace(scene) -> Workspace:
    """The calling thread's workspace for ``scene``'s robot, created on its first use.

    One ``Data`` serves every scene of a robot in a thread: a scene's model is a
    copy of the robot's with its own gravity, the same structure, so the Data
    fits all of them, and ``createData`` (which dominates loading from n of
    about 200 links: it allocates Pinocchio's nv^3 derivative tensors) runs once
    per robot and thread however many scenes a sweep builds.  Computations in a
    thread run one after another and copy what they read out of Data, so scenes
    sharing it cannot disturb each other.

    The thread's cache maps ``id(robot)`` to a weak reference to the robot and its
    workspace; the reference's callback drops the entry when the robot is freed
    (so its Data goes with it, and the id cannot be reused while the entry
    stands).  Nothing is stored on the scene or the robot.  A lookup is a
    dictionary access, less than a ``WeakKeyDictionary`` (which builds a
    reference per call).

    Raises
    ------
    ModelTooLargeError
        Pinocchio's data would not fit in the memory allowed (checked when the
        workspace is created, against the scene's ``memory_limit``).
    """
    cache = getattr(_local, "cache", None)
    if cache is None:
        cache = _local.cache = {}
    robot = scene.robot
    key = id(robot)
    entry = cache.get(key)
    if entry is not None and entry[0]() is robot:
        return entry[1]
    ws = Workspace(scene)
    cache[key] = (weakref.ref(robot, lambda _, cache=cache, key=key: cache.pop(key, None)), ws)
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
    at_rest : bool, optional
        Whether v = 0, when the caller knows it (a scene's steady velocity); default
        decided from v.
    """

    # Per-point caches start empty at the class level and are created on first use:
    # most evaluations (a joint-space scene) never read a frame, so building five
    # containers per call would be a measurable part of a linearization.
    _kinematics = False
    _rotations: dict[int, np.ndarray] | None = None
    _jacobians: dict[tuple[int, pin.ReferenceFrame], np.ndarray] | None = None
    _positions: dict[tuple[int, ...], np.ndarray] | None = None
    _homogeneous: dict[tuple[int, ...], np.ndarray] | None = None
    _mass: np.ndarray | None = None
    _elastic: np.ndarray | None = None
    _world_jacobian: np.ndarray | None = None
    _memo: dict | None = None

    def __init__(
        self,
        scene,
        q: np.ndarray,
        v: np.ndarray,
        ws: Workspace | None = None,
        *,
        at_rest: bool | None = None,
    ):
        ws = workspace(scene) if ws is None else ws
        self.scene = scene
        self.robot = scene.robot
        self.model = scene.model
        self.ws = ws
        self.data = ws.data
        self.q = q
        self.v = v
        self.free = scene.free_dofs
        #: True when v = 0: velocity-proportional forces vanish (``at_rest`` may say so
        #: when the caller knows it, as for a scene's own steady velocity).
        self.at_rest = (not np.count_nonzero(v)) if at_rest is None else at_rest
        self.calls: list[str] = []

    def memo(self, owner, build):
        """``build()`` once per evaluation and ``owner`` (an element group), then the same value.

        Groups keep what one point costs them (geometry shared by their force,
        stiffness and damping) here, on the evaluation that one caller owns, never on
        themselves: a group belongs to a scene that threads share.
        """
        if self._memo is None:
            self._memo = {}
        # keyed by the owner itself (identity hash): the entry keeps it alive, so a short-lived
        # group of one element cannot hand its id to another group within this evaluation
        value = self._memo.get(owner)
        if value is None:
            value = self._memo[owner] = build()
        return value

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
        if self._rotations is None:
            self._rotations = {}
        if frame_id not in self._rotations:
            self._ensure_kinematics()
            self._rotations[frame_id] = self.data.oMf[frame_id].rotation.copy()
        return self._rotations[frame_id]

    def frame_positions(self, frame_ids: tuple[int, ...]) -> np.ndarray:
        """World positions of several frames' origins (len(frame_ids) x 3), read-only.

        Computed once per evaluation for a given tuple of ids: an element group
        reading many frames in its force, stiffness and damping pays for one pass.
        """
        if self._positions is None:
            self._positions = {}
        return self._frame_stack(self._positions, frame_ids, _TRANSLATION, (-1, 3))

    def frame_homogeneous(self, frame_ids: tuple[int, ...]) -> np.ndarray:
        """World placements of several frames as homogeneous matrices (len(frame_ids) x 4 x 4), read-only.

        Computed once per evaluation for a given tuple of ids, like
        :meth:`frame_positions`: rotations ``[:, :3, :3]``, origins ``[:, :3, 3]``.
        """
        if self._homogeneous is None:
            self._homogeneous = {}
        return self._frame_stack(self._homogeneous, frame_ids, _HOMOGENEOUS, (-1, 4, 4))

    def _frame_stack(self, cache: dict, frame_ids: tuple[int, ...], read, shape: tuple[int, ...]) -> np.ndarray:
        """``read`` of each frame's placement, stacked (read-only) and kept in ``cache`` for this evaluation."""
        out = cache.get(frame_ids)
        if out is None:
            self._ensure_kinematics()
            oMf = self.data.oMf
            if len(frame_ids) * FRAME_LIST_RATIO >= len(oMf):  # many frames: one conversion of them all
                oMf = oMf.tolist()
            out = np.array([read(oMf[i]) for i in frame_ids], dtype=float).reshape(shape)
            out.flags.writeable = False
            cache[frame_ids] = out
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
            J = np.array(self.data.J).reshape(6, self.model.nv)  # (6,) from the binding when nv = 1
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
        if self._jacobians is None:
            self._jacobians = {}
        if key not in self._jacobians:
            local = self._jacobians.get((frame_id, pin.ReferenceFrame.LOCAL))
            if local is None:
                self._ensure_kinematics()
                local = _frame_jacobian(self.model, self.data, frame_id, pin.ReferenceFrame.LOCAL)
                self._jacobians[(frame_id, pin.ReferenceFrame.LOCAL)] = local
            if reference == pin.ReferenceFrame.LOCAL_WORLD_ALIGNED:
                R = self.frame_rotation(frame_id)
                self._jacobians[key] = np.vstack([R @ local[:3], R @ local[3:]])
            elif reference != pin.ReferenceFrame.LOCAL:
                self._jacobians[key] = _frame_jacobian(self.model, self.data, frame_id, reference)
        return self._jacobians[key]

    def world_aligned_jacobian(self, frame_id: int) -> np.ndarray:
        """Frame Jacobian in LOCAL_WORLD_ALIGNED axes (6 x nv): origin velocity and angular velocity, world axes.

        The same matrix as ``frame_jacobian(frame_id, pin.LOCAL_WORLD_ALIGNED)`` (and
        the same cache entry), read in one Pinocchio call: cheaper when the local
        Jacobian is not needed too (constraints, theory: constraints).
        """
        key = (frame_id, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        if self._jacobians is None:
            self._jacobians = {}
        J = self._jacobians.get(key)
        if J is None:
            self._ensure_kinematics()
            J = self._jacobians[key] = _frame_jacobian(
                self.model, self.data, frame_id, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
            )
        return J

    def mass_matrix(self) -> np.ndarray:
        """The full mass matrix M(q) (nv x nv), exactly symmetric."""
        if self._mass is None:
            M = self.call("crba", pin.crba, self.model, self.data, self.q)
            self._mass = M if crba_is_symmetric() else symmetric_from_upper(M, self.ws)
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


class BatchPoints:
    """The configurations of one :func:`pinlin.linearize_many` call, and what element groups compute once for all.

    The stacked path takes the points in chunks (stacks that fit a cache); per-point work that
    needs no stack (a multi-DOF spring's log, whose numpy calls cost more than the points)
    runs once on every row through :meth:`memo`, each chunk reading its own ``rows``.  Owned
    by one call, like an :class:`Evaluation`: never stored on a scene or a group.

    Parameters
    ----------
    qs : (P, nq) ndarray
        Every point of the call (checked configurations).
    rows : slice
        The rows of the chunk at hand (default: all).
    """

    __slots__ = ("qs", "rows", "_memo")

    def __init__(self, qs: np.ndarray, rows: slice = slice(None), memo: dict | None = None):
        self.qs, self.rows, self._memo = qs, rows, {} if memo is None else memo

    def chunk(self, start: int, stop: int) -> BatchPoints:
        """The same call's points, seen by the chunk of rows start:stop (one memo for all chunks)."""
        return BatchPoints(self.qs, slice(start, stop), self._memo)

    def memo(self, owner, build):
        """``build()`` once per call and ``owner`` (an element group's log, ...), then the same value (all rows)."""
        value = self._memo.get(owner)
        if value is None:
            value = self._memo[owner] = build()
        return value


def _frame_jacobian(model: pin.Model, data: pin.Data, frame_id: int, reference) -> np.ndarray:
    """A frame Jacobian as a (6, nv) array (the binding returns a (6,) vector when nv = 1)."""
    return np.reshape(pin.getFrameJacobian(model, data, frame_id, reference), (6, model.nv))
