"""The options of the three linearization entry points (:func:`~pinlin.linearize`,
:func:`~pinlin.linearize_many` and the constrained path), their defaults as named constants, and
their one check.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ParameterError
from .constraint_set import CONSTRAINT_TOL, RANK_TOL

__all__ = ["EQUILIBRIUM_TOL", "PERIODIC_TOL", "CONSTRAINT_TOL", "RANK_TOL", "check_tolerances", "check_positive"]

#: Default largest relative equilibrium residual ||r|| / (||tau|| + ||Q_e|| + ||K||) accepted at q.
EQUILIBRIUM_TOL = 1e-8
#: Default largest relative change of the equations when a prescribed joint moves (time invariance).
PERIODIC_TOL = 1e-8


def is_number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


def check_positive(name: str, value, upper: float = math.inf) -> None:
    if not (is_number(value) and 0 < value < upper):
        bound = "" if upper == math.inf else f" below {upper:g}"
        raise ParameterError(name, f"must be a finite positive number{bound}, got {value!r}")


def check_tolerances(equilibrium_tol, periodic_tol, structure_tol, constraint_tol, rank_tol) -> None:
    """Raise ParameterError for a tolerance that is not a finite positive number (structure_tol: >= 0)."""
    if (  # the common case (floats) in one expression; NaN fails every comparison
        type(equilibrium_tol) is float
        and type(periodic_tol) is float
        and type(constraint_tol) is float
        and type(rank_tol) is float
        and (structure_tol is None or type(structure_tol) is float and 0 <= structure_tol < math.inf)
        and 0 < equilibrium_tol < math.inf
        and 0 < periodic_tol < math.inf
        and 0 < constraint_tol < math.inf
        and 0 < rank_tol < 1
    ):
        return
    check_positive("equilibrium_tol", equilibrium_tol)
    check_positive("periodic_tol", periodic_tol)
    check_positive("constraint_tol", constraint_tol)
    check_positive("rank_tol", rank_tol, upper=1.0)
    if structure_tol is not None and not (is_number(structure_tol) and 0 <= structure_tol < math.inf):
        raise ParameterError("structure_tol", f"must be None or a finite number >= 0, got {structure_tol!r}")
