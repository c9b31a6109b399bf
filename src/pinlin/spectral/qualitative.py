"""Qualitative properties of the spectrum (theory: stability, paper Sec. 11).

Per mode: for an eigenpair (lam, x) of a mechanical system scaled to
x^H M x = 1, the real numbers

.. math::
    m = x^H M x,\\; d = x^H D x,\\; g = -i\\, x^H G x,\\;
    k = x^H S x,\\; n = -i\\, x^H N x

satisfy m lam^2 + (d + i g) lam + (k + i n) = 0 (multiply L(lam) x = 0 by x^H).

Per system: the structural facts that decide stability without the spectrum
(definiteness of D and S, inertia of S, N = 0, signs of det M and det K) and
the theorems built on them; :mod:`pinlin.spectral.stability` applies them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..numerics.checks import check_uncertainty
from ..numerics.definiteness import (
    DEFAULT_UNCERTAINTY,
    DEFINITENESS_TOL,
    Definiteness,
    symmetric_definiteness,
)
from ..numerics.determinant import Nonsingularity, nonsingularity, validated_nonsingularity
from ..results import persistent
from .problem import QuadraticProblem

#: The smallest positive normal double.
_TINY = float(np.finfo(float).tiny)

__all__ = [
    "ModeConstants",
    "mode_constants",
    "quadratic_forms",
    "constants_from_quadratic_forms",
    "constants_of",
    "StructuralFacts",
    "structural_facts",
    "DEFAULT_UNCERTAINTY",
    "DEFINITENESS_TOL",
]


@persistent
@dataclass(frozen=True, kw_only=True)
class ModeConstants:
    """The real constants m, d, g, k, n of each mode (theory: stability), x^H M x = 1.

    Attributes
    ----------
    m, d, g, k, n : (2n,) float
        Modal mass (1), damping [1/s], gyroscopic [1/s], stiffness [1/s^2] and
        circulatory [1/s^2] constants.
    residual : (2n,) float
        |m lam^2 + (d + ig) lam + (k + in)| / (|lam|^2 m + |lam|(|d| + |g|) + |k| + |n|).
    """

    m: np.ndarray
    d: np.ndarray
    g: np.ndarray
    k: np.ndarray
    n: np.ndarray
    residual: np.ndarray

    def overdamped(self) -> np.ndarray:
        """d^2 > 4 m k per mode (meaningful with G = N = 0: real roots)."""
        return self.d**2 > 4 * self.m * self.k


def mode_constants(lam, X, MX, CX, KX) -> ModeConstants:
    """m, d, g, k, n from the right vectors and their products with M, C = D + G, K = S + N.

    The ratios do not change when M, C, K are divided by one number: pass the
    products of M / ||M||, C / ||M||, K / ||M|| when M is tiny or huge (x^H M x
    of a unit x must not underflow).

    x^H C x = d + i g and x^H K x = k + i n because x^H D x, x^H S x are real
    and x^H G x, x^H N x imaginary; the rounding parts of the wrong kind are
    dropped.
    """
    quad = np.einsum("ij,kij->kj", np.conj(X), np.stack([MX, CX, KX]))
    return constants_from_quadratic_forms(lam, quad)


def quadratic_forms(X, P) -> np.ndarray:
    """(3, k) x^H M x, x^H C x, x^H K x for the columns of X, given P = (M X, C X, K X) as a (3, n, k) array."""
    return np.einsum("ij,kij->kj", np.conj(X), P)


def constants_from_quadratic_forms(lam, quad) -> ModeConstants:
    """:class:`ModeConstants` from the (3, k) quadratic forms x^H M x, x^H C x, x^H K x (see mode_constants)."""
    m = quad[0].real
    c = quad[1] / m
    k = quad[2] / m
    d, g = c.real, c.imag
    kk, nn = k.real, k.imag
    one = np.ones_like(m)
    a = np.abs(lam)
    num = np.abs(lam * lam + (d + 1j * g) * lam + (kk + 1j * nn))
    den = a * a + a * (np.abs(d) + np.abs(g)) + np.abs(kk) + np.abs(nn)
    with np.errstate(divide="ignore", invalid="ignore"):
        res = np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)
    return ModeConstants(m=one, d=d, g=g, k=kk, n=nn, residual=res)


def constants_of(lam, X, quad, M, C, K, norm_M: float) -> ModeConstants:
    """:class:`ModeConstants` of the unit right vectors X from their quadratic forms ``quad`` (3, k).

    Where x^H M x underflows (a tiny M) the forms are taken again with M, C, K
    divided by ||M|| (the ratios are the same).
    """
    m = quad[0].real
    bad = ~(np.isfinite(m) & (m > _TINY))
    if np.any(bad):
        quad = quad.copy()
        Xb = X[:, bad]
        quad[:, bad] = quadratic_forms(Xb, np.stack([(A / norm_M) @ Xb for A in (M, C, K)]))
    return constants_from_quadratic_forms(lam, quad)


@persistent
@dataclass(frozen=True, kw_only=True)
class StructuralFacts:
    """What the matrices alone say about the spectrum (theory: stability).

    Every decision is made against the rounding bound of the data and the
    relative data ``uncertainty`` (:func:`pinlin.numerics.definiteness`): a
    definiteness or determinant sign is stated only when every system within
    that uncertainty shares it.

    Attributes
    ----------
    damping, stiffness : str or None
        Definiteness of D and S (one of :data:`pinlin.numerics.DEFINITENESS_KINDS`);
        None for tuple input (no mechanical split).
    negative_stiffness : int or None
        Number of eigenvalues of S certainly negative (None for tuple input).
    singular_stiffness : bool or None
        Some eigenvalue of S is within its threshold of zero (its sign undecided).
    gyroscopic, circulatory, damped : bool or None
        G != 0, N != 0, D != 0 (exactly).
    det_sign_M, det_sign_K : int
        Signs of det M and det K, 0 when the data do not decide them.  p(0) = det K
        and the leading coefficient of p(lam) = det L(lam) is det M.
    reflection_symmetric : bool
        D = 0 and (G = 0 or N = 0), exactly: then det L(-lam) = det L(lam), so with
        real coefficients the spectrum is symmetric under lam -> -lam and
        lam -> -conj(lam) (reflection in the imaginary axis).
    uncertainty : float
        The relative data uncertainty the decisions hold against.
    definiteness_D, definiteness_S, definiteness_M : Definiteness or None
        The decisions about D, S and M with their numbers (inertia, extreme
        eigenvalues, threshold, margin); None for tuple input.
    det_margin_M, det_margin_K : float
        Relative perturbations that keep det M and det K of their sign (0 when undecided).
    mass : str or None
        Definiteness of M ("positive_definite" unless M is so ill-conditioned that
        rounding could make it singular); None for tuple input.
    """

    damping: str | None
    stiffness: str | None
    negative_stiffness: int | None
    singular_stiffness: bool | None
    gyroscopic: bool | None
    circulatory: bool | None
    damped: bool | None
    det_sign_M: int
    det_sign_K: int
    reflection_symmetric: bool
    uncertainty: float
    definiteness_D: Definiteness | None = None
    definiteness_S: Definiteness | None = None
    definiteness_M: Definiteness | None = None
    det_margin_M: float = 0.0
    det_margin_K: float = 0.0

    # The determinant decisions, for :meth:`at` (attributes, not fields: never dumped or compared).
    _det_K = None
    _det_M = None

    @property
    def tol(self) -> float:
        """The name of pinlin 0.2 for :attr:`uncertainty` (pass it to :func:`pinlin.numerics.definiteness`)."""
        return self.uncertainty

    @property
    def mass(self) -> str | None:
        return None if self.definiteness_M is None else self.definiteness_M.kind

    def at(self, uncertainty: float) -> StructuralFacts:
        """The same facts decided against another data uncertainty (no new factorization)."""
        if self.definiteness_S is None:
            return _general(self._det_M.at(uncertainty), self._det_K.at(uncertainty))
        return _mechanical(
            self.definiteness_M.at(uncertainty), self.definiteness_D.at(uncertainty),
            self.definiteness_S.at(uncertainty), self.gyroscopic, self.circulatory, self.damped,
            None if self._det_K is None else self._det_K.at(uncertainty),
        )

    def describe(self) -> str:
        if self.damping is None:
            return f"general coefficients; sign det M = {self.det_sign_M:+d}, sign det K = {self.det_sign_K:+d}"
        parts = [
            f"D {self.damping.replace('_', ' ')}",
            f"S {self.stiffness.replace('_', ' ')} ({self.negative_stiffness} negative eigenvalue(s))",
            "G = 0" if not self.gyroscopic else "G != 0",
            "N = 0" if not self.circulatory else "N != 0",
        ]
        if self.mass != "positive_definite":
            parts.insert(0, f"M {self.mass.replace('_', ' ')} within rounding")
        return ", ".join(parts)


def _mechanical(on_M, on_D, on_S, gyro, circ, damped, det_K) -> StructuralFacts:
    sign_M = 1 if on_M.kind == "positive_definite" else 0
    if circ:
        sign_K, margin_K = det_K.sign, det_K.margin
    else:
        sign_K = 0 if on_S.zero else (-1) ** on_S.negative
        margin_K = on_S.margin
    symmetric = (not damped) and (not gyro or not circ)
    facts = StructuralFacts(
        damping=on_D.kind, stiffness=on_S.kind, negative_stiffness=on_S.negative,
        singular_stiffness=on_S.zero > 0, gyroscopic=gyro, circulatory=circ, damped=damped, det_sign_M=sign_M,
        det_sign_K=sign_K, reflection_symmetric=symmetric, uncertainty=on_S.uncertainty, definiteness_D=on_D,
        definiteness_S=on_S, definiteness_M=on_M, det_margin_M=on_M.margin, det_margin_K=margin_K,
    )
    object.__setattr__(facts, "_det_K", det_K)
    return facts


def _general(dM: Nonsingularity, dK: Nonsingularity) -> StructuralFacts:
    """The facts of a tuple (general coefficients): determinant signs only."""
    facts = StructuralFacts(
        damping=None, stiffness=None, negative_stiffness=None, singular_stiffness=None, gyroscopic=None,
        circulatory=None, damped=None, det_sign_M=dM.sign, det_sign_K=dK.sign, reflection_symmetric=False,
        uncertainty=dM.uncertainty, det_margin_M=dM.margin, det_margin_K=dK.margin,
    )
    object.__setattr__(facts, "_det_K", dK)
    object.__setattr__(facts, "_det_M", dM)
    return facts


def structural_facts(
    problem: QuadraticProblem, uncertainty: float = DEFAULT_UNCERTAINTY, mass: Definiteness | None = None
) -> StructuralFacts:
    """Definiteness, inertia and determinant signs of the coefficients (O(n^3), no spectrum).

    For a LinearizedSystem the definiteness of M, D and S comes from
    :func:`pinlin.numerics.definiteness` and, when N = 0, the sign of
    det K = det S from the inertia of S; otherwise determinant signs come from
    :func:`pinlin.numerics.nonsingularity` (one SVD).  All against the rounding
    bound and the relative data ``uncertainty``.

    ``mass``, when given, is the decision ``symmetric_definiteness(M, uncertainty)``
    already made (the symmetric paths need it to choose eigh or QZ): it is used
    as is instead of being made again.

    Raises
    ------
    ParameterError
        ``uncertainty`` not in [0, 1).
    """
    sys = problem.system
    if sys is None:
        return _general(nonsingularity(problem.M, uncertainty), nonsingularity(problem.K, uncertainty))
    u = check_uncertainty(uncertainty)
    zero = problem.zero
    circ = not zero["N"]
    det_K = validated_nonsingularity(sys.K, u) if circ else None  # K of a system: finite, real, square
    return _mechanical(
        symmetric_definiteness(sys.M, u) if mass is None else mass,
        symmetric_definiteness(sys.D, u),
        symmetric_definiteness(sys.S, u),
        not zero["G"], circ, not zero["D"], det_K,
    )
