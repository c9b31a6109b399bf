"""Definiteness, inertia and determinant signs decided against the rounding bound of the data (theory: stability).

Determinant signs are in :mod:`pinlin.numerics.determinant` (``det_sign`` is
re-exported here, its home in pinlin 0.2).

One decision for every user: ``modes.structure``, the stability theorems and
the command-line report all call :func:`definiteness`, so they cannot
disagree.  The decision says what the floating-point data prove, not what a
fixed eigenvalue ratio suggests:

* LAPACK's symmetric eigensolver behind ``eigvalsh`` is backward stable: the
  computed eigenvalues w_i are the exact eigenvalues of A + E with
  ||E||_2 <= rho = c n eps ||A||_2 (:data:`EIGENVALUE_ROUNDING` is c).  By Weyl's
  theorem each exact eigenvalue lies within rho of w_i.
* A user may also state a relative uncertainty u of the data: the decision
  then holds for every symmetric A + F with ||F||_2 <= u ||A||_2.

.. math::
    w_i > \\rho + u\\|A\\|_2 \\Rightarrow \\lambda_i > 0, \\qquad
    w_i < -(\\rho + u\\|A\\|_2) \\Rightarrow \\lambda_i < 0, \\qquad
    \\text{otherwise undecided}

Where the eigenvalue test leaves positive definiteness undecided, a Cholesky
factorization A + Delta A = R^T R with Higham's componentwise backward error
bound |Delta A| <= gamma_{k+1} |R^T| |R| (Accuracy and Stability of Numerical
Algorithms, 2nd ed., Thm 10.3; k the longest inner product of nonzeros, so
banded matrices such as spring chains get small k) may still certify it:
lambda_min(A) >= sigma_min(R)^2 - gamma_{k+1} || |R^T| |R| ||_2.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla
from scipy.linalg.lapack import dsyevd as _dsyevd

from ..errors import ParameterError
from ..results import persistent, to_jsonable
from .checks import check_uncertainty
from .floating import EPS

__all__ = [
    "EIGENVALUE_ROUNDING",
    "DEFAULT_UNCERTAINTY",
    "DEFINITENESS_TOL",
    "DEFINITENESS_KINDS",
    "Definiteness",
    "definiteness",
    "symmetric_definiteness",
    "rounding_bound",
    "cholesky_lower_bound",
    "square_matrix",
]

#: c of the rounding bound rho = c n eps ||A||_2 of a symmetric eigenvalue (or singular
#: value) computation.  LAPACK's symmetric eigensolvers and SVD are backward stable
#: with ||E||_2 <= p(n) u ||A||_2 (u = eps / 2), p(n) a modest function of n that the
#: LAPACK Users' Guide (section 4.7) takes as 1, "usually a pessimistic upper bound";
#: c = 1 allows p(n) = 2n.  Measured on spring chains (stiffness ratios up to 1e14) and
#: random matrices of condition up to 1e14 against mpmath: errors up to 0.4 n eps ||A||_2.
EIGENVALUE_ROUNDING = 1.0

#: Default relative uncertainty of the data beyond their rounding: 0, the matrices
#: are taken as stored (the rounding bound rho is always added).
DEFAULT_UNCERTAINTY = 0.0

#: The name of pinlin 0.2 for the default of the definiteness decision (then a
#: relative eigenvalue ratio, now the data uncertainty added to the rounding bound).
DEFINITENESS_TOL = DEFAULT_UNCERTAINTY

#: The possible decisions, see :class:`Definiteness`.
DEFINITENESS_KINDS = (
    "zero",
    "positive_definite",
    "positive_semidefinite",
    "negative_definite",
    "negative_semidefinite",
    "indefinite",
)

#: Unit roundoff.
_U = EPS / 2


def rounding_bound(n: int, norm: float, factor: float = EIGENVALUE_ROUNDING) -> float:
    """rho = c n eps ||A||_2: how far rounding may move an eigenvalue of a symmetric (n, n) A."""
    return float(factor * n * EPS * norm)


@persistent
@dataclass(frozen=True, kw_only=True)
class Definiteness:
    """The definiteness of a symmetric matrix and the numbers behind the decision.

    Attributes
    ----------
    kind : str
        One of :data:`DEFINITENESS_KINDS`.  "positive_definite" is proven (every
        eigenvalue certainly positive); "positive_semidefinite" means no
        eigenvalue is certainly negative and some are within the threshold of
        zero (zero, or of either sign: the data do not decide); likewise for
        the negative kinds; "indefinite" has eigenvalues certainly of both signs.
    negative, zero, positive : int
        Inertia: eigenvalues certainly negative, undecided (within the
        threshold of zero), certainly positive.
    min_eigenvalue, max_eigenvalue : float
        Extreme computed eigenvalues (unit of the matrix); 0 for the zero matrix.
    tol : float
        The relative threshold: ``rounding + uncertainty``.
    threshold : float
        ``tol * norm``: eigenvalues within it of zero are undecided.
    norm : float
        ||A||_2 (the largest |eigenvalue|).
    rounding : float
        c n eps (:data:`EIGENVALUE_ROUNDING`): the relative rounding bound.
    uncertainty : float
        The relative data uncertainty the decision holds against.
    margin : float
        The largest relative perturbation ||F||_2 / ||A||_2 of the data that keeps
        the inertia (hence the kind): for a decided (nonsingular) inertia
        ``(min|lambda| - rho) / ||A||_2`` with the certified bounds, else 0.
        The kind is decided when margin > uncertainty.
    certificate : str
        What decided: "eigenvalues" (Weyl), "Cholesky" (Higham's backward error
        bound), or "exactly zero".
    certainly_psd : bool
        A is certainly positive semidefinite: exactly zero, positive definite, or
        positive definite on the coordinates where it is not exactly zero (rows
        and columns that are exactly zero, such as joints without a damper, are
        taken as exact: perturbations keep them zero).  A "positive_semidefinite"
        kind alone does not prove it (its undecided eigenvalues may be negative).
    """

    kind: str
    negative: int
    zero: int
    positive: int
    min_eigenvalue: float
    max_eigenvalue: float
    tol: float
    threshold: float
    norm: float = 0.0
    rounding: float = 0.0
    uncertainty: float = DEFAULT_UNCERTAINTY
    margin: float = 0.0
    certificate: str = "eigenvalues"
    certainly_psd: bool = False

    # What :meth:`at` needs to decide again (attributes, not fields: never dumped or compared):
    # the computed eigenvalues, the Cholesky lower bound, the decision on the nonzero block.
    _eigenvalues = None
    _cholesky_lower = None
    _block = None

    @property
    def singular(self) -> bool:
        """Some eigenvalue is undecided (within the threshold of zero)."""
        return self.zero > 0

    @property
    def decided(self) -> bool:
        """Every eigenvalue's sign is certain (the inertia holds within the uncertainty)."""
        return self.zero == 0

    def at(self, uncertainty: float) -> Definiteness:
        """The same decision against another relative data uncertainty (no new factorization).

        Raises
        ------
        ParameterError
            ``uncertainty`` not in [0, 1), or this decision was read back by :func:`pinlin.load`
            (which keeps the decision, not the eigenvalues it was made from).
        """
        u = check_uncertainty(uncertainty)
        if self._eigenvalues is None and self.norm != 0:  # read back by pinlin.load: no eigenvalues kept
            raise ParameterError("uncertainty", "this decision was read back from its data (pinlin.load), which "
                                 "keeps no eigenvalues to decide again: call definiteness() on the matrix")
        if self._eigenvalues is None:  # the zero matrix
            return replace(self, uncertainty=u, tol=self.rounding + u)  # nothing attached to carry over
        out = _decide(self._eigenvalues, self.norm, self.rounding, u, self._cholesky_lower)
        return _with_block(out, None if self._block is None else self._block.at(u))

    def to_dict(self) -> dict:
        """Plain JSON-serializable data (the fields)."""
        return to_jsonable({name: getattr(self, name) for name in self.__dataclass_fields__})

    def __str__(self) -> str:
        return (
            f"{self.kind.replace('_', ' ')} (inertia -{self.negative}/0:{self.zero}/+{self.positive}, "
            f"eigenvalues in [{self.min_eigenvalue:.3g}, {self.max_eigenvalue:.3g}], undecided within "
            f"{self.threshold:.2g}, margin {self.margin:.2g}, by {self.certificate})"
        )


