"""Time-domain responses of the linearized system (theory: responses).

One concept per module:

- :mod:`.free` -- free vibration from the modal solution (Jordan chains for defective roots);
- :mod:`.forced` -- any sampled or callable force, by exact discretization;
- :mod:`.energy` -- the linearized power theorem along a trajectory;
- :mod:`.sampled_force` -- the piecewise-polynomial reading of sampled (or callable) forces
  that the responses share (their input checks are in
  :mod:`pinlin.numerics.arrays`).

Arrays are (len(t), n): time first, coordinates last.  The modal expansion the
free response evaluates is :mod:`pinlin.frf.expansion` (also the modal method of
the H(s) engine); steady harmonic responses are in :mod:`pinlin.frf`, the
nonlinear reference simulation in :mod:`pinlin.nonlinear`.
"""

from ..frf.expansion import JordanBlock, ModalExpansion, modal_expansion
from .energy import EnergyBudget, energy_budget
from .forced import ForcedResponse, forced_response
from .free import FreeResponse, free_response
from .sampled_force import INTERPOLATIONS, SampledForce

__all__ = [
    "free_response",
    "FreeResponse",
    "forced_response",
    "ForcedResponse",
    "energy_budget",
    "EnergyBudget",
    "modal_expansion",
    "ModalExpansion",
    "JordanBlock",
    "SampledForce",
    "INTERPOLATIONS",
]

