"""Validation of the coefficient callables and the period of a Floquet analysis (theory: Floquet).

Every coefficient is turned into a function t -> a real (rows, cols) float array that checks each value it
returns (the callables will be Pinocchio evaluations along an orbit, where a NaN means a broken orbit, not a
number to integrate).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..errors import ParameterError

__all__ = ["check_period", "coefficient"]


def check_period(period) -> float:
    """T as a float [s]; ParameterError unless a finite positive real number.

    Examples
    --------
    >>> from pinlin.periodic.inputs import check_period
    >>> check_period(2 * np.pi) == 2 * np.pi
    True
    >>> check_period(-1.0)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: period: ...
    """
    try:
        T = float(period)
    except (TypeError, ValueError):
        raise ParameterError("period", f"expected a positive number of seconds, got {period!r}") from None
    if not math.isfinite(T) or T <= 0:
        raise ParameterError("period", f"expected a finite positive number of seconds, got {T!r}")
    return T


def _as_matrix(name: str, value, shape, t) -> np.ndarray:
    where = "" if t is None else f" at t = {t:.6g} s"
    try:
        complex_entries = np.iscomplexobj(value)
        a = None if complex_entries else np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, f"expected a real matrix{where}, got {type(value).__name__}") from None
    if complex_entries:
        raise ParameterError(name, f"expected a real matrix{where}, got complex entries")
    if shape is not None and a.shape != shape:
        raise ParameterError(name, f"expected shape {shape}{where}, got {a.shape}")
    if a.ndim != 2 or a.shape[0] != a.shape[1]:
        raise ParameterError(name, f"expected a square matrix{where}, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ParameterError(name, f"non-finite entries{where}")
    return a


def coefficient(name: str, value, shape: tuple | None = None) -> tuple[Callable[[float], np.ndarray], tuple]:
    """(checked function t -> array, shape) for a callable or a constant array ``value``.

    Parameters
    ----------
    name : str
        The argument's name, for messages.
    value : callable or array_like
        t [s] -> (k, k) array, or a constant (k, k) array.
    shape : tuple or None
        The required shape (None: whatever square shape the value at t = 0 has).

    Raises
    ------
    ParameterError
        Not callable and not a matrix; a value of the wrong shape, complex or non-finite (at any time it is
        called: the time is named); a callable that raises is reported with its exception chained.

    Examples
    --------
    >>> from pinlin.periodic.inputs import coefficient
    >>> K, shape = coefficient("K", lambda t: [[2.0 + np.cos(t)]])
    >>> print(shape, K(0.0))
    (1, 1) [[3.]]
    """
    if not callable(value):
        if value is None or isinstance(value, (str, bytes)):
            raise ParameterError(name, f"expected a callable t -> matrix or a constant matrix, got {value!r}")
        a = np.array(_as_matrix(name, value, shape, None), copy=True)
        a.flags.writeable = False
        return (lambda t: a), a.shape

    cache: dict = {}
    expected = [shape]

    def checked(t: float) -> np.ndarray:
        if t == 0.0 and cache:       # the value at 0 that validated the callable (a function of t)
            return cache[0.0]
        try:
            raw = value(t)
        except Exception as exc:  # the user's callable: report which argument and when
            raise ParameterError(name, f"raised {type(exc).__name__} at t = {t:.6g} s: {exc}") from exc
        a = _as_matrix(name, raw, expected[0], t)
        expected[0] = a.shape
        return a

    first = np.array(checked(0.0), copy=True)
    first.flags.writeable = False
    cache[0.0] = first
    return checked, first.shape
