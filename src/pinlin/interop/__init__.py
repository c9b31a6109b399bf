"""pinlin's results in other tools' forms: state-space models for python-control and scipy (issue 17).

One concept per module:

- :mod:`.signals` -- the inputs and outputs of a model written as short strings
  (``"force:joint1"``, ``"follower:tip:fz"``, ``"position:tip:x"``, ...): the table of kinds,
  units and names;
- :mod:`.frames` -- frame inputs and outputs at the operating point: wrench columns of B and
  frame rows of C through the scene's Jacobians (and ``sys.basis`` with constraints);
- :mod:`.statespace` -- :func:`state_space` -> :class:`StateSpaceModel` (A, B, C, D and names),
  with ``to_control()`` and ``to_scipy()``;
- :mod:`.python_control` -- python-control imported on demand (the optional extra ``control``)
  and :func:`frequency_response_data`, a :class:`~pinlin.FrequencyResponse` as its
  ``FrequencyResponseData``.
"""

from .python_control import frequency_response_data, import_control
from .signals import INPUT_KINDS, OUTPUT_KINDS, POINT_AXES, WRENCH_AXES, Signal, parse_inputs, parse_outputs
from .statespace import PERIODIC_TOL, StateSpaceModel, first_order, state_space

__all__ = [
    "state_space",
    "StateSpaceModel",
    "first_order",
    "PERIODIC_TOL",
    "frequency_response_data",
    "import_control",
    "Signal",
    "parse_inputs",
    "parse_outputs",
    "INPUT_KINDS",
    "OUTPUT_KINDS",
    "WRENCH_AXES",
    "POINT_AXES",
]
