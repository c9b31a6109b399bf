"""The adjoint module: characteristic polynomial, adjugate, flexibility, residues (SPEC section 4).

Paper Sec. 6-10 and 12, in the order of the data flow:

- :mod:`.polynomial`: ``p(lam) = det L(lam)`` with coefficient error bounds.
- :mod:`.adjugate`: ``adj L(lam)`` (SVD form, stable at eigenvalues), as a
  matrix polynomial of degree 2n - 2 and its derivatives at a point.
- :mod:`.eigenvectors`: eigenvectors, ``p'(lam_k)`` and Jordan chains read
  off the adjugate (Sec. 8, 9).
- :mod:`.cde`: the characteristic differential equation ``p(d/dt) x_i = 0`` (Sec. 7).
- :mod:`.flexibility`: ``H(s) = L(s)^-1`` direct and modal; the spectral form
  of the adjugate (Sec. 10).
- :mod:`.residues`: principal parts of H at roots of any multiplicity by
  contour integrals (Sec. 10, Theorem 10.2).
- :mod:`.response`: frequency responses ``H(i omega)`` (Sec. 12).
"""

from .adjugate import (
    AdjugateMatrix,
    AdjugatePolynomial,
    AdjugateTaylor,
    adjugate,
    adjugate_polynomial,
    adjugate_residual,
    adjugate_taylor,
)
from .cde import (
    CDECheck,
    CharacteristicDifferentialEquation,
    characteristic_differential_equation,
    check_free_response,
)
from .eigenvectors import (
    AdjugateChain,
    AdjugateEigenvectors,
    adjugate_chain,
    adjugate_eigenvectors,
    chain_residual,
)
from .flexibility import FlexibilityArray, flexibility, modal_adjugate
from .polynomial import CharacteristicPolynomial, characteristic_polynomial
from .residues import Residues, principal_part_residual, residues
from .response import FrequencyResponse, frequency_response

__all__ = [
    "CharacteristicPolynomial",
    "characteristic_polynomial",
    "AdjugateMatrix",
    "adjugate",
    "adjugate_residual",
    "AdjugatePolynomial",
    "adjugate_polynomial",
    "AdjugateTaylor",
    "adjugate_taylor",
    "AdjugateEigenvectors",
    "adjugate_eigenvectors",
    "AdjugateChain",
    "adjugate_chain",
    "chain_residual",
    "CharacteristicDifferentialEquation",
    "characteristic_differential_equation",
    "CDECheck",
    "check_free_response",
    "FlexibilityArray",
    "flexibility",
    "modal_adjugate",
    "Residues",
    "residues",
    "principal_part_residual",
    "FrequencyResponse",
    "frequency_response",
]
