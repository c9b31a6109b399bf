"""The verdict bracket of a boundary search (theory: boundaries).

Two parameter values whose stability verdicts fall in different classes
(:data:`~pinlin.boundaries.evaluation.VERDICT_CLASS`) enclose a boundary.  Every
new verdict replaces the end of its own class, so the bracket only shrinks and
always encloses a verdict change; an "undecided" verdict (a point within
rounding of the boundary) leaves it as it is.  A verdict of a third class (a
flutter point between a stable and a divergent end) becomes the upper end: the
lower of the boundaries is kept, and ``changed`` tells the search to look at
the new pair of verdicts again.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import BracketError, ComputationError
from .evaluation import Evaluator, check_parameter, verdict_class

__all__ = ["Bracket", "BracketChanged", "PlanMismatch", "open_bracket"]


class BracketChanged(ComputationError):
    """Internal signal: a verdict of a third class replaced an end; the search is planned again.

    :func:`~pinlin.boundaries.critical_parameter` catches it; it never reaches the caller.
    """


class PlanMismatch(ComputationError):
    """Internal signal: the quantity a search tracks does not change sign across the bracket.

    :func:`~pinlin.boundaries.critical_parameter` catches it and tries the next mechanism.
    """


@dataclass
class Bracket:
    """The current enclosure [lo, hi] of a verdict change, and the verdicts seen.

    Attributes
    ----------
    lo, hi : float
    class_lo, class_hi : str
        Verdict classes at the ends (different).
    kind_lo, kind_hi : str
        The stability kinds at the ends.
    log : list of (p, kind, step)
        Every verdict computed during the search, with the step that chose p.
    changed : bool
        The classes of the ends changed (a third class was met).
    """

    lo: float
    hi: float
    class_lo: str
    class_hi: str
    kind_lo: str
    kind_hi: str
    log: list[tuple[float, str, str]] = field(default_factory=list)
    changed: bool = False

    @property
    def width(self) -> float:
        return self.hi - self.lo

    def inside(self, p: float) -> bool:
        """p strictly between the ends."""
        return self.lo < p < self.hi

    def judge(self, ev: Evaluator, p: float, step: str, *, replan: bool = True) -> str:
        """The verdict class at p (one modal analysis); the bracket moves the end of that class to p.

        A verdict of a third class becomes the upper end and, with ``replan``, raises
        :class:`BracketChanged` so that the search is chosen again for the new pair of verdicts.
        """
        modes = ev.modes(p)
        kind = modes.stability.kind
        cls = verdict_class(modes)
        self.log.append((float(p), kind, step))
        if self.inside(p):
            if cls == self.class_lo:
                self.lo, self.kind_lo = float(p), kind
            elif cls == self.class_hi:
                self.hi, self.kind_hi = float(p), kind
            elif cls != "undecided":
                self.hi, self.class_hi, self.kind_hi, self.changed = float(p), cls, kind, True
                if replan:
                    raise BracketChanged(f"verdict {kind!r} at p = {p!r} between {self.kind_lo!r} and the old upper end"
                    )
        return cls


def open_bracket(ev: Evaluator, bracket) -> Bracket:
    """Evaluate the verdicts at the ends of ``bracket`` (two modal analyses) and check they differ.

    Raises
    ------
    BracketError
        Not two distinct finite numbers; an end's verdict is "undecided"; both
        ends have the same verdict class.
    SystemFunctionError
        From ``func``.
    """
    try:
        a, b = bracket
    except (TypeError, ValueError):
        raise BracketError(f"expected a bracket (p_low, p_high), got {bracket!r}", (bracket,)) from None
    a, b = check_parameter(a, "bracket[0]"), check_parameter(b, "bracket[1]")
    if a == b:
        raise BracketError(f"the bracket's ends are equal ({a!r}); expected two distinct values", (a, b))
    lo, hi = min(a, b), max(a, b)
    kinds = (ev.modes(lo).stability.kind, ev.modes(hi).stability.kind)
    classes = (verdict_class(ev.modes(lo)), verdict_class(ev.modes(hi)))
    if "undecided" in classes:
        end = lo if classes[0] == "undecided" else hi
        raise BracketError(
            f"the stability verdict at the bracket end p = {end!r} is 'undecided' (within rounding of a boundary): "
            f"move the end away from it; verdicts {kinds} at ({lo!r}, {hi!r})", (lo, hi), kinds)
    if classes[0] == classes[1]:
        raise BracketError(
            f"both ends of the bracket ({lo!r}, {hi!r}) have the verdict class {classes[0]!r} ({kinds[0]}, {kinds[1]}): "
            "a bracket must enclose a change of the stability verdict (stable / divergence / flutter)", (lo, hi), kinds)
    out = Bracket(lo, hi, classes[0], classes[1], kinds[0], kinds[1])
    out.log += [(lo, kinds[0], "bracket end"), (hi, kinds[1], "bracket end")]
    return out
