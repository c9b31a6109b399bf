"""The element interface: what every force element of a scene implements.

An element is a small frozen value naming a joint or frame and its parameters.
At a point (q, v) it gives its generalized force Q_e(q, v) and adds its analytic
derivatives to the linearized matrices:

    K += -dQ_e/dq,    C += -dQ_e/dv          (theory: equations)

Wrench elements (forces on a frame) do not compute Q_e themselves during
assembly: they hand Pinocchio a wrench in their joint's frame (``fext``) and add
only what Pinocchio's derivative, taken with that wrench held constant in the
joint frame, leaves out.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

import numpy as np
import pinocchio as pin

from ...errors import ParameterError
from ...numerics.arrays import readonly
from ..numbers import numeric_array

__all__ = [
    "Element",
    "ElementGroup",
    "WrenchElement",
    "DiagonalIndex",
    "as_matrix",
    "check_psd",
    "check_vector3",
    "contiguous",
]


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
    """Validate a scalar / vector / matrix coefficient: finite, >= 0 or symmetric psd (a read-only copy:
    elements are shared by threads, and the caller's array must not alias them)."""
    arr = numeric_array(value, label, "a number, a vector or a matrix")
    if arr.ndim > 2:
        raise ParameterError(label, f"expected at most 2 dimensions, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ParameterError(label, f"must be finite, got {value!r}")
    if arr.ndim < 2:
        if np.any(arr < 0):
            raise ParameterError(label, f"must be non-negative, got {value!r}")
        return readonly(arr)
    if arr.shape[0] != arr.shape[1]:
        raise ParameterError(label, f"a matrix must be square, got shape {arr.shape}")
    scale = max(np.abs(arr).max(), np.finfo(float).tiny)
    if np.abs(arr - arr.T).max() > 1e-12 * scale:
        raise ParameterError(label, "a matrix must be symmetric")
    arr = (arr + arr.T) / 2
    if np.linalg.eigvalsh(arr).min() < -1e-12 * scale:
        raise ParameterError(label, "a matrix must be positive semi-definite")
    return readonly(arr)


def check_vector3(value, label: str) -> np.ndarray:
    """Three finite numbers, as a read-only copy."""
    arr = numeric_array(value, label, "3 numbers")
    if arr.shape != (3,):
        raise ParameterError(label, f"expected 3 numbers, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ParameterError(label, f"must be finite, got {value!r}")
    return readonly(arr)


def contiguous(indices: np.ndarray) -> slice | np.ndarray:
    """``indices`` as a slice when they are consecutive and increasing (a cheaper index), else unchanged.

    ``x[contiguous(i)]`` selects the same entries as ``x[i]``; a slice gives a view
    (in-place updates through it need no fancy-index write-back).
    """
    if len(indices) and np.array_equal(indices, np.arange(indices[0], indices[0] + len(indices))):
        return slice(int(indices[0]), int(indices[0]) + len(indices))
    return indices


class DiagonalIndex:
    """The diagonal positions (iv[i], iv[i]) of an (nv x nv) matrix, for updates in one call.

    ``add(A, values)`` does ``A[iv, iv] += values`` as one flat-index update of
    ``A.flat`` (any memory layout; a third of the cost of the fancy index on small
    matrices).  With repeated indices every value is added in turn (``np.add.at``),
    so the result is the element-by-element sum, bitwise.  Immutable (shared by
    the threads that share a scene).

    Parameters
    ----------
    iv : sequence of int
        Velocity indices.
    nv : int
        Size of the matrices updated.
    """

    __slots__ = ("iv", "flat", "unique", "span")

    def __init__(self, iv, nv: int):
        iv = np.asarray(iv, dtype=np.intp).reshape(-1)
        object.__setattr__(self, "iv", readonly(iv))
        object.__setattr__(self, "flat", readonly(iv * (nv + 1)))
        object.__setattr__(self, "unique", len(set(iv.tolist())) == len(iv))
        # consecutive indices: the diagonal run as a strided slice of the flattened matrix
        run = contiguous(iv)
        span = slice(run.start * (nv + 1), run.stop * (nv + 1), nv + 1) if isinstance(run, slice) else None
        object.__setattr__(self, "span", span)

    def __setattr__(self, name, value):
        raise AttributeError(f"DiagonalIndex is immutable: cannot set {name!r}")

    def __len__(self) -> int:
        return len(self.iv)

    def add(self, A: np.ndarray, values: np.ndarray) -> None:
        """``A[iv, iv] += values`` in place, repeated indices summed in order."""
        if self.span is not None and A.flags.c_contiguous:
            run = A.ravel()[self.span]  # a view of A (ravel copies only non-contiguous arrays)
            run += values  # in place: no write-back
        elif self.unique:
            A.flat[self.flat] += values
        else:
            np.add.at(A, (self.iv, self.iv), values)

    def add_many(self, A: np.ndarray, values: np.ndarray) -> None:
        """``A[p, iv, iv] += values`` for every matrix of a C-contiguous stack A (P, nv, nv), in place."""
        if self.span is not None:
            run = A.reshape(len(A), -1)[:, self.span]  # a view: A is contiguous
            run += values
        elif self.unique:
            A.reshape(len(A), -1)[:, self.flat] += values
        else:
            np.add.at(A, (slice(None), self.iv, self.iv), values)


class ElementGroup:
    """All elements of one class in a scene, evaluated together.

    The default group loops over its elements; classes of many simple elements (1-DOF
    springs and dampers) return a vectorized one from :meth:`Element.group`.

    Attributes
    ----------
    symmetric_stiffness : bool
        True when :meth:`add_stiffness` adds an exactly symmetric matrix (it then
        adds no rounding to the skew part N).
    constant_damping : bool
        True when :meth:`add_damping` adds the same matrix at every point without reading
        its evaluation (``ev=None`` allowed): the linearization plan adds it once per scene.
    batched : bool
        True when the group implements ``add_many(qs, Q, K, batch=None)``: its forces at
        rest (v = 0) and stiffness at P configurations at once (Q (P, nv), K (P, nv, nv)),
        for :func:`pinlin.linearize_many`; ``batch`` (a
        :class:`~pinlin.model.evaluation.BatchPoints`) lets it compute once for all the call's points.
    """

    batched = False

    def __init__(self, elements: tuple[Element, ...]):
        self.elements = elements
        self.symmetric_stiffness = all(type(e).symmetric_stiffness for e in elements)
        self.constant_damping = False

    def add_force(self, ev, Q: np.ndarray) -> None:
        """Add the elements' generalized forces Q_e(q, v) to Q (nv,)."""
        for element in self.elements:
            Q += element.generalized_force(ev)

    def add_stiffness(self, ev, K: np.ndarray) -> None:
        """Add -dQ_e/dq to K (nv x nv)."""
        for element in self.elements:
            element.add_stiffness(ev, K)

    def add_damping(self, ev, C: np.ndarray) -> None:
        """Add -dQ_e/dv to C (nv x nv)."""
        for element in self.elements:
            element.add_damping(ev, C)

    def add_elastic_stiffness(self, ev, K: np.ndarray) -> None:
        """Add the elements' elastic stiffness (psd, Rayleigh's K_e) to K (nv x nv)."""
        for element in self.elements:
            element.add_elastic_stiffness(ev, K)


class Element(ABC):
    """A force element of a scene (theory: elements).

    Subclasses name a joint or frame, are checked against the robot by :meth:`check` when a
    :class:`~pinlin.Scene` is built and evaluated through an :class:`~pinlin.linearization.Evaluation`.
    The class attribute :attr:`invariance` (declared on the class itself, never inherited) says
    what the force depends on; docs/elements.md says what each kind promises and how to write one.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> class Torque(pinlin.Element):
    ...     # a constant torque [N m] on joint1: no stiffness, no damping
    ...     kind = "torque"
    ...     def check(self, robot):
    ...         robot.joint("joint1")
    ...     def generalized_force(self, ev):
    ...         return np.array([0.5, 0.0])
    >>> sys = pinlin.linearize(pinlin.Scene(robot, [Torque()]), np.zeros(2), balancing=True)
    >>> np.round(sys.S, 6)
    array([[12.8511 ,  2.20725],
           [ 2.20725,  2.20725]])
    """

    #: Short label used in reports and scene files.
    kind: ClassVar[str] = "element"
    #: True for elements that act through Pinocchio's ``fext``.
    is_wrench: ClassVar[bool] = False
    #: True when the element's stiffness -dQ_e/dq is always exactly symmetric.
    symmetric_stiffness: ClassVar[bool] = False
    #: What the force depends on, for the time-invariance proofs (class docstring): "joint-space",
    #: "body-fixed load", "dead load" or "unknown"; counts only on the class that declares it.
    invariance: ClassVar[str] = "unknown"

    @abstractmethod
    def check(self, robot) -> None:
        """Raise a :class:`~pinlin.PinlinError` if the element does not fit the robot.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> pinlin.JointSpring("joint3", 1.0).check(robot)  # doctest: +IGNORE_EXCEPTION_DETAIL
        Traceback (most recent call last):
            ...
        JointNotFoundError: ...
        """

    @abstractmethod
    def generalized_force(self, ev) -> np.ndarray:
        """Generalized force Q_e(q, v) of the element (nv,) [N or N m].

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> spring = pinlin.JointSpring("joint1", 2.0)
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [spring]), np.array([0.1, 0.0]), np.zeros(2))
        >>> np.round(spring.generalized_force(ev), 6)
        array([-0.2,  0. ])
        """

    def add_stiffness(self, ev, K: np.ndarray) -> None:  # noqa: B027 (optional hook)
        """Add -dQ_e/dq (tangent space, nv x nv) to K; nothing by default.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> spring = pinlin.JointSpring("joint1", 2.0)
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [spring]), np.array([0.1, 0.0]), np.zeros(2))
        >>> K = np.zeros((2, 2))
        >>> spring.add_stiffness(ev, K)
        >>> K
        array([[2., 0.],
               [0., 0.]])
        """

    def add_damping(self, ev, C: np.ndarray) -> None:  # noqa: B027 (optional hook)
        """Add -dQ_e/dv (nv x nv) to C; nothing by default.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> damper = pinlin.JointDamper("joint2", 0.3)
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [damper]), np.zeros(2), np.zeros(2))
        >>> C = np.zeros((2, 2))
        >>> damper.add_damping(ev, C)
        >>> C
        array([[0. , 0. ],
               [0. , 0.3]])
        """

    def add_elastic_stiffness(self, ev, K: np.ndarray) -> None:  # noqa: B027 (optional hook)
        """Add the element's elastic stiffness to K (nv x nv); nothing by default.

        The psd part that stores strain energy (a spring's k, not its preload's geometric term,
        gravity nor loads): :class:`~pinlin.RayleighDamping`'s K_e in beta K_e.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> spring = pinlin.JointSpring("joint1", 2.0)
        >>> ev = pinlin.linearization.Evaluation(pinlin.Scene(robot, [spring]), np.array([0.1, 0.0]), np.zeros(2))
        >>> K = np.zeros((2, 2))
        >>> spring.add_elastic_stiffness(ev, K)
        >>> K
        array([[2., 0.],
               [0., 0.]])
        """

    def needs(self) -> frozenset[str]:
        """What the element reads from an :class:`~pinlin.linearization.Evaluation`.

        A subset of ``{"frame_kinematics", "mass_matrix"}``: frame placements and
        Jacobians (``computeJointJacobians`` + ``updateFramePlacements``), and the
        mass matrix (``crba`` unless the dynamics pass already gave it).  Joint-space
        elements need neither.  :attr:`pinlin.Scene.needs` collects them, and a test
        checks that ``sys.calls`` runs nothing else beyond the dynamics.

        Examples
        --------
        >>> pinlin.JointSpring("joint1", 2.0).needs()
        frozenset()
        >>> pinlin.LinearSpringDamper("tip", np.zeros(3), stiffness=1.0).needs()
        frozenset({'frame_kinematics'})
        """
        return frozenset()

    @classmethod
    def group(cls, elements: tuple[Element, ...], robot) -> ElementGroup:
        """The elements of this class in one scene, for evaluation together.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> springs = (pinlin.JointSpring("joint1", 2.0), pinlin.JointSpring("joint2", 1.0))
        >>> type(pinlin.JointSpring.group(springs, robot)).__name__
        'SpringGroup'
        """
        return ElementGroup(elements)


class WrenchElement(Element):
    """A wrench applied at a frame origin; it reaches Pinocchio as ``fext``.

    Examples
    --------
    >>> isinstance(pinlin.FollowerWrench("tip", force=[0.0, 0.0, 1.0]), pinlin.model.WrenchElement)
    True
    """

    is_wrench: ClassVar[bool] = True
    #: True when the wrench is constant in its joint's frame (then ``fext`` does not depend on q).
    body_fixed: ClassVar[bool] = False
    frame: str
    force: np.ndarray
    torque: np.ndarray

    def check(self, robot) -> None:
        robot.frame_id(self.frame)

    def needs(self) -> frozenset[str]:
        return frozenset() if self.body_fixed else frozenset({"frame_kinematics"})

    @abstractmethod
    def local_wrench(self, ev) -> np.ndarray:
        """The wrench (force, torque) at the frame origin, in the frame's axes (6,).

        Examples
        --------
        >>> pinlin.FollowerWrench("tip", force=[0.0, 0.0, 1.0]).local_wrench(None)
        array([0., 0., 1., 0., 0., 0.])
        """

    def joint_wrench(self, ev, model: pin.Model, robot) -> tuple[int, pin.Force]:
        """The wrench in its parent joint's frame, as Pinocchio's ``fext`` wants it.

        ``ev`` may be None for a body-fixed wrench (its local wrench does not depend on q).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> joint, force = pinlin.FollowerWrench("tip", force=[0.0, 0.0, 1.0]).joint_wrench(None, robot.model, robot)
        >>> joint, force.vector
        (2, array([0., 0., 1., 0., 0., 0.]))
        """
        frame = model.frames[robot.frame_id(self.frame)]
        w = self.local_wrench(ev)
        return frame.parentJoint, frame.placement.act(pin.Force(w[:3], w[3:]))

    def generalized_force(self, ev) -> np.ndarray:
        """Q = J^T w with J the frame Jacobian in the frame's axes (nv,)."""
        return ev.frame_jacobian(ev.robot.frame_id(self.frame)).T @ self.local_wrench(ev)

