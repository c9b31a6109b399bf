"""Errors of the analyses: equilibria, mass matrices, time-periodic scenes, convergence, integration,
eigenvalues and residues, stability boundaries."""

from __future__ import annotations

from collections.abc import Sequence

from .base import ComputationError, InputError

__all__ = ["NotAnEquilibriumError", "SingularMassError", "TimePeriodicError", "ConvergenceError", "IntegrationError", "IntegrationBudgetError", "NotAnEigenvalueError", "NotSimpleError", "EigenvalueNotIsolatedError", "BracketError", "BoundaryNotIsolatedError", "SystemFunctionError", "SweepTimeoutError"]


class NotAnEquilibriumError(InputError):
    """``linearize`` was asked to work at a point that is not an equilibrium.

    Attributes
    ----------
    residual : float
        Norm of the generalized-force residual [N or N m].
    relative_residual : float
        The residual divided by the size of the forces that should balance.

    Examples
    --------
    >>> try:
    ...     raise pinlin.NotAnEquilibriumError("q is no equilibrium", residual=9.81, relative_residual=0.5)
    ... except pinlin.InputError as exc:
    ...     print(exc.relative_residual)
    0.5
    """

    def __init__(self, message: str, residual: float, relative_residual: float):
        super().__init__(message)
        self.residual = residual
        self.relative_residual = relative_residual


class SingularMassError(InputError):
    """The mass matrix is singular or indefinite.

    Attributes
    ----------
    joints : tuple of str
        Joints whose motion carries no inertia.

    Examples
    --------
    >>> try:
    ...     raise pinlin.SingularMassError("M is singular", joints=["joint2"])
    ... except pinlin.InputError as exc:
    ...     print(exc.joints)
    ('joint2',)
    """

    def __init__(self, message: str, joints: Sequence[str]):
        super().__init__(message)
        self.joints = tuple(joints)


class TimePeriodicError(InputError):
    """The linearized equations depend on the angle of a prescribed joint.

    Then they are time-periodic, not constant-coefficient, and pinlin's analysis
    (built on a constant dynamic stiffness) does not apply.

    Attributes
    ----------
    joint : str
        The prescribed joint whose angle changes the equations.
    variation : float
        Largest relative change of M, C, K or the residual over the tested angles.

    Examples
    --------
    >>> try:
    ...     raise pinlin.TimePeriodicError("M depends on the table angle", joint="table", variation=0.25)
    ... except pinlin.InputError as exc:
    ...     print((exc.joint, exc.variation))
    ('table', 0.25)
    """

    def __init__(self, message: str, joint: str, variation: float):
        super().__init__(message)
        self.joint = joint
        self.variation = variation


class ConvergenceError(ComputationError):
    """An iteration did not converge.

    Attributes
    ----------
    history : tuple of float
        The residual norm at each iteration.

    Examples
    --------
    >>> try:
    ...     raise pinlin.ConvergenceError("Newton did not converge", [1.0, 0.5, 0.4])
    ... except pinlin.ComputationError as exc:
    ...     print(exc.history)
    (1.0, 0.5, 0.4)
    """

    def __init__(self, message: str, history: Sequence[float]):
        super().__init__(message)
        self.history = tuple(history)


class IntegrationError(ComputationError):
    """A time integration (the nonlinear reference simulation) failed.

    Attributes
    ----------
    t_reached : float
        The time [s] up to which the solution is valid.

    Examples
    --------
    >>> try:
    ...     raise pinlin.IntegrationError("the step size underflowed", t_reached=1.5)
    ... except pinlin.ComputationError as exc:
    ...     print(exc.t_reached)
    1.5
    """

    def __init__(self, message: str, t_reached: float):
        super().__init__(message)
        self.t_reached = float(t_reached)


class IntegrationBudgetError(IntegrationError):
    """A time integration stopped at its budget of steps or wall time, or would clearly exceed it.

    Attributes: ``t_reached`` [s] (the solution is valid up to it), ``t_end`` [s] (asked for),
    ``steps`` (taken), ``elapsed`` [s] (spent), ``budget`` (``"max_steps"`` or ``"max_time"``).

    Examples
    --------
    >>> try:
    ...     raise pinlin.IntegrationBudgetError("out of steps",
    ...         t_reached=2.0, t_end=10.0, steps=100, elapsed=0.1, budget="max_steps")
    ... except pinlin.IntegrationError as exc:
    ...     print((exc.t_reached, exc.budget))
    (2.0, 'max_steps')
    """

    def __init__(self, message: str, t_reached: float, t_end: float, steps: int, elapsed: float, budget: str):
        super().__init__(message, t_reached)
        self.t_end, self.steps, self.elapsed, self.budget = float(t_end), int(steps), float(elapsed), budget


