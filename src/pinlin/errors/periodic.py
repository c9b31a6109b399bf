"""Errors of the time-periodic analyses (theory: Floquet): a multi-blade transform that is not exact."""

from __future__ import annotations

from .base import InputError

__all__ = ["MultibladeNotExactError"]


class MultibladeNotExactError(InputError):
    """The multi-blade (Coleman) coordinates leave time-dependent coefficients (N = 2 blades, dissimilar
    blades or blades not equally spaced): the transform is not exact and the system needs Floquet analysis.

    Attributes
    ----------
    matrix : str
        The transformed matrix that varies ("M", "C" or "K").
    variation : float
        Its largest relative change over the checked times.
    tolerance : float
        The relative change allowed.
    """

    def __init__(self, message: str, matrix: str, variation: float, tolerance: float):
        super().__init__(message)
        self.matrix, self.variation, self.tolerance = matrix, float(variation), float(tolerance)