def _kind(neg: int, zero: int, pos: int) -> str:
    if neg == 0 and zero == 0:
        return "positive_definite"
    if neg == 0:
        return "positive_semidefinite"
    if pos == 0 and zero == 0:
        return "negative_definite"
    if pos == 0:
        return "negative_semidefinite"
    return "indefinite"


def _decide(w: np.ndarray, norm: float, rounding: float, u: float, chol: float | None) -> Definiteness:
    """The decision from the computed eigenvalues w (ascending) and the Cholesky lower bound."""
    n = w.shape[0]
    rho = rounding * norm
    thr = rho + u * norm
    lo, hi = float(w[0]), float(w[-1])
    # w ascending: all beyond the threshold on one side when its first (last) member is
    if lo > thr:
        neg, pos = 0, n
    elif hi < -thr:
        neg, pos = n, 0
    else:
        neg = int(np.count_nonzero(w < -thr)) if lo < -thr else 0
        pos = int(np.count_nonzero(w > thr)) if hi > thr else 0
    zero = n - neg - pos
    certificate = "eigenvalues"
    # certified lower bound on min |lambda| when the inertia is decided, from the eigenvalues
    smallest = lo if lo >= 0 else (-hi if hi <= 0 else float(np.abs(w).min()))
    gap = smallest - rho
    if chol is not None and neg == 0 and chol > lo - rho:
        gap = chol
        if zero and chol > u * norm:
            pos, zero, certificate = n, 0, "Cholesky"
    margin = max(gap / norm, 0.0) if zero == 0 else 0.0
    out = Definiteness(
        kind=_kind(neg, zero, pos), negative=neg, zero=zero, positive=pos, min_eigenvalue=lo,
        max_eigenvalue=hi, tol=rounding + u, threshold=thr, norm=norm, rounding=rounding, uncertainty=u,
        margin=margin, certificate=certificate,
    )
    object.__setattr__(out, "_eigenvalues", w)
    object.__setattr__(out, "_cholesky_lower", chol)
    return out


