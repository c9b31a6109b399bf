"""The honest stability verdict, one concept per module:

- :mod:`.verdict` -- :class:`Stability`, the verdict as a result (kind, reason, margins), and its kinds;
- :mod:`.rules` -- the ordered rules (theorems and numerical decisions) that decide it;
- :mod:`.decide` -- :func:`decide_stability` (the rules against the eigenvalues' error bounds, and the
  margin's bisection) and :func:`stability_from_structure` (the theorems alone);
- :mod:`.unstructured` -- the class of perturbations a margin covers, and the unstructured margin;
- :mod:`.dissipation` -- what small damping of a given shape does to the eigenvalues on the axis
  (:class:`DissipationRow`, the table of a marginal verdict).
"""

from .decide import MARGIN_FLOOR, decide_stability, stability_from_structure
from .dissipation import DissipationRow
from .verdict import KINDS, MARGIN_CAP, STABILITY_SAFETY, Stability, theorem_verdict

__all__ = [
    "Stability",
    "DissipationRow",
    "KINDS",
    "STABILITY_SAFETY",
    "MARGIN_CAP",
    "MARGIN_FLOOR",
    "decide_stability",
    "theorem_verdict",
    "stability_from_structure",
]
