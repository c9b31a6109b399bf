"""State-space form of the linearized equations, for python-control and scipy (theory: equations, conventions).

With the state s = [x; x'] (coordinates, then their rates), the second-order
equation M x'' + C x' + K x = F u (C = D + G, K = S + N) reads

.. math::
    \\dot s = \\begin{bmatrix} 0 & I \\\\ -M^{-1} K & -M^{-1} C \\end{bmatrix} s
            + \\begin{bmatrix} 0 \\\\ M^{-1} F \\end{bmatrix} u,
    \\qquad y = [C_x \\;\\; C_v]\\, s

so that ``C (i omega I - A)^{-1} B = C_x H(i omega) F + i omega C_v H(i omega) F``
with H = L^{-1} the dynamic flexibility: with the default inputs (F = I) and
outputs (C_x = I, C_v = 0) it is :func:`pinlin.frequency_response` itself.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..extras import import_control
from ..linearization.system import check_system
from ..numerics.arrays import readonly
from ..numerics.checks import check_tolerance
from ..results import Result
from .frames import OperatingPoint
from .signal_names import FRAME_KINDS, Signal, parse_inputs, parse_outputs

__all__ = ["StateSpaceModel", "state_space", "PERIODIC_TOL"]

#: Default largest relative change of a frame signal when a moving prescribed joint advances:
#: the default ``periodic_tol`` of :func:`pinlin.linearize`, so both refuse the same scenes.
PERIODIC_TOL = 1e-8


@dataclass(frozen=True, repr=False, eq=False)
class StateSpaceModel(Result):
    """``s' = A s + B u``, ``y = C s + D u`` with the state s = [coordinates; rates].

    Attributes
    ----------
    A : (2n, 2n) ndarray
        [[0, I], [-M^-1 K, -M^-1 C]]: blocks [1], [1/s^2] and [1/s].
    B : (2n, m) ndarray
        [[0], [M^-1 F]]: F's columns are the generalized forces of the inputs
        [N or N m per unit of input].
    C : (p, 2n) ndarray
        Output rows on the coordinates (first n columns) and rates (last n).
    D : (p, m) ndarray
        Zero: no output here feeds through an input.
    state_names : tuple of str
        ``dof_names`` then ``"rate:" + name`` for each.
    input_names, output_names : tuple of str
        The signals (:mod:`pinlin.interop.signal_names`), in the order of B's
        columns and C's rows.
    dof_names : tuple of str
        The coordinates of the system.
    method : str
        What was computed and how.
    error : float
        Relative residual of the first-order blocks against the second-order
        form, ``||M X - Y||_F / (||M||_F ||X||_F + ||Y||_F)`` with
        ``X = M^-1 Y``, ``Y = [K, C, F]`` computed by Cholesky solves: a
        backward error, at rounding level (a few eps) whatever cond(M).  The
        frame rows and columns are exact up to the rounding of the kinematics.
    elapsed : float
        Seconds.
    notes : tuple of str

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])  # x'' + 0.2 x' + 4 x = u
    >>> model = pinlin.state_space(sys)
    >>> model.A
    array([[ 0. ,  1. ],
           [-4. , -0.2]])
    >>> model.state_names, model.input_names, model.n_states
    (('x1', 'rate:x1'), ('force:x1',), 2)
    >>> type(model.to_scipy()).__name__
    'StateSpaceContinuous'
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    state_names: tuple[str, ...]
    input_names: tuple[str, ...]
    output_names: tuple[str, ...]
    dof_names: tuple[str, ...]
    method: str
    error: float
    elapsed: float
    notes: tuple[str, ...] = ()

    @property
    def n_states(self) -> int:
        return self.A.shape[0]

    @property
    def n_inputs(self) -> int:
        return self.B.shape[1]

    @property
    def n_outputs(self) -> int:
        return self.C.shape[0]

    def to_control(self, name: str | None = None):
        """The model as a python-control ``StateSpace`` with the state, input and output names.

        Parameters
        ----------
        name : str, optional
            The system's name in python-control (its generic ``sys[k]`` when omitted).

        Raises
        ------
        MissingDependencyError
            python-control is not installed (``pip install 'pinlin[control]'``).

        Examples
        --------
        >>> model = pinlin.state_space(pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]]))
        >>> ss = model.to_control(name="oscillator")
        >>> ss.name, ss.state_labels, ss.input_labels, ss.output_labels
        ('oscillator', ['x1', 'rate:x1'], ['force:x1'], ['x1'])
        """
        control = import_control()
        kwargs = {} if name is None else {"name": str(name)}
        return control.ss(
            np.array(self.A),
            np.array(self.B),
            np.array(self.C),
            np.array(self.D),
            states=list(self.state_names),
            inputs=list(self.input_names),
            outputs=list(self.output_names),
            **kwargs,
        )

    def to_scipy(self):
        """The model as a ``scipy.signal.StateSpace`` (continuous time; scipy keeps no names).

        Examples
        --------
        >>> model = pinlin.state_space(pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]]))
        >>> lti = model.to_scipy()
        >>> type(lti).__name__, bool(np.array_equal(lti.A, model.A)), lti.B.ravel().tolist()
        ('StateSpaceContinuous', True, [0.0, 1.0])
        """
        from scipy import signal

        return signal.StateSpace(np.array(self.A), np.array(self.B), np.array(self.C), np.array(self.D))

    def __repr__(self) -> str:
        def short(names):
            return list(names) if len(names) <= 4 else list(names[:3]) + ["...", names[-1]]

        return (
            f"StateSpaceModel(states={self.n_states}, inputs={short(self.input_names)}, "
            f"outputs={short(self.output_names)}, error={self.error:.1e}, elapsed={self.elapsed:.3g} s)"
        )




