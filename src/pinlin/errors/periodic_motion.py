"""Errors of periodic prescribed motions and periodic reference orbits (theory: Floquet)."""

from __future__ import annotations

from .base import ComputationError, InputError

__all__ = ["QuasiPeriodicError", "PeriodicOrbitError", "OrbitLimitError"]


class QuasiPeriodicError(InputError):
    """The prescribed motions have no common period (incommensurate periods): the motion is quasi-periodic.

    Attributes
    ----------
    periods : dict of str to float
        Joint name -> period [s] of each periodic prescribed motion.

    Examples
    --------
    >>> try:
    ...     raise pinlin.QuasiPeriodicError("no common period", periods={"a": 1.0, "b": 2 ** 0.5})
    ... except pinlin.InputError as exc:
    ...     print(sorted(exc.periods))
    ['a', 'b']
    """

    def __init__(self, message: str, periods: dict):
        super().__init__(message)
        self.periods = dict(periods)


class PeriodicOrbitError(ComputationError):
    """The shooting for a periodic orbit failed (did not converge, diverged, or found no orbit).

    Attributes
    ----------
    history : tuple of float
        The relative residual ||x(T) - x(0)|| of each Newton step (the start first).
    period : float
        The last period tried [s].

    Examples
    --------
    >>> try:
    ...     raise pinlin.PeriodicOrbitError("shooting diverged", history=[1e-2, 1e3], period=2.0)
    ... except pinlin.ComputationError as exc:
    ...     print(exc.period)
    2.0
    """

    def __init__(self, message: str, history=(), period: float = float("nan")):
        super().__init__(message)
        self.history = tuple(float(h) for h in history)
        self.period = float(period)


class OrbitLimitError(PeriodicOrbitError):
    """The motion leaves a joint's position limits of the model.

    Attributes
    ----------
    joint : str
    time : float
        Time [s] at which the limit is crossed.
    value, lower, upper : float
        The joint position and its limits [rad or m].

    Examples
    --------
    >>> try:
    ...     raise pinlin.OrbitLimitError("joint1 leaves its limits",
    ...         "joint1", time=0.7, value=3.2, lower=-3.0, upper=3.0)
    ... except pinlin.PeriodicOrbitError as exc:
    ...     print((exc.joint, exc.upper))
    ('joint1', 3.0)
    """

    def __init__(self, message: str, joint: str, time: float, value: float, lower: float, upper: float,
                 history=(), period: float = float("nan")):
        super().__init__(message, history, period)
        self.joint, self.time, self.value, self.lower, self.upper = joint, float(time), float(value), float(lower), float(upper)
