"""The Newton machinery the two equilibrium solvers share (unconstrained and with constraints).

- :func:`newton_step` -- the step of a square system, least squares (minimum norm) when it is singular;
- :data:`ARMIJO`, :data:`STALL_RATIO` -- the line search's sufficient decrease and the stall test;
- :data:`RTOL`, :data:`MAX_ITERATIONS`, :data:`MIN_STEP` -- the solvers' defaults, and
  :func:`check_solver_parameters`, their one check.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg

from ..errors import ParameterError

__all__ = ["newton_step", "check_solver_parameters", "ARMIJO", "STALL_RATIO", "RTOL", "MAX_ITERATIONS", "MIN_STEP"]

#: Armijo's sufficient-decrease constant of the line search: a step is taken when
#: ||r|| falls by at least ARMIJO * alpha of itself (the usual 1e-4 of Nocedal and
#: Wright: almost any decrease, so full Newton steps are kept near the solution).
ARMIJO = 1e-4
#: The residual has stalled when three steps reduced it by less than 1 - STALL_RATIO
#: (10 %): Newton converging would have cut it by orders of magnitude.
STALL_RATIO = 0.9
#: Default relative residual at which the equilibrium solvers stop.
RTOL = 1e-12
#: Default largest number of Newton steps.
MAX_ITERATIONS = 50
#: Default smallest line-search fraction before the search gives up.
MIN_STEP = 1e-10


def newton_step(K: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, bool]:
    """Solve K dx = -r; least squares (minimum norm) when K is singular or nearly so.

    Returns the step and whether least squares was used (the caller reports it).
    """
    with warnings.catch_warnings():
        warnings.simplefilter("error", scipy.linalg.LinAlgWarning)
        try:
            step = scipy.linalg.solve(K, -r, check_finite=False)
            if np.all(np.isfinite(step)):
                return step, False
        except (np.linalg.LinAlgError, scipy.linalg.LinAlgWarning):
            pass
    return scipy.linalg.lstsq(K, -r, check_finite=False)[0], True


def check_solver_parameters(rtol, max_iterations, min_step) -> None:
    """Raise ParameterError unless rtol > 0 is finite, max_iterations >= 0 an integer and 0 < min_step < 1."""
    if not (isinstance(rtol, (int, float, np.integer, np.floating)) and 0 < rtol < np.inf):
        raise ParameterError("rtol", f"must be a positive number, got {rtol!r}")
    if isinstance(max_iterations, bool) or not isinstance(max_iterations, (int, np.integer)) or max_iterations < 0:
        raise ParameterError("max_iterations", f"must be an integer >= 0, got {max_iterations!r}")
    if not (isinstance(min_step, (int, float, np.integer, np.floating)) and 0 < min_step < 1):
        raise ParameterError(
            "min_step", f"must be a line-search fraction in (0, 1), got {min_step!r}"
        )
