"""Spectral analysis of L(lam) = lam^2 M + lam C + K (SPEC sections 4, 5 and 9).

One concept per module:

- :mod:`.problem` -- the coefficients, their norms, Fan-Lin-Van Dooren scaling;
- :mod:`.qep` -- the general solver (scaled companion form, QZ, vector recovery);
- :mod:`.structured` -- cheaper exact paths for structured mechanical systems;
- :mod:`.accuracy` -- backward error eta, condition number kappa, error bounds;
- :mod:`.jordan` -- clusters, partial multiplicities, Jordan chains;
- :mod:`.qualitative` -- modal constants m, d, g, k, n and structural facts;
- :mod:`.stability` -- the honest stability verdict;
- :mod:`.modes` -- the result object;
- :mod:`.analysis` -- :func:`modal_analysis`, which ties them together.
"""

from .analysis import EIGH_TOL, STRUCTURE_TOL, modal_analysis
from .jordan import CLUSTER_TOL, RANK_TOL, Cluster, JordanChains, jordan_chains
from .modes import MODE_KINDS, Method, Modes
from .problem import QuadraticProblem, Scaling, as_problem, fan_lin_van_dooren
from .qualitative import DEFINITENESS_TOL, ModeConstants, StructuralFacts
from .stability import KINDS, STABILITY_SAFETY, Stability, stability_from_structure

__all__ = [
    "modal_analysis",
    "jordan_chains",
    "stability_from_structure",
    "Modes",
    "Method",
    "Stability",
    "Cluster",
    "JordanChains",
    "ModeConstants",
    "StructuralFacts",
    "QuadraticProblem",
    "Scaling",
    "as_problem",
    "fan_lin_van_dooren",
    "KINDS",
    "MODE_KINDS",
    "CLUSTER_TOL",
    "RANK_TOL",
    "STRUCTURE_TOL",
    "EIGH_TOL",
    "DEFINITENESS_TOL",
    "STABILITY_SAFETY",
]
