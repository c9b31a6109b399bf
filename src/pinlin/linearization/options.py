"""The options of the linearization entry points (:func:`~pinlin.linearize`,
:func:`~pinlin.linearize_many` and the constrained path) as one frozen, validated value
(:class:`LinearizeOptions`), their defaults as named constants, and their one check.

The public functions take the options as explicit keywords, build one
:class:`LinearizeOptions` at entry and hand it down; nothing below them sees a loose
tolerance or a dictionary of options.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from .constraint_set import CONSTRAINT_TOL, RANK_TOL

__all__ = ["EQUILIBRIUM_TOL", "PERIODIC_TOL", "CONSTRAINT_TOL", "RANK_TOL", "LinearizeOptions", "check_tolerances",
           "check_positive"]

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
    check_positive("equilibrium_tol", equilibrium_tol)
    check_positive("periodic_tol", periodic_tol)
    check_positive("constraint_tol", constraint_tol)
    check_positive("rank_tol", rank_tol, upper=1.0)
    if structure_tol is not None and not (is_number(structure_tol) and 0 <= structure_tol < math.inf):
        raise ParameterError("structure_tol", f"must be None or a finite number >= 0, got {structure_tol!r}")


@dataclass(frozen=True)
class LinearizeOptions:
    """The options of one linearization, checked once (see :func:`pinlin.linearize` for each).

    Raises
    ------
    ParameterError
        A tolerance is not a finite positive number (``structure_tol``: None or >= 0;
        ``rank_tol``: below 1).

    Examples
    --------
    >>> options = LinearizeOptions(equilibrium_tol=1e-6)
    >>> options.equilibrium_tol, options.balancing, options.structure_tol
    (1e-06, False, None)
    >>> LinearizeOptions(rank_tol=2.0)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: rank_tol: must be a finite positive number below 1, got 2.0
    """

    balancing: bool = False
    equilibrium_tol: float = EQUILIBRIUM_TOL
    structure_tol: float | None = None
    periodic_tol: float = PERIODIC_TOL
    constraint_tol: float = CONSTRAINT_TOL
    rank_tol: float = RANK_TOL

    def __post_init__(self):
        check_tolerances(self.equilibrium_tol, self.periodic_tol, self.structure_tol, self.constraint_tol, self.rank_tol)
        object.__setattr__(self, "balancing", bool(self.balancing))
