"""Old private helpers of the adjoint package, kept importable while pinlin.frf moves to :mod:`pinlin.numerics`.

Every name here is an alias of the one in :mod:`pinlin.numerics` (or
:mod:`pinlin.results`); nothing is defined here.  Remove this module once no
module imports ``pinlin.adjoint._util``.
"""

from __future__ import annotations

from ..numerics.checks import check_radii, check_system, complex_points, complex_scalar, dof_indices
from ..numerics.checks import check_tolerance as positive
from ..numerics.floating import EPS, LOG_MAX, LOG_TINY, checked_exp
from ..numerics.scaling import eigenvalue_bounds, natural_scale
from ..results import ResultArray

__all__ = [
    "ResultArray",
    "check_system",
    "checked_exp",
    "complex_points",
    "complex_scalar",
    "dof_indices",
    "EPS",
    "natural_scale",
    "eigenvalue_bounds",
    "positive",
    "check_radii",
    "LOG_MAX",
    "LOG_TINY",
]
