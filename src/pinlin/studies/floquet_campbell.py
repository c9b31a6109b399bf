"""Campbell diagrams of periodic systems: Floquet exponents against a speed (theory: Floquet).

At each speed the Floquet analysis gives exponents lambda_k = log(mu_k) / T, defined modulo i 2 pi / T; the
representative is the one whose frequency carries most of the mode's energy (``FloquetAnalysis.frequencies``,
from the harmonic content of each Floquet mode).  Those points — decay rate Re lambda_k and identified frequency
— are followed from speed to speed by :func:`~pinlin.studies.tracking.track_modes` (by eigenvalue distance: a
Floquet mode's shape is a periodic function, not a vector to compare); draw them with
``pinlin.plot.campbell(result.speeds, result.exponents, error_bounds=result.error_bound)``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..boundaries.evaluation import call_family
from ..errors import ParameterError, SystemFunctionError
from ..numerics.arrays import readonly
from ..periodic import FloquetAnalysis
from ..results import Result
from .tracking import TrackedModes, track_modes

__all__ = ["FloquetCampbell", "floquet_campbell"]


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class FloquetCampbell(Result):
    """Floquet exponents of a periodic family over a range of speeds.

    Attributes
    ----------
    speeds : (steps,) ndarray
        The speeds [rad/s] (or any parameter) in the order given.
    exponents : (steps, m) ndarray, complex
        Re lambda [1/s] + i (identified frequency) [rad/s] of each mode, in tracked order (column j follows one
        mode).
    error_bound : (steps, m) ndarray
        Bound on each exponent's real part [1/s]: the multiplier's bound over |mu| T.
    stable : tuple of str
        The Floquet verdict at each speed.
    tracked : TrackedModes
        The tracking (its ``order`` maps each analysis' order to the columns).
    error : float
        The largest relative error bound of a multiplier over all speeds.
    elapsed : float
        Seconds [s].
    method : str

    Examples
    --------
    >>> def analysis(w):     # a damped Mathieu equation whose pumping grows with w
    ...     return pinlin.floquet_analysis_matrices([[1.0]], [[0.05]], lambda t: [[1.3 + 0.4 * w * np.cos(t)]], 2 * np.pi)
    >>> camp = pinlin.floquet_campbell(analysis, [0.5, 1.0, 1.5])
    >>> print(camp.speeds.tolist(), len(camp.stable), camp.error < 1e-10)
    [0.5, 1.0, 1.5] 3 True
    """

    speeds: np.ndarray
    exponents: np.ndarray
    error_bound: np.ndarray
    stable: tuple
    tracked: TrackedModes
    error: float
    elapsed: float
    method: str = "Floquet analysis at each speed, exponents identified by harmonic content, tracked"

    def __repr__(self) -> str:
        return (f"FloquetCampbell(steps={self.speeds.size}, modes={self.exponents.shape[1]}, "
                f"error={self.error:.1e}, elapsed={self.elapsed:.3g} s)")


def floquet_campbell(func: Callable[[float], FloquetAnalysis], speeds) -> FloquetCampbell:
    """The Floquet exponents of ``func(speed)`` at each speed, identified and tracked.

    Parameters
    ----------
    func : callable
        ``speed -> FloquetAnalysis`` (e.g. ``lambda w: pinlin.floquet_analysis(scene(w), orbit(w))``).
    speeds : (steps,) array_like
        At least two finite values [rad/s].

    Returns
    -------
    FloquetCampbell

    Raises
    ------
    ParameterError
        Fewer than two speeds, or non-finite ones.
    SystemFunctionError
        ``func`` raised, returned something else or analyses of different sizes.

    Examples
    --------
    >>> def analysis(w):     # a damped Mathieu equation whose pumping grows with w
    ...     return pinlin.floquet_analysis_matrices([[1.0]], [[0.05]], lambda t: [[1.3 + 0.4 * w * np.cos(t)]], 2 * np.pi)
    >>> camp = pinlin.floquet_campbell(analysis, [0.5, 1.0, 1.5])
    >>> print(camp.exponents.shape, camp.stable[0], np.round(camp.exponents.real[0] + 0.0, 6))
    (3, 2) asymptotically_stable [-0.025 -0.025]
    """
    t0 = time.perf_counter()
    w = np.asarray(speeds, dtype=float).ravel()
    if w.size < 2 or not np.all(np.isfinite(w)):
        raise ParameterError("speeds", f"expected at least two finite speeds, got {speeds!r}")
    rows, bounds, kinds, worst = [], [], [], 0.0
    for s in w.tolist():
        flo = call_family(func, float(s))
        if not isinstance(flo, FloquetAnalysis):
            raise SystemFunctionError(f"func({s!r}) returned {type(flo).__name__}; expected a FloquetAnalysis",
                                      float(s))
        if rows and flo.multipliers.size != rows[0].size:
            raise SystemFunctionError(f"func({s!r}) has {flo.multipliers.size} multipliers, the first speed "
                                      f"{rows[0].size}", float(s))
        mu = np.asarray(flo.multipliers)
        rows.append(np.asarray(flo.exponents).real + 1j * np.asarray(flo.frequencies))
        bounds.append(np.asarray(flo.error_bound) / np.maximum(np.abs(mu), np.finfo(float).tiny) / flo.period)
        kinds.append(flo.stability.kind)
        worst = max(worst, float(flo.error))
    tracked = track_modes(np.array(rows))
    exponents = np.asarray(tracked.eigenvalues)
    bound = np.take_along_axis(np.array(bounds), np.asarray(tracked.order), axis=1)
    return FloquetCampbell(speeds=readonly(w), exponents=readonly(exponents), error_bound=readonly(bound),
                           stable=tuple(kinds), tracked=tracked, error=worst, elapsed=time.perf_counter() - t0)
