"""The element interface and the shared evaluation workspace.

An element is a small frozen value naming a joint or frame and its parameters.
At a point (q, v) it gives its generalized force Q_e(q, v) and adds its analytic
derivatives to the linearized matrices:

    K += -dQ_e/dq,    C += -dQ_e/dv          (SPEC section 1)

Wrench elements (forces on a frame) do not compute Q_e themselves during
assembly: they hand Pinocchio a wrench in their joint's frame (``fext``) and add
only what Pinocchio's derivative, taken with that wrench held constant in the
joint frame, leaves out.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import TYPE_CHECKING, ClassVar

import numpy as np
import pinocchio as pin

from ..errors import ParameterError

if TYPE_CHECKING:  # pragma: no cover
    from ..robot import Robot
    from ..scene import Scene

__all__ = ["Element", "ElementGroup", "WrenchElement", "Evaluation", "symmetric_from_upper"]


def symmetric_from_upper(a: np.ndarray, lower: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """A copy of ``a`` with its strictly lower triangle mirrored from the upper one.

    Pinocchio's C++ ``crba`` fills only the upper triangle of M (its Python
    binding may or may not mirror it, depending on the version).
    """
    a = np.array(a)
    a[lower] = a.T[lower]
    return a


class Evaluation:
    """Kinematic quantities at one (q, v), computed on first use and shared.

    Every Pinocchio algorithm run through :meth:`call` is logged in
    :attr:`calls`, so that a linearization can report (and tests can check)
    exactly which algorithms a scene triggered.

    Parameters
    ----------
    scene : Scene
    q : ndarray (nq,)
    v : ndarray (nv,)
    """

    def __init__(self, scene: Scene, q: np.ndarray, v: np.ndarray):
        self.scene = scene
        self.robot = scene.robot
        self.model = scene.model
        self.data = scene.data
        self.q = q
        self.v = v
        self.free = scene.free_dofs
        #: True when v = 0: velocity-proportional forces vanish.
        self.at_rest = not v.any()
        self.calls: list[str] = []
        self._kinematics = False
        self._rotations: dict[int, np.ndarray] = {}
        self._jacobians: dict[int, np.ndarray] = {}
        self._mass: np.ndarray | None = None

    def call(self, name: str, algorithm, *args):
        """Run a Pinocchio algorithm and log its name."""
        self.calls.append(name)
        return algorithm(*args)

    def _ensure_kinematics(self) -> None:
        if not self._kinematics:
            self.call("computeJointJacobians", pin.computeJointJacobians, self.model, self.data, self.q)
            self.call("updateFramePlacements", pin.updateFramePlacements, self.model, self.data)
            self._kinematics = True

    def frame_rotation(self, frame_id: int) -> np.ndarray:
        """World orientation R of a frame (3 x 3): world vector = R @ local vector."""
        if frame_id not in self._rotations:
            self._ensure_kinematics()
            self._rotations[frame_id] = self.data.oMf[frame_id].rotation.copy()
        return self._rotations[frame_id]

    def frame_jacobian(self, frame_id: int) -> np.ndarray:
        """Frame Jacobian in the frame's own axes (6 x nv, linear rows first)."""
        if frame_id not in self._jacobians:
            self._ensure_kinematics()
            self._jacobians[frame_id] = pin.getFrameJacobian(
                self.model, self.data, frame_id, pin.ReferenceFrame.LOCAL
            )
        return self._jacobians[frame_id]

    def mass_matrix(self) -> np.ndarray:
        """The full mass matrix M(q) (nv x nv), exactly symmetric."""
        if self._mass is None:
            M = self.call("crba", pin.crba, self.model, self.data, self.q)
            self._mass = symmetric_from_upper(M, self.scene.lower)
        return self._mass

    def provide_mass_matrix(self, M: np.ndarray) -> None:
        """Hand over a mass matrix an algorithm already computed at this q (saves a crba)."""
        self._mass = M

    def spring_matrix(self) -> np.ndarray:
        """Block-diagonal stiffness of the scene's joint springs (nv x nv), psd."""
        from .joint_spring import JointSpring

        K = np.zeros((self.model.nv, self.model.nv))
        for element in self.scene.elements:
            if isinstance(element, JointSpring):
                j = self.robot.joint(element.joint)
                K[j.v_slice, j.v_slice] += element.matrix(j)
        return K


def as_matrix(value, size: int, label: str) -> np.ndarray:
    """A scalar, vector (diagonal) or symmetric psd matrix as a (size x size) matrix.

    Raises
    ------
    ParameterError
        Wrong shape, non-finite, negative, asymmetric or indefinite values.
    """
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        arr = np.eye(size) * float(arr)
    elif arr.ndim == 1:
        if arr.shape != (size,):
            raise ParameterError(label, f"expected a number, {size} values or a {size}x{size} matrix, got shape {arr.shape}")
        arr = np.diag(arr)
    elif arr.shape != (size, size):
        raise ParameterError(label, f"expected a number, {size} values or a {size}x{size} matrix, got shape {arr.shape}")
    return arr


