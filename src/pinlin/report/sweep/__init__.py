"""``pinlin sweep``: a scene over one or two parameters.

One concept per module, in the order the sweep is made:

- :mod:`.parameters` -- the ``[sweep]`` table: parameter paths, values, and the scene
  at each value (:func:`sweep_plan`, :class:`SweepPlan`);
- :mod:`.run` -- :func:`run_sweep`: the modes at every point, tracked by shape, the
  verdicts and the exact boundaries between them (:func:`pinlin.critical_parameter`);
- :mod:`.document` -- :func:`sweep_document`, the JSON document;
- :mod:`.schema` -- :data:`SWEEP_SCHEMA`, its JSON Schema (version :data:`SWEEP_VERSION`);
- :mod:`.text` -- :func:`render_sweep_text`, the human-readable report;
- :mod:`.figure` -- :func:`write_sweep_plot`: root locus and tracked modes, or a stability map.
"""

from .document import sweep_document
from .figure import write_sweep_plot
from .parameters import MAX_POINTS, SweepParameter, SweepPlan, sweep_plan
from .run import SweepOutcome, VerdictChange, run_sweep, system_at
from .schema import SWEEP_SCHEMA, SWEEP_VERSION
from .text import render_sweep_text

__all__ = [
    "sweep_plan",
    "SweepPlan",
    "SweepParameter",
    "MAX_POINTS",
    "run_sweep",
    "system_at",
    "SweepOutcome",
    "VerdictChange",
    "sweep_document",
    "SWEEP_SCHEMA",
    "SWEEP_VERSION",
    "render_sweep_text",
    "write_sweep_plot",
]
