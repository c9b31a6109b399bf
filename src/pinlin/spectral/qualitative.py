"""Qualitative properties of the spectrum (SPEC section 5, paper Sec. 11).

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
import scipy.linalg as sla

from .problem import QuadraticProblem

__all__ = ["ModeConstants", "mode_constants", "StructuralFacts", "structural_facts", "DEFINITENESS_TOL"]

#: Default relative tolerance of the definiteness and singularity tests: an
#: eigenvalue of a symmetric matrix A with |w| <= tol ||A||_2 counts as zero.
DEFINITENESS_TOL = 1e-10


@dataclass(frozen=True)
class ModeConstants:
    """The real constants m, d, g, k, n of each mode (SPEC section 5), x^H M x = 1.

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

    x^H C x = d + i g and x^H K x = k + i n because x^H D x, x^H S x are real
    and x^H G x, x^H N x imaginary; the rounding parts of the wrong kind are
    dropped.
    """
    m = np.einsum("ij,ij->j", X.conj(), MX).real
    c = np.einsum("ij,ij->j", X.conj(), CX) / m
    k = np.einsum("ij,ij->j", X.conj(), KX) / m
    d, g = c.real, c.imag
    kk, nn = k.real, k.imag
    one = np.ones_like(m)
    a = np.abs(lam)
    num = np.abs(lam * lam + (d + 1j * g) * lam + (kk + 1j * nn))
    den = a * a + a * (np.abs(d) + np.abs(g)) + np.abs(kk) + np.abs(nn)
    with np.errstate(divide="ignore", invalid="ignore"):
        res = np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)
    return ModeConstants(one, d, g, kk, nn, res)


def _definiteness(A: np.ndarray, tol: float) -> tuple[str, int, int, float]:
    """("zero" | "positive_definite" | "positive_semidefinite" | "negative_definite" |
    "negative_semidefinite" | "indefinite", #negative, #zero, smallest eigenvalue)."""
    if not np.any(A):
        return "zero", 0, A.shape[0], 0.0
    w = np.linalg.eigvalsh(A)
    thr = tol * np.max(np.abs(w))
    neg = int(np.sum(w < -thr))
    zero = int(np.sum(np.abs(w) <= thr))
    pos = A.shape[0] - neg - zero
    if neg == 0 and zero == 0:
        kind = "positive_definite"
    elif neg == 0:
        kind = "positive_semidefinite"
    elif pos == 0 and zero == 0:
        kind = "negative_definite"
    elif pos == 0:
        kind = "negative_semidefinite"
    else:
        kind = "indefinite"
    return kind, neg, zero, float(w[0])


def _det_sign(A: np.ndarray, tol: float) -> int:
    """Sign of det A from an LU factorization, or 0 when A is singular to tol.

    Singular means LAPACK's reciprocal 1-norm condition estimate (``dgecon``)
    is at most tol.
    """
    lu, piv, info = sla.lapack.dgetrf(A)
    d = np.diag(lu)
    if info != 0 or np.any(d == 0):
        return 0
    rcond, info = sla.lapack.dgecon(lu, float(np.linalg.norm(A, 1)), norm="1")
    if info != 0 or rcond <= tol:
        return 0
    swaps = int(np.sum(piv != np.arange(piv.shape[0])))
    return int(np.prod(np.sign(d)) * (-1) ** swaps)


@dataclass(frozen=True)
class StructuralFacts:
    """What the matrices alone say about the spectrum (SPEC section 5).

    Attributes
    ----------
    damping, stiffness : str or None
        Definiteness of D and S ("zero", "positive_definite",
        "positive_semidefinite", "negative_definite", "negative_semidefinite",
        "indefinite"); None for tuple input (no mechanical split).
    negative_stiffness : int or None
        Number of negative eigenvalues of S (None for tuple input).
    singular_stiffness : bool or None
        S has an eigenvalue within tol ||S|| of zero.
    gyroscopic, circulatory, damped : bool or None
        G != 0, N != 0, D != 0 (exactly).
    det_sign_M, det_sign_K : int
        Signs of det M and det K (0: singular to tol).  p(0) = det K and the
        leading coefficient of p(lam) = det L(lam) is det M.
    reflection_symmetric : bool
        D = 0 and (G = 0 or N = 0): then det L(-lam) = det L(lam), so with real
        coefficients the spectrum is symmetric under lam -> -lam and
        lam -> -conj(lam) (reflection in the imaginary axis).
    tol : float
        The relative tolerance of the definiteness and singularity tests.
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
    tol: float

    def describe(self) -> str:
        if self.damping is None:
            return f"general coefficients; sign det M = {self.det_sign_M:+d}, sign det K = {self.det_sign_K:+d}"
        parts = [
            f"D {self.damping.replace('_', ' ')}",
            f"S {self.stiffness.replace('_', ' ')} ({self.negative_stiffness} negative eigenvalue(s))",
            "G = 0" if not self.gyroscopic else "G != 0",
            "N = 0" if not self.circulatory else "N != 0",
        ]
        return ", ".join(parts)


def structural_facts(problem: QuadraticProblem, tol: float = DEFINITENESS_TOL) -> StructuralFacts:
    """Definiteness, inertia and determinant signs of the coefficients (O(n^3), no spectrum).

    For a LinearizedSystem, det M > 0 (M is positive definite by construction)
    and, when N = 0, the sign of det K = det S follows from the inertia of S;
    otherwise determinant signs come from LU factorizations with a condition
    estimate (``tol`` on the reciprocal condition number).
    """
    sys = problem.system
    if sys is None:
        sign_M = _det_sign(problem.M, tol)
        sign_K = _det_sign(problem.K, tol)
        return StructuralFacts(None, None, None, None, None, None, None, sign_M, sign_K, False, tol)
    damping, *_ = _definiteness(sys.D, tol)
    stiffness, neg, zero, _ = _definiteness(sys.S, tol)
    gyro, circ, damped = not sys.is_zero("G"), not sys.is_zero("N"), not sys.is_zero("D")
    if circ:
        sign_K = _det_sign(sys.K, tol)
    else:
        sign_K = 0 if zero else (-1) ** neg
    symmetric = (not damped) and (not gyro or not circ)
    return StructuralFacts(damping, stiffness, neg, zero > 0, gyro, circ, damped, 1, sign_K, symmetric, tol)
