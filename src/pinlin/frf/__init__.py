"""Frequency response functions: the dynamic flexibility H(s) = L(s)^-1 = adj L(s) / p(s) and the responses built on it (SPEC section 4, 6).

One concept per module:

- :mod:`.engine` -- H(s) direct (LU of L(s)) and modal (eigenpairs and Jordan
  blocks), with the residual of L(s) H(s) = I;
- :mod:`.frequency` -- :func:`frequency_response`: H(i omega) over a frequency grid;
- :mod:`.harmonic` -- :func:`harmonic_response`: the steady amplitude H(i omega) F;
- :mod:`.residues` -- principal parts of H at a root of any multiplicity, by contour
  integrals (paper Sec. 10, Theorem 10.2).
"""

from .engine import FlexibilityArray, flexibility, modal_adjugate
from .frequency import FrequencyResponse, frequency_response
from .harmonic import HARMONIC_METHODS, HarmonicResponse, harmonic_response
from .residues import Residues, principal_part_residual, residues

__all__ = [
    "FlexibilityArray",
    "flexibility",
    "modal_adjugate",
    "FrequencyResponse",
    "frequency_response",
    "HarmonicResponse",
    "harmonic_response",
    "HARMONIC_METHODS",
    "Residues",
    "residues",
    "principal_part_residual",
]
