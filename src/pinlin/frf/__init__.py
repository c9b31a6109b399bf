"""Frequency response functions: H(s) = L(s)^-1 = adj L(s) / p(s) and the responses built on it (theory: flexibility, responses).

One concept per module:

- :mod:`.engine` -- the one engine for X(s) = H(s) B: "direct" (the default: LU
  of L(s) per point, or for many points one Schur form and triangular solves) or
  "modal" (eigenpairs and Jordan blocks), the relative defect per point, one
  behaviour at a pole;
- :mod:`.schur` -- the direct method for many points: generalized real Schur form
  of the scaled companion pencil, quasi-triangular solves (Laub 1981 in pencil form);
- :mod:`.modal` -- the modal method's evaluation and its check (exact at sampled
  points, a closed-form bound at the others);
- :mod:`.measures` -- ||L(s)|| without forming L(s), and the residual ||L(s) X - B||;
- :mod:`.expansion` -- the modal expansion (eigenvectors and Jordan chains in
  first-order form) that the modal method and the free response evaluate;
- :mod:`.flexibility` -- :func:`flexibility`: H(s) on any points; the spectral
  form of the adjugate;
- :mod:`.frequency` -- :func:`frequency_response`: H(i omega) between chosen
  inputs and outputs, python-control's axis order;
- :mod:`.harmonic` -- :func:`harmonic_response`: the steady amplitude H(i omega) F;
- :mod:`.residues` -- principal parts of H at a root of any multiplicity, by contour
  integrals of H from the engine (paper Sec. 10, Theorem 10.2); :mod:`.contour` finds
  and samples the contour (argument-principle counts);
- :mod:`._inputs` -- the check of angular frequencies.

Axis orders: stacks put the points first (``flexibility``: (len(s), n, n);
``harmonic_response``: (len(omega), n), like a time response (len(t), n));
``FrequencyResponse.response`` follows python-control, (outputs, inputs,
frequencies).  Per-point figures (``defects``, ``distance``) are 1-D over the
points (scalars for a scalar point).
"""

from .engine import DEFAULT_METHOD, METHODS
from .expansion import JordanBlock, ModalExpansion, modal_expansion
from .flexibility import FlexibilityArray, flexibility, modal_adjugate
from .frequency import FrequencyResponse, frequency_response
from .harmonic import HARMONIC_METHODS, HarmonicResponse, harmonic_response
from .residues import Residues, principal_part_residual, residues

__all__ = [
    "METHODS",
    "DEFAULT_METHOD",
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
    "ModalExpansion",
    "JordanBlock",
    "modal_expansion",
]
