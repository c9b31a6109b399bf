"""Responses of the linearized system and the nonlinear reference (SPEC section 6, issue 5).

One concept per module:

- :mod:`.free` -- free vibration from the modal solution (Jordan chains for defective roots);
- :mod:`.harmonic` -- steady state under harmonic forcing, H(i omega) F;
- :mod:`.forced` -- any sampled or callable force, by exact discretization;
- :mod:`.energy` -- the linearized power theorem along a trajectory;
- :mod:`.simulate` -- the nonlinear reference (Pinocchio forward dynamics on the manifold);
- :mod:`.expansion`, :mod:`.state`, :mod:`.signal` -- the modal expansion, the
  first-order form and the piecewise-polynomial reading of sampled forces they share.
"""

from .energy import EnergyBudget, energy_budget
from .expansion import JordanBlock, ModalExpansion, modal_expansion
from .forced import ForcedResponse, forced_response
from .free import FreeResponse, free_response
from .harmonic import HARMONIC_METHODS, HarmonicResponse, harmonic_response
from .signal import INTERPOLATIONS, SampledForce
from .simulate import EXPLICIT_METHODS, IMPLICIT_METHODS, Simulation, linear_coordinates, simulate
from .state import first_order

__all__ = [
    "free_response",
    "FreeResponse",
    "harmonic_response",
    "HarmonicResponse",
    "HARMONIC_METHODS",
    "forced_response",
    "ForcedResponse",
    "energy_budget",
    "EnergyBudget",
    "simulate",
    "Simulation",
    "linear_coordinates",
    "EXPLICIT_METHODS",
    "IMPLICIT_METHODS",
    "modal_expansion",
    "ModalExpansion",
    "JordanBlock",
    "SampledForce",
    "INTERPOLATIONS",
    "first_order",
]
