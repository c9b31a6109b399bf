"""pinlin's results in other tools' forms: state-space models for python-control and scipy.

One concept per module:

- :mod:`.signal_names` -- the inputs and outputs of a model written as short strings
  (``"force:joint1"``, ``"follower:tip:fz"``, ``"position:tip:x"``, ...): the table of kinds,
  units and names;
- :mod:`.frames` -- frame inputs and outputs at the operating point: wrench columns of B and
  frame rows of C through the scene's Jacobians (and ``sys.basis`` with constraints);
- :mod:`.statespace` -- :func:`state_space` -> :class:`StateSpaceModel` (A, B, C, D and names),
  with ``to_control()`` and ``to_scipy()``;
- python-control is imported on demand (:mod:`pinlin.extras`; the optional extra ``control``)
  and :func:`frequency_response_data`, a :class:`~pinlin.FrequencyResponse` as its
  ``FrequencyResponseData``.
"""

from ..extras import import_control
from ..frf.control import frequency_response_data
from .signal_names import (
    INPUT_KINDS,
    OUTPUT_KINDS,
    POINT_AXES,
    WRENCH_AXES,
    Signal,
    parse_inputs,
    parse_outputs,
)
from .statespace import PERIODIC_TOL, StateSpaceModel, state_space

__all__ = [
    "state_space",
    "StateSpaceModel",
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
