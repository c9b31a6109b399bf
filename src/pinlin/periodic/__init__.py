"""Time-periodic linear equations: Floquet analysis and the multi-blade transform (theory: Floquet).

One concept per module:

- :mod:`.options` -- :class:`FloquetOptions`, the pipeline's numerical options and their defaults, checked once;
- :mod:`.inputs` -- checked coefficient functions t -> matrix and the period;
- :mod:`.sampling` -- the trigonometric interpolant of periodic coefficients from equispaced samples, its
  error measured on fresh samples;
- :mod:`.second_order` -- M, C, K in first-order form, and the tests of their conservative structure
  (constant, or a time-varying Lagrangian system);
- :mod:`.gauss_step` -- the Gauss-Legendre collocation step with step doubling and its accept test, on a
  stack of steps;
- :mod:`.collocation` -- step transitions of y' = A(t) y step by step,
  grouped into well-conditioned segments;
- :mod:`.collocation_grid` -- the same on a step grid refined in rounds, for coefficients cheap at many times;
- :mod:`.jumps` -- jumps of the coefficients, found in their samples and located by bisection (step boundaries);
- :mod:`.sampled` -- the transitions from sampled coefficients (or, where they do not converge, at the nodes
  with a step boundary at each jump);
- :mod:`.cyclic` -- multipliers and periodic eigenvectors of a segment product from the lifted block-cyclic
  matrix (the product is never formed for them);
- :mod:`.bounds` -- each multiplier's error bound (integration error, eigensolver backward error and the
  reference orbit's error through its periodic condition; the square-root bound of a Jordan pair at 1);
- :mod:`.harmonics` -- frequencies of the Floquet modes from their harmonic content;
- :mod:`.floquet_verdict` -- the stability verdict from multipliers, bounds and (conservative) Krein signatures;
- :mod:`.result` -- :class:`FloquetAnalysis`, the result;
- :mod:`.analysis` -- :func:`floquet_from_first_order` and :func:`floquet_analysis_matrices`;
- :mod:`.multiblade` -- :func:`multiblade_transform_matrices` (Coleman coordinates of N >= 3 identical blades).

Scenes (a URDF model with periodic prescribed motions or an autonomous free oscillation):

- :mod:`.period` -- :func:`scene_period`, the common period of everything that moves;
- :mod:`.coefficients` -- :func:`variational_coefficients`: M(t), C(t), K(t) along a motion from Pinocchio's
  RNEA derivatives at the actual acceleration;
- :mod:`.orbit_result` -- :class:`PeriodicOrbit`, the periodic reference motion;
- :mod:`.orbit_error` -- the orbit's own error in its variational coefficients (its first-order correction);
- :mod:`.shooting` -- :func:`periodic_orbit`, that motion by Newton shooting with the monodromy;
- :mod:`.scene_floquet` -- :func:`floquet_analysis`, the Floquet analysis of a scene along its orbit;
- :mod:`.multiblade_scene` -- :func:`multiblade_transform`, a scene's rotor in multi-blade coordinates.
"""

from .analysis import floquet_analysis_matrices, floquet_from_first_order
from .coefficients import VariationalCoefficients, variational_coefficients
from .multiblade import multiblade_transform_matrices
from .multiblade_scene import multiblade_transform
from .options import FloquetOptions
from .orbit_result import PeriodicOrbit
from .period import scene_period
from .result import FloquetAnalysis
from .scene_floquet import floquet_analysis
from .shooting import periodic_orbit

__all__ = ["FloquetAnalysis", "FloquetOptions", "floquet_from_first_order", "floquet_analysis_matrices",
           "multiblade_transform_matrices", "multiblade_transform", "PeriodicOrbit", "periodic_orbit",
           "floquet_analysis", "variational_coefficients", "VariationalCoefficients", "scene_period"]