def _input_matrix(sys, signals: list[Signal], point: OperatingPoint | None) -> np.ndarray:
    F = np.zeros((sys.n, len(signals)))
    for j, s in enumerate(signals):
        if s.kind == "force":
            F[s.index, j] = 1.0
        else:
            F[:, j] = point.input_column(s)
    return F + 0.0


def _output_matrix(sys, signals: list[Signal], point: OperatingPoint | None) -> np.ndarray:
    n = sys.n
    Cout = np.zeros((len(signals), 2 * n))
    for i, s in enumerate(signals):
        if s.kind in ("coordinate", "rate"):
            Cout[i, s.index + (n if s.kind == "rate" else 0)] = 1.0
        else:
            offset = n if s.kind == "velocity" else 0
            Cout[i, offset : offset + n] = point.output_row(s)
    return Cout + 0.0  # no -0. entries handed to python-control


def state_space(
    sys, inputs=None, outputs=None, scene=None, *, periodic_tol: float = PERIODIC_TOL
) -> StateSpaceModel:
    """The linearized system as a state-space model, ready for python-control or scipy (theory: equations, conventions).

    .. math::
        \\dot s = A s + B u,\\quad y = C s + D u,\\qquad
        s = \\begin{bmatrix} x \\\\ \\dot x \\end{bmatrix},\\quad
        A = \\begin{bmatrix} 0 & I \\\\ -M^{-1} K & -M^{-1} C \\end{bmatrix},\\quad
        B = \\begin{bmatrix} 0 \\\\ M^{-1} F \\end{bmatrix}

    By default the inputs are the generalized forces on all coordinates and the
    outputs all coordinates, in ``sys.dof_names`` order, so that the model's
    frequency response equals ``pinlin.frequency_response(sys, omega).response``
    (python-control's order ``[output, input, frequency]``).

    Parameters
    ----------
    sys : LinearizedSystem
    inputs : signal or list of signals, optional
        Coordinates (``"joint1"``, an index, ``"force:joint1"``), wrenches at
        frames (``"follower:tip:fz"``, ``"dead:tip:fx"``, ``"dead:tip"`` for all
        six components, a :class:`~pinlin.FollowerWrench` or
        :class:`~pinlin.DeadWrench` scaled by the input, or a pair ``(name,
        wrench)``); see :mod:`pinlin.interop.signal_names` for the full table.
    outputs : signal or list of signals, optional
        Coordinates (``"joint1"``, an index), rates (``"rate:joint1"``), the
        world-axes displacement or velocity of a frame origin
        (``"position:tip:x"``, ``"velocity:tip"`` for x, y and z).
    scene : Scene, optional
        The scene ``sys`` was linearized from; needed by frame inputs and
        outputs (Jacobians at ``sys.q``; with constraints, through ``sys.basis``).
    periodic_tol : float
        Largest relative change of a frame signal when a moving prescribed
        joint is advanced; above it the signal is time-periodic and refused.

    Returns
    -------
    StateSpaceModel

    Raises
    ------
    ParameterError
        ``sys`` is not a LinearizedSystem; an unknown coordinate, kind or axis;
        a signal named twice; frame signals without ``scene`` or with
        something else than a Scene; a bad ``periodic_tol``.
    FrameNotFoundError
        A frame the robot does not have.
    InputError
        ``sys`` has no operating point or was not linearized from ``scene``.
    ConfigurationError
        ``sys.q`` is not a configuration of the scene's robot.
    TimePeriodicError
        A frame signal moves with a prescribed joint (its world-axes value is
        time-periodic).

    See Also
    --------
    frequency_response_data : a :class:`~pinlin.FrequencyResponse` as python-control data.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot)
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> model = pinlin.state_space(sys, inputs="force:joint1", outputs=["joint2", "position:tip:x"], scene=scene)
    >>> model.A.shape, model.B.shape, model.C.shape
    ((4, 4), (4, 1), (2, 4))
    >>> model.output_names, bool(model.error < 1e-14)
    (('joint2', 'position:tip:x'), True)
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    periodic_tol = check_tolerance(periodic_tol, "periodic_tol")
    ins = parse_inputs(inputs, sys.dof_names, "inputs")
    outs = parse_outputs(outputs, sys.dof_names, "outputs")
    at_frames = sorted({s.name for s in ins + outs if s.kind in FRAME_KINDS})
    point = None
    if at_frames:
        if scene is None:
            raise ParameterError(
                "scene", f"signals {at_frames} act at frames: pass the scene the system was linearized from"
            )
        point = OperatingPoint(sys, scene, periodic_tol)
    F = _input_matrix(sys, ins, point)
    A, B, error = sys.first_order(F)
    Cout = _output_matrix(sys, outs, point)
    notes = []
    if point is not None and getattr(sys, "basis", None) is not None:
        notes.append("frame signals mapped through sys.basis (constrained coordinates)")
    return StateSpaceModel(
        A=readonly(A),
        B=readonly(B),
        C=readonly(Cout),
        D=readonly(np.zeros((len(outs), len(ins)))),
        state_names=tuple(sys.dof_names) + tuple(f"rate:{name}" for name in sys.dof_names),
        input_names=tuple(s.name for s in ins),
        output_names=tuple(s.name for s in outs),
        dof_names=tuple(sys.dof_names),
        method="first-order form s = [x; x'], A and B by Cholesky solves with M"
        + ("; frame signals through the Jacobians at sys.q" if point is not None else ""),
        error=error,
        elapsed=time.perf_counter() - t0,
        notes=tuple(notes),
    )
