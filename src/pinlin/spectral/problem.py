"""The quadratic eigenvalue problem behind a modal analysis (theory: spectrum).

.. math::  L(\\lambda) x = (\\lambda^2 M + \\lambda C + K) x = 0,
           \\qquad y^T L(\\lambda) = 0

A :class:`QuadraticProblem` holds the three real coefficient matrices, their
Frobenius norms (the weights of the backward error and of the condition
number), and the Fan-Lin-Van Dooren scaling.  It is built either from a
:class:`~pinlin.LinearizedSystem` (M symmetric positive definite, C = D + G,
K = S + N) or from a tuple ``(M, C, K)`` of general real square matrices with M
nonsingular, which need not be mechanical at all.

Two rules, on purpose: a LinearizedSystem is a mechanical system,
and its constructor and :meth:`~pinlin.LinearizedSystem.from_matrices` refuse
an M that is not symmetric positive definite; a tuple is the general quadratic
eigenvalue problem of theory: spectrum ("any nonsingular leading" coefficient,
such as the check problem of the theory pages (theory: spectrum) with a non-symmetric A2), solved by the
general path with no theorem of theory: stability applied.  Both refuse complex,
non-finite and non-square input with the same messages.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError, ParameterError, SingularMassError
from ..linearization.system import LinearizedSystem
from ..numerics.accuracy import eigen_weight
from ..numerics.arrays import readonly
from ..numerics.checks import check_tolerance
from ..numerics.norms import coefficient_norms
from ..numerics.scaling import Scaling, fan_lin_van_dooren

__all__ = ["QuadraticProblem", "Scaling", "fan_lin_van_dooren", "as_problem", "SINGULAR_MASS_RCOND"]

#: The smallest positive normal double: a scaled coefficient below it has lost its digits.
TINY = float(np.finfo(float).tiny)

#: Default: a tuple's M counts as singular when its reciprocal 2-norm condition
#: number is below this (n eps is where LU loses every digit).
SINGULAR_MASS_RCOND = 1e-14


@dataclass(frozen=True, eq=False)
class QuadraticProblem:
    """Real coefficients of L(lam) = lam^2 M + lam C + K and what the solvers need of them.

    Attributes
    ----------
    M, C, K : (n, n) ndarray
        Read-only real coefficients.
    system : LinearizedSystem or None
        The mechanical system when built from one; None for a plain tuple.
    norm_M, norm_C, norm_K : float
        Frobenius norms: the weights of eta and kappa (theory: spectrum).
    scaling : Scaling
        Fan-Lin-Van Dooren parameters for these norms.
    """

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    system: LinearizedSystem | None
    norm_M: float
    norm_C: float
    norm_K: float
    scaling: Scaling

    @property
    def n(self) -> int:
        return self.M.shape[0]

    @functools.cached_property
    def zero(self) -> dict[str, bool]:
        """Which of D, G, N (a LinearizedSystem's) are exactly zero, decided once; empty for a tuple."""
        sys = self.system
        if sys is None:
            return {}
        return {name: not np.count_nonzero(getattr(sys, name)) for name in ("D", "G", "N")}

    @functools.cached_property
    def symmetric(self) -> bool:
        """M, C and K exactly symmetric: L(lam)^T = L(lam), so left eigenvectors are right ones."""
        if self.system is not None:  # M, D, S are symmetric by construction; G and N are exactly zero or not
            return self.zero["G"] and self.zero["N"]
        return all(np.array_equal(X, X.T) for X in (self.M, self.C, self.K))

    @functools.cached_property
    def stacked(self) -> np.ndarray:
        """(3n, n) the coefficients M, C, K one above the other (one product gives M V, C V, K V)."""
        return np.concatenate([self.M, self.C, self.K])

    @property
    def mechanical(self) -> bool:
        """True when built from a LinearizedSystem (M spd, D, S symmetric, G, N skew)."""
        return self.system is not None

    def factors(self, scaling: Scaling | None = None) -> tuple[float, float, float] | None:
        """(gamma^2 delta, gamma delta, delta), or None when a scaled coefficient is out of double range.

        Out of range: a factor, or a factor times its coefficient's norm, over- or underflows
        (a nonzero coefficient would become inf or 0).
        """
        if scaling is None or scaling is self.scaling:
            return self._own_factors
        return self._factors_of(scaling)

    @functools.cached_property
    def _own_factors(self) -> tuple[float, float, float] | None:
        """:meth:`factors` of the problem's own scaling, formed once."""
        return self._factors_of(self.scaling)

    def _factors_of(self, s: Scaling) -> tuple[float, float, float] | None:
        # Python floats: a product that overflows is inf and one that underflows 0, without warnings
        g, d = float(s.gamma), float(s.delta)
        factors = (g * g * d, g * d, d)
        for f, norm in zip(factors, self.norms):
            size = f * norm
            if not math.isfinite(f) or f == 0 or (norm > 0 and not (math.isfinite(size) and size > TINY)):
                return None
        return factors

    def scaled(self, scaling: Scaling | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(M_s, C_s, K_s) = (gamma^2 delta M, gamma delta C, delta K).

        Raises
        ------
        ComputationError
            A scaled coefficient is out of double range (see :meth:`factors`).
        """
        f = self.factors(scaling)
        if f is None:
            s = self.scaling if scaling is None else scaling
            raise ComputationError(
                f"the scaling gamma = {s.gamma:.3g}, delta = {s.delta:.3g} takes the coefficients (norms "
                f"{self.norm_M:.3g}, {self.norm_C:.3g}, {self.norm_K:.3g}) out of double range; rescale the system"
            )
        return f[0] * self.M, f[1] * self.C, f[2] * self.K

    @property
    def norms(self) -> tuple[float, float, float]:
        """(||M||, ||C||, ||K||), Frobenius."""
        return self.norm_M, self.norm_C, self.norm_K

    def weight(self, lam) -> np.ndarray:
        """|lam|^2 ||M|| + |lam| ||C|| + ||K||: the scale of L(lam) in the backward error."""
        return eigen_weight(lam, self.norms)


def _matrix(name: str, value, n: int | None) -> np.ndarray:
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):  # a ragged nested list
        raise ParameterError(name, "expected a real matrix of numbers (rectangular)") from None
    if np.iscomplexobj(a):
        raise ParameterError(name, "expected a real matrix, got complex entries")
    try:
        a = np.array(a, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, "expected a real matrix of numbers") from None
    if a.ndim != 2 or a.shape[0] != a.shape[1]:
        raise ParameterError(name, f"expected a square matrix, got shape {a.shape}")
    if a.shape[0] == 0:
        raise ParameterError(name, "expected at least one coordinate, got shape (0, 0)")
    if n is not None and a.shape != (n, n):
        raise ParameterError(name, f"expected shape {(n, n)} like M, got {a.shape}")
    if not np.all(np.isfinite(a)):
        bad = tuple(int(i) for i in np.argwhere(~np.isfinite(a))[0])
        raise ParameterError(name, f"has non-finite entries (first at index {bad})")
    return a


def as_problem(source, *, mass_rcond: float = SINGULAR_MASS_RCOND) -> QuadraticProblem:
    """Turn a LinearizedSystem or a tuple (M, C, K) into a :class:`QuadraticProblem`.

    Parameters
    ----------
    source : LinearizedSystem or tuple (M, C, K)
        A tuple holds general real square matrices of one size; M must be
        nonsingular (it need not be symmetric).
    mass_rcond : float
        A tuple's M is refused as singular when sigma_min / sigma_max of M is
        below this value.

    Raises
    ------
    ParameterError
        Not a system or a 3-tuple; matrices not real, square, of one shape or finite.
    SingularMassError
        M of a tuple is (numerically) singular.
    """
    if isinstance(source, LinearizedSystem):
        M, C, K, system = source.M, source.C, source.K, source
    elif isinstance(source, (tuple, list)):
        if len(source) != 3:
            raise ParameterError("sys", f"expected a LinearizedSystem or a tuple (M, C, K), got {len(source)} items")
        M = _matrix("M", source[0], None)
        C = _matrix("C", source[1], M.shape[0])
        K = _matrix("K", source[2], M.shape[0])
        rcond = check_tolerance(mass_rcond, "mass_rcond", upper=1.0)
        sv = np.linalg.svd(M, compute_uv=False)
        if sv[-1] <= rcond * sv[0]:
            raise SingularMassError(
                f"M is singular: sigma_min/sigma_max = {sv[-1] / sv[0] if sv[0] else 0.0:.3g} <= mass_rcond "
                f"{rcond:g}; the quadratic eigenproblem then has infinite eigenvalues, which pinlin does not treat",
                (),
            )
        M, C, K, system = readonly(M, float), readonly(C, float), readonly(K, float), None
    else:
        raise ParameterError(
            "sys", f"expected a LinearizedSystem or a tuple (M, C, K) of arrays, got {type(source).__name__}"
        )
    norms = coefficient_norms(M, C, K)
    return QuadraticProblem(M, C, K, system, *norms, fan_lin_van_dooren(*norms))
