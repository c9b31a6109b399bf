"""The limit of a flutter boundary as damping of a given shape vanishes (theory: stability).

For D = eps D1(p) added to a family whose undamped systems func(p) are
marginally stable, the first-order rate of the axis eigenvalues is

.. math::
    g(p) = \\max_k \\frac{d\\,\\mathrm{Re}\\,\\lambda_k}{d\\varepsilon}\\Big|_{\\varepsilon = 0}
         = \\max_k \\langle D_1, \\mathrm{sym}\\,\\mathrm{Re}(-\\lambda_k x_k y_k^T)\\rangle

(:mod:`pinlin.spectral.stability.dissipation`).  For every small eps > 0 the
damped system is asymptotically stable where g < 0 and unstable where g > 0, so
the flutter boundary p_c(eps) tends to the root p_d of g: the limit problem,
solved directly (no sequence of small dampings).  For 2 DOF, g(p) = 0 is
b3 a2 b1 - a4 b1^2 - b3^2 a0 = 0 (theory: stability).  Where g stays negative up to
the point where the undamped eigenvalues meet (a coalescence, beyond which
func(p) is no longer marginally stable), the limit is that coalescence itself,
found by :func:`~pinlin.boundaries.critical_parameter` without ``damping``.

The search: bisection on "g(p) > 0 or func(p) not marginally stable" until
both ends have a computed rate, then Brent's method on g.  The error bound is
the final bracket plus ``BOUND_SAFETY`` times the rate's first-order error
divided by the slope |g'(p_d)| (a central difference).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..errors import BracketError, ConvergenceError, ParameterError
from ..spectral.stability.dissipation import damping_row
from .evaluation import Evaluator

__all__ = ["vanishing_damping_limit", "VanishingLimit", "check_damping", "SLOPE_STEP"]

#: Relative step of the central difference that measures |g'(p_d)| for the error bound.
SLOPE_STEP = 1e-6


def check_damping(damping, n: int) -> Callable[[float], np.ndarray]:
    """``damping`` (an (n, n) array or a callable p -> array) as a callable, checked (ParameterError)."""
    if callable(damping):
        return lambda p: _shape(damping(p), n)
    fixed = _shape(damping, n)
    return lambda p: fixed


def _shape(D1, n: int) -> np.ndarray:
    try:
        D1 = np.array(D1, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("damping", "expected an (n, n) real matrix or a callable p -> matrix") from None
    if D1.shape != (n, n) or not np.all(np.isfinite(D1)):
        raise ParameterError("damping", f"expected a finite ({n}, {n}) matrix, got shape {D1.shape}")
    if not np.allclose(D1, D1.T, rtol=0, atol=1e-14 * max(1.0, float(np.abs(D1).max()))):
        raise ParameterError("damping", "expected a symmetric matrix (a damping shape)")
    return 0.5 * (D1 + D1.T)


def _rate(ev: Evaluator, shape, p: float):
    """(g(p), its error, the axis eigenvalue) or None when func(p) is not marginally stable."""
    modes = ev.modes(p)
    if modes.stability.kind != "marginally_stable":
        return None
    row = damping_row(modes, shape(p))
    if row is None:
        return None
    return row.rate, row.rate_error, row.eigenvalue


@dataclass(frozen=True, kw_only=True)
class VanishingLimit:
    """What :func:`vanishing_damping_limit` found; :func:`pinlin.critical_parameter` makes it a result.

    ``value`` is None when g < 0 up to the coalescence of the undamped eigenvalues (the limit is then the
    coalescence, found without damping).
    """

    value: float | None
    eigenvalue: complex
    error_bound: float
    bracket: tuple[float, float]
    evaluations: int
    function_calls: int
    steps: tuple[str, ...]
    elapsed: float


def vanishing_damping_limit(func, bracket, damping, *, atol: float | None = None, max_evaluations: int = 80,
                            modal_options=None) -> VanishingLimit:
    """The limit p_d of the flutter boundary for D = eps D1, eps -> 0 (module doc).

    Called by :func:`pinlin.critical_parameter` with ``damping=``.

    Returns
    -------
    VanishingLimit

    Raises
    ------
    BracketError
        func(lo) is not marginally stable, or small damping of the shape does not stabilize it there.
    ConvergenceError
        More than ``max_evaluations`` modal analyses.
    """
    t0 = time.perf_counter()
    ev = Evaluator(func, modal_options)
    lo, hi = (float(b) for b in bracket)
    if not (np.isfinite(lo) and np.isfinite(hi) and lo != hi):
        raise BracketError(f"expected two distinct finite numbers, got {bracket!r}", bracket)
    shape = check_damping(damping, ev.system(lo).n)
    at_lo = _rate(ev, shape, lo)
    if at_lo is None or at_lo[0] >= -at_lo[1]:
        raise BracketError(
            f"at p = {lo!r} the undamped system must be marginally stable and small damping of the shape must "
            f"stabilize it (rate {None if at_lo is None else at_lo[0]!r})", bracket)
    steps = [f"g({lo:.6g}) = {at_lo[0]:.3e}"]
    a, b = lo, hi
    at_b = _rate(ev, shape, b)
    while at_b is None:  # beyond the coalescence: bisect until both ends have a rate
        if ev.analyses >= max_evaluations:
            raise ConvergenceError(f"vanishing-damping limit: more than {max_evaluations} modal analyses", steps)
        if abs(b - a) <= 4 * np.finfo(float).eps * max(abs(a), abs(b)):
            steps.append("g < 0 up to where the undamped eigenvalues meet: the limit is the coalescence")
            return VanishingLimit(
                value=None, eigenvalue=0j, error_bound=np.inf, bracket=(a, b), evaluations=ev.analyses,
                function_calls=ev.calls, steps=tuple(steps), elapsed=time.perf_counter() - t0,
            )
        mid = 0.5 * (a + b)
        at_mid = _rate(ev, shape, mid)
        steps.append(f"g({mid:.6g}) = {'not marginal' if at_mid is None else f'{at_mid[0]:.3e}'}")
        if at_mid is not None and at_mid[0] < 0:
            a = mid
        else:
            b, at_b = mid, at_mid
    if at_b[0] <= 0:
        raise BracketError(f"the rate stays negative on [{lo!r}, {hi!r}]: no limit boundary there", bracket)

    def g(p):
        if ev.analyses >= max_evaluations:
            raise ConvergenceError(f"vanishing-damping limit: more than {max_evaluations} modal analyses", steps)
        value = _rate(ev, shape, p)
        if value is None:
            raise ConvergenceError(f"func({p!r}) is not marginally stable inside the rate's bracket", steps)
        return value[0]

    xtol = 2 * np.finfo(float).eps * max(abs(a), abs(b), 1.0) if atol is None else float(atol)
    value, info = brentq(g, a, b, xtol=xtol, rtol=4 * np.finfo(float).eps, full_output=True)
    steps.append(f"Brent on g in [{a:.15g}, {b:.15g}]: {info.iterations} iterations")
    h = SLOPE_STEP * max(abs(value), 1.0)
    slope = abs(g(value + h) - g(value - h)) / (2 * h)
    _, err, lam = _rate(ev, shape, value)
    bound = xtol + 4.0 * err / slope if slope > 0 else np.inf
    return VanishingLimit(
        value=float(value), eigenvalue=complex(lam), error_bound=float(bound), bracket=(a, b),
        evaluations=ev.analyses, function_calls=ev.calls, steps=tuple(steps),
        elapsed=time.perf_counter() - t0,
    )
