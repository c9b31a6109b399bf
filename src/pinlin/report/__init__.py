"""The analysis report of ``pinlin analyze``: what it computes, its JSON document, its text and its figure.

One concept per module, in the order the report is made:

- :mod:`.document` -- :func:`analyze`: equilibrium, linearization and modal analysis
  of a scene spec, and the JSON document built from the results' ``to_dict()``;
- :mod:`.schema` -- :data:`REPORT_SCHEMA`, the JSON Schema of that document (the
  published contract, versioned by :data:`REPORT_VERSION`);
- :mod:`.units` -- the units of coordinates and matrix entries that the report prints;
- :mod:`.text` -- :func:`render_text`, the human-readable report;
- :mod:`.figure` -- :func:`write_plot`, the eigenvalue map and frequency responses;
- :mod:`.outputs` -- the optional outputs (``--json``, ``--plot``, ``--animate``): checked
  before computing, written after the text;
- :mod:`.scenes` -- the scenes analysed without a scene file (``--example``, the bundled ones);
- :mod:`.sweep` -- ``pinlin sweep``: the ``[sweep]`` table, the sweep, its document, text and figure.

The command line itself (argparse, exit codes) is :mod:`pinlin.cli`.
"""

from .document import analyze, matrix_structure, scene_section
from .figure import write_plot
from .schema import REPORT_SCHEMA, REPORT_VERSION
from .text import render_text

__all__ = ["analyze", "scene_section", "matrix_structure", "REPORT_SCHEMA", "REPORT_VERSION", "render_text", "write_plot"]