def check_psd(value, label: str) -> np.ndarray:
    """Validate a scalar / vector / matrix coefficient: finite, >= 0 or symmetric psd."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected a number, a vector or a matrix, got {value!r}") from None
    if arr.ndim > 2:
        raise ParameterError(label, f"expected at most 2 dimensions, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ParameterError(label, f"must be finite, got {value!r}")
    if arr.ndim < 2:
        if np.any(arr < 0):
            raise ParameterError(label, f"must be non-negative, got {value!r}")
        return arr
    if arr.shape[0] != arr.shape[1]:
        raise ParameterError(label, f"a matrix must be square, got shape {arr.shape}")
    scale = max(np.abs(arr).max(), np.finfo(float).tiny)
    if np.abs(arr - arr.T).max() > 1e-12 * scale:
        raise ParameterError(label, "a matrix must be symmetric")
    arr = (arr + arr.T) / 2
    if np.linalg.eigvalsh(arr).min() < -1e-12 * scale:
        raise ParameterError(label, "a matrix must be positive semi-definite")
    return arr


def check_vector3(value, label: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected 3 numbers, got {value!r}") from None
    if arr.shape != (3,):
        raise ParameterError(label, f"expected 3 numbers, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ParameterError(label, f"must be finite, got {value!r}")
    return arr


class ElementGroup:
    """All elements of one class in a scene, evaluated together.

    The default group loops over its elements; element classes whose elements
    are many and simple (1-DOF springs and dampers) return a vectorized group
    from :meth:`Element.group`, so a 200-joint chain costs a few array
    operations, not 200 Python calls.

    Attributes
    ----------
    symmetric_stiffness : bool
        True when :meth:`add_stiffness` adds an exactly symmetric matrix (it then
        adds no rounding to the skew part N).
    """

    def __init__(self, elements: tuple[Element, ...]):
        self.elements = elements
        self.symmetric_stiffness = all(type(e).symmetric_stiffness for e in elements)

    def add_force(self, ev: Evaluation, Q: np.ndarray) -> None:
        """Add the elements' generalized forces Q_e(q, v) to Q (nv,)."""
        for element in self.elements:
            Q += element.generalized_force(ev)

    def add_stiffness(self, ev: Evaluation, K: np.ndarray) -> None:
        """Add -dQ_e/dq to K (nv x nv)."""
        for element in self.elements:
            element.add_stiffness(ev, K)

    def add_damping(self, ev: Evaluation, C: np.ndarray) -> None:
        """Add -dQ_e/dv to C (nv x nv)."""
        for element in self.elements:
            element.add_damping(ev, C)


class Element(ABC):
    """A force element of a scene (SPEC section 2).

    Subclasses are frozen dataclasses that name a joint or frame; they are
    checked against a robot by :meth:`check` when a :class:`~pinlin.Scene` is
    built, and evaluated through an :class:`Evaluation`.
    """

    #: Short label used in reports and scene files.
    kind: ClassVar[str] = "element"
    #: True for elements that act through Pinocchio's ``fext``.
    is_wrench: ClassVar[bool] = False
    #: True when the element's stiffness -dQ_e/dq is always exactly symmetric.
    symmetric_stiffness: ClassVar[bool] = False

    @abstractmethod
    def check(self, robot: Robot) -> None:
        """Raise a :class:`~pinlin.PinlinError` if the element does not fit the robot."""

    @abstractmethod
    def generalized_force(self, ev: Evaluation) -> np.ndarray:
        """Generalized force Q_e(q, v) of the element (nv,) [N or N m]."""

    def add_stiffness(self, ev: Evaluation, K: np.ndarray) -> None:  # noqa: B027 (optional hook)
        """Add -dQ_e/dq (tangent space, nv x nv) to K; nothing by default."""

    def add_damping(self, ev: Evaluation, C: np.ndarray) -> None:  # noqa: B027 (optional hook)
        """Add -dQ_e/dv (nv x nv) to C; nothing by default."""

    @classmethod
    def group(cls, elements: tuple[Element, ...], robot: Robot) -> ElementGroup:
        """The elements of this class in one scene, for evaluation together."""
        return ElementGroup(elements)


class WrenchElement(Element):
    """A wrench applied at a frame origin; it reaches Pinocchio as ``fext``."""

    is_wrench: ClassVar[bool] = True
    #: True when the wrench is constant in its joint's frame (then ``fext`` does not depend on q).
    body_fixed: ClassVar[bool] = False
    frame: str
    force: np.ndarray
    torque: np.ndarray

    def check(self, robot: Robot) -> None:
        robot.frame_id(self.frame)

    @abstractmethod
    def local_wrench(self, ev: Evaluation) -> np.ndarray:
        """The wrench (force, torque) at the frame origin, in the frame's axes (6,)."""

    def joint_wrench(self, ev: Evaluation) -> tuple[int, pin.Force]:
        """The wrench in its parent joint's frame, as Pinocchio's ``fext`` wants it."""
        frame = ev.model.frames[ev.robot.frame_id(self.frame)]
        w = self.local_wrench(ev)
        return frame.parentJoint, frame.placement.act(pin.Force(w[:3], w[3:]))

    def generalized_force(self, ev: Evaluation) -> np.ndarray:
        """Q = J^T w with J the frame Jacobian in the frame's axes (nv,)."""
        return ev.frame_jacobian(ev.robot.frame_id(self.frame)).T @ self.local_wrench(ev)

