"""Calling a parameter family ``func(p) -> LinearizedSystem`` safely and counting the cost (theory: boundaries).

An :class:`Evaluator` wraps the user's function: it checks every value it
returns (a :class:`~pinlin.LinearizedSystem` of one size and one set of
coordinates), turns any failure into a :class:`~pinlin.errors.SystemFunctionError`
that names the parameter value, keeps each system and its modal analysis for the
duration of one search (never longer: the function may change between calls),
and counts the calls of ``func`` and the modal analyses -- the figures the
boundary searches report as their cost.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from ..errors import ParameterError, SystemFunctionError
from ..linearization.system import LinearizedSystem
from ..periodic import FloquetAnalysis
from ..spectral import Modes, modal_analysis

__all__ = ["Evaluator", "PeriodicFamily", "call_family", "VERDICT_CLASS", "verdict_class", "check_parameter"]

#: The stability kinds (``modes.stability.kind``) grouped into the classes whose change is a boundary:
#: asymptotic and marginal stability are one class ("stable"); "undecided" is its own.
VERDICT_CLASS = {
    "asymptotically_stable": "stable",
    "marginally_stable": "stable",
    "divergence": "divergence",
    "flutter": "flutter",
    "undecided": "undecided",
}


def verdict_class(modes: Modes) -> str:
    """The class of ``modes.stability.kind`` (see :data:`VERDICT_CLASS`)."""
    return VERDICT_CLASS[modes.stability.kind]


def check_parameter(value, label: str) -> float:
    """``value`` as a finite float.

    Raises
    ------
    ParameterError
        Not a real finite number.
    """
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected a real number, got {value!r}") from None
    if not math.isfinite(out):
        raise ParameterError(label, f"expected a finite number, got {value!r}")
    return out


def call_family(func: Callable, p: float, label: str = "func"):
    """``func(p)``; any failure of the user's function as a :class:`~pinlin.errors.SystemFunctionError`
    naming the parameter value (the cause chained)."""
    try:
        return func(p)
    except Exception as exc:  # noqa: BLE001 - any failure of the user's function is reported with p
        raise SystemFunctionError(f"{label}({p!r}) raised {type(exc).__name__}: {exc}", p) from exc


class PeriodicFamily(Exception):  # noqa: N818 - a signal to the search, not an error the user sees
    """Raised by :meth:`Evaluator.system` when the family returns a Floquet analysis: the search of a
    periodic family is a different one (:mod:`pinlin.boundaries.periodic`); ``p`` and ``value`` hand over
    the value already computed."""

    def __init__(self, p: float, value: FloquetAnalysis):
        super().__init__(p)
        self.p, self.value = p, value


class Evaluator:
    """``func`` with checks, a per-search memory of its values, and cost counters.

    Parameters
    ----------
    func : callable
        ``func(p) -> LinearizedSystem``.
    modal_options : mapping, optional
        Keyword arguments passed to :func:`pinlin.modal_analysis`.
    label : str
        How ``func`` is named in error messages.

    Attributes
    ----------
    calls : int
        Calls of ``func`` made so far.
    analyses : int
        Modal analyses made so far.
    """

    def __init__(self, func: Callable[[float], Any], modal_options: Mapping[str, Any] | None = None,
                 label: str = "func"):
        if not callable(func):
            raise ParameterError(label, f"expected a callable p -> LinearizedSystem, got {type(func).__name__}")
        self.func = func
        self.label = label
        self.modal_options = dict(modal_options or {})
        self.calls = 0
        self.analyses = 0
        self._systems: dict[float, LinearizedSystem] = {}
        self._modes: dict[float, Modes] = {}
        self._first: tuple[float, LinearizedSystem] | None = None

    def system(self, p: float) -> LinearizedSystem:
        """``func(p)``, checked (computed once per value of p).

        Raises
        ------
        SystemFunctionError
            ``func`` raised, returned something other than a LinearizedSystem, or
            a system whose size or coordinates differ from its first value.
        """
        p = float(p)
        if p in self._systems:
            return self._systems[p]
        self.calls += 1
        sys = call_family(self.func, p, self.label)
        if isinstance(sys, FloquetAnalysis) and self._first is None:
            raise PeriodicFamily(p, sys)
        if not isinstance(sys, LinearizedSystem):
            raise SystemFunctionError(
                f"{self.label}({p!r}) returned {type(sys).__name__}; expected a pinlin.LinearizedSystem", p
            )
        if self._first is None:
            self._first = (p, sys)
        else:
            p0, sys0 = self._first
            if sys.n != sys0.n or sys.dof_names != sys0.dof_names:
                raise SystemFunctionError(
                    f"{self.label} returned systems of different sizes or coordinates: n = {sys0.n} "
                    f"{sys0.dof_names} at p = {p0!r}, n = {sys.n} {sys.dof_names} at p = {p!r}", p
                )
        self._systems[p] = sys
        return sys

    def modes(self, p: float) -> Modes:
        """The modal analysis of ``func(p)`` (computed once per value of p).

        Raises
        ------
        SystemFunctionError
            As :meth:`system`.
        """
        p = float(p)
        if p not in self._modes:
            sys = self.system(p)
            self.analyses += 1
            self._modes[p] = modal_analysis(sys, **self.modal_options)
        return self._modes[p]

    def matrices(self, p: float) -> np.ndarray:
        """(3, n, n) stack of M, C, K of ``func(p)``."""
        sys = self.system(p)
        return np.stack([sys.M, sys.C, sys.K])

    def evaluated(self) -> list[float]:
        """Parameter values at which ``func`` has been called, in increasing order."""
        return sorted(self._systems)

    def nearest(self, p: float, *, exclude: float | None = None) -> float | None:
        """The evaluated parameter value nearest to p (other than ``exclude``), or None."""
        others = [x for x in self._systems if x != exclude]
        return min(others, key=lambda x: abs(x - p)) if others else None
