"""Figures: spectra, loci, Campbell diagrams, stability maps, responses, mode shapes and their animations.

matplotlib is an optional extra (``pip install 'pinlin[plot]'``).  Every function
takes an optional ``ax`` (or ``axes``) to draw into and returns it, so plots
compose into the user's own figures; without matplotlib each raises
:class:`~pinlin.errors.MissingDependencyError`.  Conventions (docs/conventions.md):
lambda [1/s] in the complex plane, frequencies omega [rad/s], phases in degrees
on axes, positions [m].  No function here runs Pinocchio in a ``Data`` of its
own making: kinematics go through the calling thread's workspace
(:func:`pinlin.model.evaluation.workspace`).

One concept per module:

- :mod:`.style` -- the matplotlib import, colours (:data:`VERDICT_COLORS`) and line widths;
- :mod:`.eigenvalues` -- :func:`eigenvalue_map` (one spectrum, by mode kind, with error
  bars) and :func:`root_locus` (eigenvalues over a parameter, tracked by shape);
- :mod:`.campbell` -- :func:`campbell`: damped frequencies against spin speed;
- :func:`stability_map` -- verdicts over two parameters and the exact boundary
  (:mod:`.stability_map`);
- :mod:`.frequency` -- :func:`frequency_response`: magnitude and phase of one output;
- :mod:`.skeleton` -- the kinematic tree as a stick figure (:class:`Skeleton`) and a
  mode's motion of it (:func:`mode_motion`);
- :mod:`.mode_shapes` -- :func:`mode_shape` (3-D or on a plane, a few phases) and
  :func:`chain_mode_shape` (a planar chain along a given shape);
- :mod:`.animation` -- :func:`animate_mode`: one cycle of a mode, as a GIF or in a notebook;
- :mod:`.energy` -- :func:`mode_energy`: a mode's kinetic, strain and dissipation shares as bars;
- :mod:`.work_precision` -- :func:`work_precision`: error against run time (benchmarks).
"""

from .animation import animate_mode
from .campbell import UNSTABLE_RTOL, campbell
from .eigenvalues import AXIS_MARGIN, KIND_STYLE, MIN_REAL_SPAN_FRACTION, eigenvalue_map, root_locus
from .energy import ENERGY_COLORS, mode_energy
from .frequency import frequency_response
from .mode_shapes import chain_mode_shape, mode_shape
from .skeleton import MODE_AMPLITUDE_FRACTION, ModeMotion, Skeleton, mode_motion
from .stability_map import stability_map
from .style import VERDICT_COLORS
from .work_precision import work_precision

__all__ = [
    "eigenvalue_map",
    "root_locus",
    "campbell",
    "stability_map",
    "frequency_response",
    "mode_shape",
    "animate_mode",
    "mode_motion",
    "ModeMotion",
    "Skeleton",
    "chain_mode_shape",
    "work_precision",
    "mode_energy",
    "ENERGY_COLORS",
    "VERDICT_COLORS",
    "KIND_STYLE",
    "AXIS_MARGIN",
    "MIN_REAL_SPAN_FRACTION",
    "UNSTABLE_RTOL",
    "MODE_AMPLITUDE_FRACTION",
]
