"""Errors of the time-periodic analyses (theory: Floquet): a multi-blade transform that is not exact, periodic
coefficients that sampling cannot resolve."""

from __future__ import annotations

from .base import ComputationError, InputError

__all__ = ["MultibladeNotExactError", "SamplingError"]


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

    Examples
    --------
    >>> try:
    ...     raise pinlin.MultibladeNotExactError("two blades", matrix="M", variation=0.2, tolerance=1e-10)
    ... except pinlin.InputError as exc:
    ...     print(exc.matrix)
    M
    """

    def __init__(self, message: str, matrix: str, variation: float, tolerance: float):
        super().__init__(message)
        self.matrix, self.variation, self.tolerance = matrix, float(variation), float(tolerance)


class SamplingError(ComputationError):
    """``sampling="spectral"`` was asked for, but the trigonometric interpolant of the periodic coefficients
    did not reach its tolerance (non-smooth coefficients, or more harmonics than ``max_samples`` resolves).

    Attributes
    ----------
    samples : int
        Coefficient evaluations made.
    history : tuple of float
        The measured relative interpolation error after each doubling of the samples.
    tolerance : float
        The relative error asked for.

    Examples
    --------
    >>> try:
    ...     raise pinlin.SamplingError("not resolved", samples=64, history=[1e-2, 1e-3], tolerance=1e-12)
    ... except pinlin.ComputationError as exc:
    ...     print(exc.samples)
    64
    """

    def __init__(self, message: str, samples: int, history, tolerance: float):
        super().__init__(message)
        self.samples, self.history, self.tolerance = int(samples), tuple(history), float(tolerance)