class NotAnEigenvalueError(InputError):
    """A point given as an eigenvalue (a root of det L) is not one, to the stated tolerance.

    Attributes
    ----------
    lam : complex
        The point [1/s].
    distance : float
        How far it is from being a root, in the measure the message names
        (relative smallest singular value of L, or relative distance to the
        nearest eigenvalue).

    Examples
    --------
    >>> try:
    ...     raise pinlin.NotAnEigenvalueError("2j is no eigenvalue", lam=2j, distance=0.3)
    ... except pinlin.InputError as exc:
    ...     print(exc.distance)
    0.3
    """

    def __init__(self, message: str, lam: complex, distance: float):
        super().__init__(message)
        self.lam = complex(lam)
        self.distance = float(distance)


class NotSimpleError(InputError):
    """A method needs a simple root or a simple dynamic stiffness, and this one is not.

    Attributes
    ----------
    lam : complex or None
        The offending eigenvalue [1/s], when there is one.
    measure : float
        The quantity that failed the test (named in the message).

    Examples
    --------
    >>> try:
    ...     raise pinlin.NotSimpleError("lam = 0 is defective", lam=0.0, measure=1e-17)
    ... except pinlin.InputError as exc:
    ...     print(exc.lam)
    0j
    """

    def __init__(self, message: str, lam: complex | None = None, measure: float = float("nan")):
        super().__init__(message)
        self.lam = None if lam is None else complex(lam)
        self.measure = float(measure)


class EigenvalueNotIsolatedError(ComputationError):
    """No contour around an eigenvalue separates it from the rest of the spectrum.

    Attributes
    ----------
    lam : complex
        The eigenvalue [1/s].
    inner : float
        Radius [1/s] of the cluster taken as the eigenvalue itself.
    outer : float
        Radius [1/s] at which the next eigenvalue was found.

    Examples
    --------
    >>> try:
    ...     raise pinlin.EigenvalueNotIsolatedError("no separating contour", lam=1j, inner=0.1, outer=0.1)
    ... except pinlin.ComputationError as exc:
    ...     print((exc.inner, exc.outer))
    (0.1, 0.1)
    """

    def __init__(self, message: str, lam: complex, inner: float, outer: float):
        super().__init__(message)
        self.lam = complex(lam)
        self.inner = float(inner)
        self.outer = float(outer)


class BracketError(InputError):
    """A bracket cannot hold a stability boundary (theory: boundaries): its ends have the same verdict class, one is
    "undecided", or they are not two distinct finite numbers; ``bracket``, ``verdicts`` (the kinds at its ends).

    Examples
    --------
    >>> try:
    ...     raise pinlin.BracketError("both ends stable", bracket=(0.0, 1.0), verdicts=("stable", "stable"))
    ... except pinlin.InputError as exc:
    ...     print(exc.verdicts)
    ('stable', 'stable')
    """

    def __init__(self, message: str, bracket, verdicts=()):
        super().__init__(message)
        self.bracket, self.verdicts = tuple(bracket), tuple(verdicts)


class BoundaryNotIsolatedError(InputError):
    """The verdict changes, but not at an isolated parameter value (theory: boundaries): it stays "undecided" over an
    interval far wider than rounding; ``interval``: where.

    Examples
    --------
    >>> try:
    ...     raise pinlin.BoundaryNotIsolatedError("undecided on an interval", interval=(0.4, 0.6))
    ... except pinlin.InputError as exc:
    ...     print(exc.interval)
    (0.4, 0.6)
    """

    def __init__(self, message: str, interval):
        super().__init__(message)
        self.interval = tuple(float(x) for x in interval)


class SystemFunctionError(InputError):
    """A user's ``func(p) -> LinearizedSystem`` raised (chained as ``__cause__``), returned something else, or
    systems of different sizes (theory: boundaries); ``p``: the parameter value.

    Examples
    --------
    >>> try:
    ...     raise pinlin.SystemFunctionError("func(p) returned None", p=0.5)
    ... except pinlin.InputError as exc:
    ...     print(exc.p)
    0.5
    """

    def __init__(self, message: str, p: float):
        super().__init__(message)
        self.p = float(p)


class SweepTimeoutError(ComputationError, TimeoutError):
    """Points of a sweep did not finish within its ``timeout`` (cancelled, except those already running: an
    executor cannot stop a call once started).

    Attributes
    ----------
    timeout : float
        The seconds waited.
    pending : tuple of int
        Indices (grid order) of the points not finished.
    points : tuple of dict
        Those points.

    Examples
    --------
    >>> try:
    ...     raise pinlin.SweepTimeoutError(5.0, pending=[2], points=[{"k": 3.0}])
    ... except TimeoutError as exc:
    ...     print(exc)
    timeout: 1 points not finished after 5 s (cancelled unless already running): #2 {'k': 3.0}
    """

    #: Points named in the message; the rest are counted.
    SHOWN = 5

    def __init__(self, timeout: float, pending, points):
        self.timeout = float(timeout)
        self.pending = tuple(int(i) for i in pending)
        self.points = tuple(dict(p) for p in points)
        shown = ", ".join(f"#{i} {p}" for i, p in zip(self.pending[: self.SHOWN], self.points))
        more = f" and {len(self.pending) - self.SHOWN} more" if len(self.pending) > self.SHOWN else ""
        super().__init__(f"timeout: {len(self.pending)} points not finished after {self.timeout:g} s "
                         f"(cancelled unless already running): {shown}{more}")