def square_matrix(A) -> np.ndarray:
    """A as a float (n, n) array.

    Raises
    ------
    ParameterError
        Complex, not square, empty or non-finite.
    """
    if np.iscomplexobj(A):
        raise ParameterError("A", "expected a real matrix, got complex entries")
    A = np.asarray(A, dtype=float)
    if A.ndim != 2 or A.shape[0] != A.shape[1] or A.shape[0] == 0:
        raise ParameterError("A", f"expected a square matrix, got shape {A.shape}")
    if not np.all(np.isfinite(A)):
        raise ParameterError("A", "has non-finite entries")
    return A


def _factor_bound(R: np.ndarray, B: np.ndarray, gamma: float, factor: float) -> float:
    """(sigma_min(R) - c n eps sigma_max(R))^2 - gamma ||B||_2 (-inf when the first term vanishes)."""
    n = R.shape[0]
    s = np.linalg.svd(R, compute_uv=False)
    smin = float(s[-1] - factor * n * EPS * s[0])
    if smin <= 0:
        return -np.inf
    return smin * smin - gamma * float(np.linalg.norm(B, 2)) * (1 + n * EPS)


def cholesky_lower_bound(A: np.ndarray, factor: float = EIGENVALUE_ROUNDING) -> float | None:
    """A certified lower bound on lambda_min(A) from a Cholesky factorization, or None if it fails.

    .. math::
        A + \\Delta A = R^T R,\\quad |\\Delta A| \\le \\gamma_{k+1} |R^T| |R|
        \\;\\Rightarrow\\;
        \\lambda_{\\min}(A) \\ge \\bigl(\\hat\\sigma_{\\min}(R) - c\\,n\\,\\epsilon\\,\\hat\\sigma_{\\max}(R)\\bigr)^2
        - \\gamma_{k+1} \\| |R^T| |R| \\|_2

    with k the largest number of nonzeros in a column of R (the longest inner
    product with rounding; a product with an exact zero is exact) and
    gamma_m = m u / (1 - m u).  The singular values of R carry the same
    rounding bound as eigenvalues.  The same bound for the diagonally scaled
    matrix H = S A S, S = diag(a_ii)^(-1/2) (factor R S, Sylvester: H > 0 iff
    A > 0), times min a_ii (lambda_min(A) >= lambda_min(H) min a_ii), is also
    taken, and the larger of the two returned: it certifies matrices such as the mass
    matrix of a chain with a near-massless link, positive definite far beyond
    rounding relative to their diagonal but not to their norm.  Barring underflow.
    """
    d = np.diag(A)
    if np.any(d <= 0):
        return None
    try:
        R = sla.cholesky(A, lower=False, check_finite=False)
    except (np.linalg.LinAlgError, sla.LinAlgError):
        return None
    if not np.all(np.isfinite(R)):
        return None
    k = int(np.max(np.count_nonzero(R, axis=0)))
    gamma = (k + 1) * _U / (1 - (k + 1) * _U)
    absR = np.abs(R)
    B = absR.T @ absR  # nonnegative: its norm is computed to a relative n eps, covered by (1 + n eps)
    plain = _factor_bound(R, B, gamma, factor)
    w = 1.0 / np.sqrt(d)
    scaled = _factor_bound(R * w, B * w[:, None] * w[None, :], gamma, factor) * float(np.min(d))
    best = max(plain, scaled)
    return best if np.isfinite(best) else None


