"""The one engine for the dynamic flexibility H(s) = L(s)^-1 (SPEC sections 4, 6 and 8; paper Sec. 10).

Every frequency-domain result of pinlin is ``X(s) = H(s) B`` for a block B of
right-hand sides: identity columns for :func:`pinlin.flexibility` and
:func:`pinlin.frequency_response`, a force amplitude F for
:func:`pinlin.harmonic_response`, and the contour samples of
:func:`pinlin.residues`.  :func:`solve` evaluates it by one of two methods:

- ``"direct"`` (the default everywhere): an LU factorization of
  ``L(s) = s^2 M + s C + K`` per point (batched LAPACK gesv), O(n^3) per point.
  It is backward stable at every point whatever the spectrum (defective,
  clustered, or with ill-conditioned eigenvectors) and needs no eigensolution:
  that is why it is the default.
- ``"modal"``: the modal expansion (:mod:`pinlin.frf.expansion`) of one modal
  analysis, Jordan blocks included,

  .. math::
      X(s) = \\sum_k \\frac{x_k c_k}{s - \\lambda_k}
           + \\sum_b V_b (sI - J_b)^{-1} d_b,

  with (c, d) the coefficients of the state (0, M^{-1} B) on the modes and
  chains (for a simple L, ``c_k = y_k^T B``: the SPEC's sum
  ``sum_k x_k y_k^T / (s - lam_k)``).  O(n) per point, output and input once
  the eigen-data are known: faster for many points; its accuracy follows the
  conditioning of the eigenvectors, which the error figure shows.

The error figure of every evaluation (one name, ``defects``, one value per point)
is the relative defect, the normwise backward error of the linear system
(Rigal and Gaches 1967):

.. math::
    \\eta(s) = \\frac{\\|L(s) X - B\\|_F}{\\|L(s)\\|_F \\|X\\|_F + \\|B\\|_F},

the smallest relative change of L(s) and B for which X is exact; the forward
error is at most about cond(L(s)) eta.  ``error`` is its largest value.

A pole (s at an eigenvalue, an undamped resonance for s = i omega) is treated
the same way by both methods: a :class:`~pinlin.ParameterError` naming the point,
when L(s) is singular to working precision, that is when

- LAPACK finds L(s) exactly singular (direct), or
- the amplification ``||L(s)|| ||X|| / ||B||`` (a lower bound of the condition
  number of L(s)) exceeds ``1 / POLE_TOL`` (both methods), or
- s lies within ``POLE_TOL * scale`` of an eigenvalue in a denominator of the
  modal sum (modal).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..errors import AccuracyWarning, ComputationError, ParameterError
from ..linearization.system import LinearizedSystem
from ..numerics import CHUNK_BYTES, EPS, chunks
from .expansion import ModalExpansion, check_modes, complex_matmul, modal_expansion

__all__ = [
    "METHODS",
    "DEFAULT_METHOD",
    "DEFAULT_TOL",
    "POLE_TOL",
    "Solution",
    "SingularPoint",
    "solve",
    "stiffness_stack",
    "stiffness_norms",
    "residuals",
    "lu_solve",
    "per_point",
    "pole_error",
    "warn_inaccurate",
]

#: The methods of :func:`solve`; see the module docstring.
METHODS = ("direct", "modal")
#: The default method of every function built on the engine (backward stable, no eigensolution).
DEFAULT_METHOD = "direct"
#: Default threshold of the AccuracyWarning on ``error``: far above the rounding of a
#: backward-stable solve (about n eps), below any accuracy a user plots or compares.
DEFAULT_TOL = 1e-8
#: L(s) counts as singular to working precision when its condition number exceeds 1 / POLE_TOL
#: (about 4.5e13): the forward error bound cond(L) eps is then above 1e-2, at most two digits of H
#: would be guaranteed.  Relative to the eigenvalue scale, the same tolerance marks a point within
#: rounding of a computed eigenvalue (100 eps covers the rounding of the eigenvalues and of L(s)).
POLE_TOL = 1e2 * EPS
#: ||L(s)||_F^2 from its expansion in |s| and the six inner products of M, C, K is exact up to
#: about 10 eps W^2 (W = |s|^2 ||M|| + |s| ||C|| + ||K||); where ||L||^2 < NORM_CANCEL eps W^2 the
#: terms cancel (near a resonance of a proportional system) and the norm is recomputed from L(s)
#: itself, so that every norm used is accurate to 1e-3 relative or better.
NORM_CANCEL = 1e4
#: Copies of an (n, m) block alive at once in :func:`residuals` (X, M X, C X, K X and L X - B).
_BLOCK_COPIES = 5


class SingularPoint(Exception):
    """LAPACK found L(s) exactly singular at point ``index`` (internal: callers turn it into an error)."""

    def __init__(self, index: int):
        super().__init__(index)
        self.index = int(index)


@dataclass(frozen=True)
class Solution:
    """X(s) = H(s) B at every point, with the figures of the evaluation.

    Attributes
    ----------
    X : (len(s), len(rows), m) complex ndarray
    defects : (len(s),) ndarray or None
        Relative defect per point (module docstring); None when not checked.
    distance : (len(s),) ndarray or None
        min_k |s - lam_k| [1/s] over the computed eigenvalues; None without a modal analysis.
    expansion : ModalExpansion or None
        The modal expansion used (modal method).
    projection_residual : float or None
        How well the modal coefficients reproduce the state (0, M^-1 B) (modal method).
    """

    X: np.ndarray
    defects: np.ndarray | None
    distance: np.ndarray | None
    expansion: ModalExpansion | None
    projection_residual: float | None

    @property
    def error(self) -> float | None:
        """max(defects), None when the defects were not computed."""
        return None if self.defects is None else float(np.max(self.defects))


def pole_error(label: str, values: np.ndarray, k: int, why: str) -> ParameterError:
    """The one error for a point at a pole of H (both methods, every function)."""
    return ParameterError(
        label,
        f"{label}[{k}] = {values[k]:.10g} is at an eigenvalue of the system, where H has a pole ({why}): "
        f"L is singular there and a steady state does not exist (an undamped resonance for s = i omega); "
        f"pinlin.residues gives the principal part of H at an eigenvalue",
    )


def stiffness_stack(sys: LinearizedSystem, s: np.ndarray) -> np.ndarray:
    """L(s_k) = s_k^2 M + s_k C + K for a 1-D array of points: (len(s), n, n) complex."""
    z = np.asarray(s, dtype=complex)[:, None, None]
    with np.errstate(over="ignore", invalid="ignore"):  # (callers check ||L|| for overflow and raise)
        L = z * sys.M  # Horner, in place: (s M + C) s + K
        L += sys.C
        L *= z
        L += sys.K
    return L


def stiffness_norms(sys: LinearizedSystem, s: np.ndarray, values=None, label: str = "s") -> np.ndarray:
    """||L(s)||_F per point without forming L(s), except where its terms cancel (see NORM_CANCEL).

    .. math::
        \\|L(s)\\|_F^2 = |s|^4 \\langle M,M\\rangle + |s|^2 \\langle C,C\\rangle + \\langle K,K\\rangle
        + 2\\,\\mathrm{Re}(s^2 \\bar s) \\langle M,C\\rangle + 2\\,\\mathrm{Re}(s^2) \\langle M,K\\rangle
        + 2\\,\\mathrm{Re}(s) \\langle C,K\\rangle

    Raises
    ------
    ComputationError
        L(s) overflows double precision at some point.
    """
    values = s if values is None else values
    M, C, K = (np.asarray(A, dtype=float) for A in (sys.M, sys.C, sys.K))
    MM, CC, KK, MC, MK, CK = (float(np.vdot(A, B)) for A, B in ((M, M), (C, C), (K, K), (M, C), (M, K), (C, K)))
    a = np.abs(s)
    with np.errstate(over="ignore", invalid="ignore"):
        W = a * a * np.sqrt(MM) + a * np.sqrt(CC) + np.sqrt(KK)
        sq = (a**4 * MM + a * a * CC + KK + 2 * np.real(s * s * np.conj(s)) * MC + 2 * np.real(s * s) * MK
              + 2 * np.real(s) * CK)
    bad = ~(np.isfinite(W) & np.isfinite(sq))
    if np.any(bad):
        k = int(np.flatnonzero(bad)[0])
        raise ComputationError(
            f"L(s) overflows double precision at {label}[{k}] = {values[k]:.6g}: rescale the system "
            f"(units, or time in other units) or leave out such points"
        )
    out = np.sqrt(np.maximum(sq, 0.0))
    cancel = np.flatnonzero(sq < NORM_CANCEL * EPS * W * W)
    for sl in chunks(cancel.size, sys.n):
        idx = cancel[sl]
        out[idx] = np.linalg.norm(stiffness_stack(sys, s[idx]), axis=(1, 2))
    return out


def residuals(sys: LinearizedSystem, s: np.ndarray, X: np.ndarray, B: np.ndarray) -> np.ndarray:
    """||L(s) X(s) - B||_F per point for X (len(s), n, m): three real matrix products per block of points."""
    F, n, m = X.shape
    per = max(1, CHUNK_BYTES // (_BLOCK_COPIES * np.dtype(complex).itemsize * n * m))
    M, C, K = (np.asarray(A, dtype=float) for A in (sys.M, sys.C, sys.K))
    out = np.empty(F)
    for start in range(0, F, per):
        sl = slice(start, min(F, start + per))
        f = sl.stop - sl.start
        # columns ordered (point, input); complex numbers as pairs of reals for one real product each
        flat = np.ascontiguousarray(np.moveaxis(X[sl], 0, 1)).reshape(n, f * m).view(float)
        MX, CX, KX = ((A @ flat).view(complex) for A in (M, C, K))
        z = np.repeat(s[sl], m)
        R = (z * z) * MX + z * CX + KX - np.tile(B, (1, f))
        out[sl] = np.linalg.norm(R.reshape(n, f, m), axis=(0, 2))
    return out


def lu_solve(sys: LinearizedSystem, s: np.ndarray, B: np.ndarray) -> np.ndarray:
    """The direct method: ``L(s) X = B`` by LU per point (batched LAPACK gesv, in chunks of bounded memory).

    Returns
    -------
    X : (len(s), n, m) complex ndarray

    Raises
    ------
    SingularPoint
        LAPACK found L(s) exactly singular at a point (callers turn it into their error).
    """
    F, n, m = s.size, sys.n, B.shape[1]
    X = np.empty((F, n, m), dtype=complex)
    for sl in chunks(F, n):
        L = stiffness_stack(sys, s[sl])
        try:
            X[sl] = np.linalg.solve(L, np.broadcast_to(B, (L.shape[0], n, m)))
        except np.linalg.LinAlgError:
            bad = [i for i in range(L.shape[0]) if np.linalg.matrix_rank(L[i]) < n]
            raise SingularPoint(sl.start + (bad[0] if bad else 0)) from None
    return X


def _modal(expansion: ModalExpansion, s: np.ndarray, B: np.ndarray, rows: np.ndarray):
    """Rows ``rows`` of H(s) B from the modal expansion: (F, len(rows), m), and the projection residual."""
    sys = expansion.system
    m = B.shape[1]
    rhs = scipy.linalg.cho_solve(scipy.linalg.cho_factor(sys.M), B.astype(complex))
    c, d, projection = expansion.coefficients(np.zeros_like(rhs), rhs)
    R = expansion.right[rows]  # (r, k)
    W = 1.0 / (s[:, None] - expansion.lam[None, :])  # (F, k)
    # (F, k) x (k, r m): the Khatri-Rao product of the right vectors and the coefficients
    KR = (c[:, None, :] * R.T[:, :, None]).reshape(expansion.lam.size, len(rows) * m)
    X = complex_matmul(W, KR).reshape(s.size, len(rows), m)
    for block, coef in zip(expansion.blocks, d):
        # (sI - J)^-1 coef for J = lam0 I + (superdiagonal ones): back substitution from the chain's end
        r = block.length
        shift = (s - block.lam0)[:, None]
        D = np.empty((s.size, r, m), dtype=complex)
        D[:, r - 1] = coef[r - 1][None, :] / shift
        for i in range(r - 2, -1, -1):
            D[:, i] = (coef[i][None, :] + D[:, i + 1]) / shift
        X += np.einsum("fim,ri->frm", D, block.vectors[rows])
    return X, projection


def _near_eigenvalue(s: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """Distance [1/s] of each point to the nearest of ``lam`` (inf when there is none)."""
    if lam.size == 0:
        return np.full(s.size, np.inf)
    return np.min(np.abs(s[:, None] - lam[None, :]), axis=1)


def _modal_solution(sys, s, B, modes, rows, check, values, label):
    """The modal method: expansion, X (all rows when checked or asked), ||L||, ||L X - B||, projection."""
    expansion = modal_expansion(sys, modes)
    lam = expansion.eigenvalues
    scale = max(float(np.max(np.abs(lam), initial=0.0)), expansion.gamma)
    hit = _near_eigenvalue(s, lam) <= POLE_TOL * scale
    if np.any(hit):
        raise pole_error(label, values, int(np.flatnonzero(hit)[0]), "within rounding of a computed eigenvalue")
    full = check or len(rows) == sys.n
    X, projection = _modal(expansion, s, B, np.arange(sys.n) if full else rows)
    nL = stiffness_norms(sys, s, values, label) if full else None
    res = residuals(sys, s, X, B) if check else None
    return expansion, X, nL, res, projection


def _defects(X, B, nL, res, values, label) -> np.ndarray | None:
    """The relative defect per point (None without residuals), after the amplification test for a pole."""
    if nL is None:
        return None
    F = X.shape[0]
    nX = np.linalg.norm(X.reshape(F, -1), axis=1)
    nB = float(np.linalg.norm(B))
    with np.errstate(over="ignore", invalid="ignore"):
        amplification = nL * nX / nB if nB > 0 else np.zeros(F)
    singular = ~(amplification * POLE_TOL <= 1.0)  # NaN (from an overflowing X) counts as singular
    if np.any(singular):
        k = int(np.flatnonzero(singular)[0])
        raise pole_error(label, values, k, f"||L|| ||X|| / ||B|| = {amplification[k]:.1e} exceeds 1 / POLE_TOL")
    if res is None:
        return None
    den = nL * nX + nB
    return np.where(den > 0, res / np.where(den > 0, den, 1.0), 0.0)


def solve(
    sys: LinearizedSystem,
    s: np.ndarray,
    B: np.ndarray,
    *,
    method: str = DEFAULT_METHOD,
    modes=None,
    rows: np.ndarray | None = None,
    check: bool = True,
    label: str = "s",
    values: np.ndarray | None = None,
) -> Solution:
    """``X(s) = H(s) B`` at every point of ``s`` by ``method`` (see the module docstring).

    Parameters
    ----------
    sys : LinearizedSystem
    s : (F,) complex ndarray
        Points [1/s], already checked finite.
    B : (n, m) ndarray
        Right-hand sides (columns).
    method : {"direct", "modal"}
    modes : Modes, optional
        A modal analysis of ``sys`` (computed for ``method="modal"`` when omitted;
        with ``method="direct"`` it only serves ``distance``).
    rows : (r,) int ndarray, optional
        The rows of X wanted (default all).  The modal method with
        ``check=False`` evaluates only these (and then cannot apply the
        amplification test for a pole).
    check : bool
        Compute the relative defect per point (needs all rows).
    label, values : str, ndarray
        The caller's name and values of the points, for messages
        (``"omega"`` and the frequencies for s = i omega).

    Returns
    -------
    Solution

    Raises
    ------
    ParameterError
        Unknown method, ``modes`` of another system, a point at a pole.
    ComputationError
        L(s) overflows double precision; the modal expansion does not apply.
    """
    if method not in METHODS:
        raise ParameterError("method", f"expected one of {METHODS}, got {method!r}")
    values = s if values is None else values
    rows = np.arange(sys.n) if rows is None else np.asarray(rows, dtype=int)
    B = np.asarray(B, dtype=complex)
    expansion = projection = distance = None
    if modes is not None or method == "modal":
        modes = check_modes(sys, modes)
        distance = _near_eigenvalue(s, np.asarray(modes.eigenvalues))
    if method == "direct":
        nL = stiffness_norms(sys, s, values, label)
        try:
            X = lu_solve(sys, s, B)
        except SingularPoint as exc:
            raise pole_error(label, values, exc.index, "L(s) is exactly singular") from None
        res = residuals(sys, s, X, B) if check else None
    else:
        expansion, X, nL, res, projection = _modal_solution(sys, s, B, modes, rows, check, values, label)
    defects = _defects(X, B, nL, res, values, label)
    if X.shape[1] == sys.n and not np.array_equal(rows, np.arange(sys.n)):
        X = X[:, rows]  # (the modal method without a check computed only these rows)
    return Solution(X=X, defects=defects, distance=distance, expansion=expansion, projection_residual=projection)


def warn_inaccurate(function: str, method: str, defects: np.ndarray | None, tol: float, label: str, values) -> None:
    """An AccuracyWarning when the largest relative defect exceeds ``tol`` (the same text from every function)."""
    if defects is None or not np.max(defects) > tol:
        return
    k = int(np.argmax(defects))
    hint = "; method='direct' is backward stable" if method != "direct" else ""
    warnings.warn(
        f"{function} ({method}): relative defect {defects[k]:.1e} > tol {tol:g} at {label}[{k}] = "
        f"{values[k]:.6g}{hint}",
        AccuracyWarning,
        stacklevel=3,
    )


def per_point(values, scalar: bool):
    """A per-point figure shaped as the caller gave the points: a Python scalar for a scalar point."""
    if values is None:
        return None
    return values[0].item() if scalar else values
