"""The adjoint module: characteristic polynomial, adjugate, eigenvectors from the adjugate (theory: adjoint).

Paper Sec. 6-10 and 12, in the order of the data flow:

- :mod:`._circle`: polynomial coefficients from samples on circles (FFT), each
  from the circle where its error bound is smallest (used by the next three).
- :mod:`.polynomial`: ``p(lam) = det L(lam)`` with coefficient error bounds.
- :mod:`.svd`: the SVD form of the adjugate in logarithms (stable at eigenvalues).
- :mod:`.adjugate`: ``adj L(lam)`` at a point, with its residual.
- :mod:`.adjugate_series`: ``adj L`` as a matrix polynomial of degree 2n - 2 and
  its Taylor coefficients at a point.
- :mod:`.eigenvectors`: eigenvectors, ``p'(lam_k)`` and Jordan chains read
  off the adjugate (Sec. 8, 9).
- :mod:`.cde`: the characteristic differential equation ``p(d/dt) x_i = 0`` (Sec. 7).

The dynamic flexibility ``H(s) = adj L(s) / p(s)``, its residues and the frequency
responses built on it live in :mod:`pinlin.frf`.
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
from .polynomial import CharacteristicPolynomial, characteristic_polynomial

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
]

