"""The result of a one-parameter stability boundary search: :class:`CriticalParameter`."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..results import Result

__all__ = ["CriticalParameter"]


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class CriticalParameter(Result):
    """A stability boundary p* of a one-parameter family (theory: boundaries).

    Attributes
    ----------
    value : float
        p* [unit of p].
    kind : str
        "divergence" or "flutter": the verdict on the unstable side; between two
        unstable verdicts (flutter on one side, divergence on the other),
        "divergence" (where real eigenvalues in the right half-plane appear).
    mechanism : str
        "crossing" (an eigenvalue crosses the imaginary axis transversally),
        "coalescence" (two eigenvalues meet and leave an axis: a double eigenvalue
        at p*) or "bisection" (verdicts only).
    eigenvalue : complex
        The critical eigenvalue at p* [1/s] (on the imaginary axis for a
        stable/unstable boundary; the double eigenvalue of a coalescence).
    error_bound : float
        Absolute bound on |p* - value| [unit of p]: the last Newton correction
        plus ``BOUND_SAFETY`` times the root's rounding-level uncertainty, widened
        to the interval over which the verdicts were checked on both sides
        (``verified``); for bisection half the final bracket.
    bracket : tuple of float
        The final verdict bracket: the verdicts at its ends differ.
    verdicts : tuple of str
        Stability kinds below and above p*.
    verified : bool
        The verdicts at value -+ error_bound were computed and differ.
    evaluations : int
        Modal analyses made (the bracket's ends included).
    function_calls : int
        Calls of ``func``.
    steps : tuple of str
        The iteration's steps, in order.
    method : str
    error : float
        ``error_bound`` (absolute, in the unit of p).
    elapsed : float
        Seconds [s].
    notes : tuple of str

    Examples
    --------
    >>> def family(p):
    ...     return pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.1]], [[1.0 - p]])
    >>> crit = pinlin.critical_parameter(family, (0.0, 2.0))
    >>> crit.mechanism, crit.verdicts, crit.verified
    ('crossing', ('asymptotically_stable', 'divergence'), True)
    """

    value: float
    kind: str
    mechanism: str
    eigenvalue: complex
    error_bound: float
    bracket: tuple[float, float]
    verdicts: tuple[str, str]
    verified: bool
    evaluations: int
    function_calls: int
    steps: tuple[str, ...]
    method: str
    elapsed: float
    notes: tuple[str, ...] = field(default=())

    @property
    def error(self) -> float:
        return self.error_bound

    def __repr__(self) -> str:
        return (f"CriticalParameter(value={self.value:.15g}, kind={self.kind!r}, mechanism={self.mechanism!r}, "
                f"error_bound={self.error_bound:.1e}, eigenvalue={self.eigenvalue:.6g}, "
                f"evaluations={self.evaluations}, verified={self.verified}, elapsed={self.elapsed:.3g}s)")