def definiteness(
    A, uncertainty: float = DEFAULT_UNCERTAINTY, *, rounding_factor: float = EIGENVALUE_ROUNDING
) -> Definiteness:
    """Definiteness and inertia of the symmetric matrix A, decided against rounding and a data uncertainty.

    .. math::
        \\rho = c\\,n\\,\\epsilon\\,\\|A\\|_2, \\qquad
        w_i > \\rho + u\\|A\\|_2 \\Rightarrow \\lambda_i > 0, \\qquad
        w_i < -(\\rho + u\\|A\\|_2) \\Rightarrow \\lambda_i < 0

    with w the eigenvalues computed by ``eigvalsh`` (see the module doc);
    when these leave positive definiteness open while w_min > 0, the Cholesky
    certificate (:func:`cholesky_lower_bound`) is tried.  The matrix that is
    exactly zero is "zero" (all n eigenvalues zero, exactly).  theory: stability.

    Parameters
    ----------
    A : (n, n) array_like
        Real symmetric matrix (only its lower triangle is read by ``eigvalsh``).
    uncertainty : float
        Relative uncertainty u of A in the 2-norm, in [0, 1): the decision holds
        for every symmetric A + F with ||F||_2 <= u ||A||_2.  Default 0: A as stored.
    rounding_factor : float
        c of the rounding bound (default :data:`EIGENVALUE_ROUNDING`).

    Returns
    -------
    Definiteness

    Raises
    ------
    ParameterError
        A not a finite real square matrix; ``uncertainty`` not in [0, 1).
    """
    return symmetric_definiteness(square_matrix(A), check_uncertainty(uncertainty), rounding_factor)


def symmetric_definiteness(A: np.ndarray, u: float, rounding_factor: float = EIGENVALUE_ROUNDING) -> Definiteness:
    """:func:`definiteness` of a matrix known to be a finite real (n, n) float array, ``u`` known valid.

    For callers whose matrices are validated already (a LinearizedSystem's M, D, S):
    no input checks, one LAPACK call (``dsyevd``, eigenvalues only, lower triangle).
    """
    n = A.shape[0]
    rounding = float(rounding_factor * n * EPS)
    if not np.count_nonzero(A):
        return _with_block(
            Definiteness(
                kind="zero", negative=0, zero=n, positive=0, min_eigenvalue=0.0, max_eigenvalue=0.0,
                tol=rounding + u, threshold=0.0, norm=0.0, rounding=rounding, uncertainty=u, margin=0.0,
                certificate="exactly zero",
            ), None
        )
    w, _, info = _dsyevd(A, compute_v=0, lower=1)
    if info != 0:  # LAPACK's divide and conquer did not converge: numpy's driver instead (it raises if that fails too)
        w = np.linalg.eigvalsh(A)
    norm = float(max(abs(w[0]), abs(w[-1])))
    chol = None
    rho = rounding * norm
    if w[0] > 0 and w[0] - rho <= u * norm:  # positive definiteness left open by the eigenvalues
        chol = cholesky_lower_bound(A, rounding_factor)
    out = _decide(w, norm, rounding, u, chol)
    block = None
    if out.kind == "positive_semidefinite":
        live = A.any(axis=0).nonzero()[0]
        if live.size < n:  # exact zero rows and columns: is the rest positive definite?
            block = symmetric_definiteness(A[live[:, None], live], u, rounding_factor)
    return _with_block(out, block)


def _with_block(out: Definiteness, block: Definiteness | None) -> Definiteness:
    """``out`` with ``certainly_psd`` set (from the nonzero block when given)."""
    sure = out.kind in ("zero", "positive_definite") or (
        out.kind == "positive_semidefinite" and block is not None and block.kind == "positive_definite"
    )
    object.__setattr__(out, "certainly_psd", sure)  # set once, right after construction
    object.__setattr__(out, "_block", block)
    return out

