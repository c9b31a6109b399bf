"""Eigenvalue sensitivities and exact stability boundaries (theory: boundaries).

One concept per module:

- :mod:`.evaluation` -- calling ``func(p) -> LinearizedSystem`` safely, counting the cost;
- :mod:`.derivatives` -- dM/dp, dC/dp, dK/dp: exact (user), Richardson differences, secants;
- :mod:`.sensitivity` -- d lambda / dp for simple, semisimple and defective eigenvalues;
  :func:`eigenvalue_sensitivity`;
- :mod:`.bracket` -- the verdict bracket every search keeps;
- :mod:`.crossing` -- Newton on a transversal crossing (Re lambda = 0, mu = 0);
- :mod:`.coalescence` -- Newton on the defining system of a double eigenvalue;
- :mod:`.pairing` -- the predictor that brings a coalescence within Newton's reach;
- :mod:`.verify` -- verdicts beside the value found; bisection on the verdict;
- :mod:`.critical` -- :func:`critical_parameter`, which ties them together;
- :mod:`.continuation` -- :func:`stability_boundary`, a boundary curve in a plane of two parameters;
- the stability map that draws them is :func:`pinlin.plot.stability_map`.
"""

from .continuation import BoundaryFailure, StabilityBoundary, stability_boundary
from .critical import BOUND_SAFETY, MAX_EVALUATIONS, CriticalParameter, critical_parameter
from .derivatives import RICHARDSON_LEVELS, STEP_FRACTION
from .sensitivity import EigenvalueSensitivity, eigenvalue_sensitivity

__all__ = [
    "eigenvalue_sensitivity",
    "EigenvalueSensitivity",
    "critical_parameter",
    "CriticalParameter",
    "stability_boundary",
    "StabilityBoundary",
    "BoundaryFailure",
    "BOUND_SAFETY",
    "MAX_EVALUATIONS",
    "RICHARDSON_LEVELS",
    "STEP_FRACTION",
]
