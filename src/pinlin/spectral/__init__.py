"""Spectral analysis of L(lam) = lam^2 M + lam C + K (theory: spectrum, stability, conventions).

One concept per module, in the order of :func:`modal_analysis`:

- :mod:`.problem` -- the coefficients and their norms (Fan-Lin-Van Dooren
  scaling from :mod:`pinlin.numerics.scaling`);
- :mod:`.paths` -- which solver path applies, and why (:func:`choose_path`);
- :mod:`.raw` -- :class:`~pinlin.spectral.raw.RawSpectrum`, what a solver path returns;
- :mod:`.qep` -- the general solver (scaled companion form, QZ, vector recovery);
- :mod:`.structured` -- cheaper exact paths for structured mechanical systems;
- :mod:`.refine` -- eigh with Newton refinement for the symmetric-definite pencils
  of those paths (backward errors at rounding level whatever cond(M)), from one
  Cholesky factor of M that also predicts eigh's accuracy (:func:`~pinlin.spectral.refine.mass_factor`);
- :mod:`.ordering` -- the order of the spectrum and the per-eigenvalue kinds (vectorized);
- :mod:`.accuracy` -- eta, kappa, sensitivities and the error model (bounds as
  functions of the data uncertainty) of the computed pairs (formulas in
  :mod:`pinlin.numerics.accuracy`);
- :mod:`.multiplicity` -- clusters of computed eigenvalues and their partial
  multiplicities (block Toeplitz ranks; semisimple clusters certified without an SVD);
- :mod:`.projected` -- the partial multiplicities of a cluster from the small pencil projected
  on its deflating subspace (no SVD of size n);
- :mod:`.clusters` -- the clusters of a computed spectrum, their structure (a conjugate cluster
  from its partner) and their left vectors;
- :mod:`.jordan` -- Jordan chains at an eigenvalue (:func:`jordan_chains`);
- :mod:`.qualitative` -- modal constants m, d, g, k, n and structural facts;
- :mod:`.stability` -- the verdict: :class:`Stability` and the theorems on structure alone
  (:mod:`.stability.verdict`), its rules tried in order (:mod:`.stability.rules`),
  :func:`decide_stability` and :func:`stability_from_structure` (:mod:`.stability.decide`; the
  verdict's margin computed on first access);
- :mod:`.deferred` -- what :class:`Modes` keeps to form its condition numbers, structural
  facts, verdict and notes on first access;
- :mod:`.modes` -- the result object :class:`Modes` (condition numbers, modal
  constants, participation, structural facts, verdict and notes formed on first access);
- :mod:`.participation` -- each coordinate's share of a mode's kinetic plus potential energy;
- :mod:`.energy` -- :class:`ModeEnergy` (``modes.energy(k, scene)``): a mode's kinetic energy per
  body, strain energy per element and dissipation per damper;
- :mod:`.tables` -- one record per eigenvalue (``modes.to_pandas()``);
- :mod:`.analysis` -- :func:`modal_analysis`, which ties them together.
"""

from .analysis import EIGH_TOL, STRUCTURE_TOL, modal_analysis
from .energy import ModeEnergy, mode_energy
from .jordan import CLUSTER_TOL, RANK_TOL, JordanChains, jordan_chains
from .modes import MODE_KINDS, Method, Modes
from .multiplicity import Cluster
from .participation import DOMINANT_COUNT, DOMINANT_SHARE
from .problem import QuadraticProblem, Scaling, as_problem, fan_lin_van_dooren
from .qualitative import DEFAULT_UNCERTAINTY, DEFINITENESS_TOL, ModeConstants, StructuralFacts
from .stability import KINDS, MARGIN_CAP, STABILITY_SAFETY, Stability, stability_from_structure

__all__ = [
    "modal_analysis",
    "jordan_chains",
    "stability_from_structure",
    "Modes",
    "Method",
    "Stability",
    "Cluster",
    "JordanChains",
    "ModeEnergy",
    "mode_energy",
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
    "DEFAULT_UNCERTAINTY",
    "STABILITY_SAFETY",
    "MARGIN_CAP",
    "DOMINANT_SHARE",
    "DOMINANT_COUNT",
]
