"""The numerical options of the Floquet pipeline, defaulted and validated in one place: :class:`FloquetOptions`.

:func:`~pinlin.periodic.analysis.floquet_from_first_order`, :func:`~pinlin.periodic.analysis.floquet_analysis_matrices`
and :func:`~pinlin.periodic.scene_floquet.floquet_analysis` spell these options out as keywords (with the defaults
below) and hand them on as one :class:`FloquetOptions`, checked once when it is made.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from numbers import Integral, Real

import numpy as np

from ..errors import ParameterError

__all__ = ["FloquetOptions", "RTOL", "STAGES", "GROWTH", "HARMONICS", "SAFETY", "MAX_STEPS", "MAX_TIME",
           "SAMPLING", "SAMPLING_MODES", "MAX_SAMPLES", "STRUCTURE_TOL"]

#: Accepted local error of an integration step, relative to the step transition's 2-norm.
RTOL = 1e-13
#: Gauss-Legendre stages s (order 2 s).
STAGES = 6
#: Condition number at which a segment of step transitions closes.
GROWTH = 1e3
#: J of the reported harmonic content (harmonics j = -J..J).
HARMONICS = 16
#: Factor on the error bounds before they decide the verdict.
SAFETY = 10.0
#: Integration budget: accepted plus rejected steps.
MAX_STEPS = 20000
#: Integration budget: wall time [s].
MAX_TIME = 600.0
#: Default way of evaluating the coefficients (see :data:`SAMPLING_MODES`).
SAMPLING = "auto"
#: "spectral": the trigonometric interpolant of equispaced samples; "nodes": the coefficients at every
#: collocation node; "auto": spectral where the interpolant converges, else nodes.
SAMPLING_MODES = ("auto", "spectral", "nodes")
#: Most samples per period the interpolant may use.
MAX_SAMPLES = 256
#: Relative size [units of eps] below which an asymmetric part of K, a symmetric part of C or a change of
#: M or C over time counts as rounding in the conservative-structure test.
STRUCTURE_TOL = 100.0


def _number(value) -> bool:
    return isinstance(value, Real) and not isinstance(value, bool) and bool(np.isfinite(value))


def _integer(value) -> bool:
    return isinstance(value, Integral) and not isinstance(value, bool)


#: name -> (test, what is expected): the checks of :class:`FloquetOptions`.
_CHECKS = {
    "rtol": (lambda x: _number(x) and 1e-16 <= x < 1e-2, "in [1e-16, 1e-2)"),
    "stages": (lambda x: _integer(x) and 2 <= x <= 12, "an int in 2..12"),
    "growth": (lambda x: _number(x) and 10.0 <= x <= 1e8, "in [10, 1e8]"),
    "harmonics": (lambda x: _integer(x) and x >= 0, "an int >= 0"),
    "safety": (lambda x: _number(x) and 1.0 <= x < 1e6, "in [1, 1e6)"),
    "max_steps": (lambda x: _integer(x) and x >= 1, "an int >= 1"),
    "max_time": (lambda x: _number(x) and x >= 0, "a time >= 0 [s]"),
    "sampling": (lambda x: isinstance(x, str) and x in SAMPLING_MODES,
                 f"one of {', '.join(map(repr, SAMPLING_MODES))}"),
    "max_samples": (lambda x: _integer(x) and 16 <= x <= 65536, "an int in 16..65536"),
    "structure_tol": (lambda x: _number(x) and x >= 0, "a number >= 0 (units of eps)"),
}


@dataclass(frozen=True)
class FloquetOptions:
    """How a Floquet analysis integrates, samples and decides (each field validated when made).

    Attributes
    ----------
    rtol : float
        :data:`RTOL`.
    stages : int
        :data:`STAGES`.
    growth : float
        :data:`GROWTH`.
    harmonics : int
        :data:`HARMONICS`.
    safety : float
        :data:`SAFETY`.
    max_steps, max_time : int, float
        :data:`MAX_STEPS`, :data:`MAX_TIME` [s].
    sampling : {"auto", "spectral", "nodes"}
        :data:`SAMPLING_MODES`.
    max_samples : int
        :data:`MAX_SAMPLES`.
    structure_tol : float
        :data:`STRUCTURE_TOL` [units of eps].

    Raises
    ------
    ParameterError
        An option out of its range (named, with what was expected).

    Examples
    --------
    >>> from pinlin.periodic.options import FloquetOptions
    >>> FloquetOptions(rtol=1e-10).stages
    6
    >>> FloquetOptions(stages=1)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: stages: expected an int in 2..12, got 1
    """

    rtol: float = RTOL
    stages: int = STAGES
    growth: float = GROWTH
    harmonics: int = HARMONICS
    safety: float = SAFETY
    max_steps: int = MAX_STEPS
    max_time: float = MAX_TIME
    sampling: str = SAMPLING
    max_samples: int = MAX_SAMPLES
    structure_tol: float = STRUCTURE_TOL

    def __post_init__(self):
        for f in fields(self):
            value = getattr(self, f.name)
            test, expected = _CHECKS[f.name]
            if not test(value):
                raise ParameterError(f.name, f"expected {expected}, got {value!r}")
            if f.type in ("int", "float"):     # numpy scalars become Python numbers
                object.__setattr__(self, f.name, int(value) if f.type == "int" else float(value))
