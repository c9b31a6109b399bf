"""The one engine for the dynamic flexibility H(s) = L(s)^-1 (theory: flexibility, responses, error figures; paper Sec. 10).

Every frequency-domain result of pinlin is ``X(s) = H(s) B`` for a block B of
right-hand sides: identity columns for :func:`pinlin.flexibility` and
:func:`pinlin.frequency_response`, a force amplitude F for
:func:`pinlin.harmonic_response`, and the contour samples of
:func:`pinlin.residues`.  :func:`solve` evaluates it by one of two methods:

- ``"direct"`` (the default everywhere): backward stable at every point whatever
  the spectrum (defective, clustered, or with ill-conditioned eigenvectors), no
  eigensolution needed: that is why it is the default.  Few points: an LU
  factorization of ``L(s) = s^2 M + s C + K`` per point (batched LAPACK gesv),
  O(n^3) per point.  Many points (when :func:`pinlin.frf.schur.schur_pays`): one
  generalized real Schur form of the scaled companion pencil, then a
  quasi-triangular solve per point, O(n^2) per point and right-hand side
  (:mod:`pinlin.frf.schur`; Laub 1981 in pencil form).
- ``"modal"``: the modal expansion (:mod:`pinlin.frf.expansion`) of one modal
  analysis, Jordan blocks included,

  .. math::
      X(s) = \\sum_k \\frac{x_k c_k}{s - \\lambda_k}
           + \\sum_b V_b (sI - J_b)^{-1} d_b,

  with (c, d) the coefficients of the state (0, M^{-1} B) on the modes and
  chains (for a simple L, ``c_k = y_k^T B``: the modal sum of the theory pages (theory: flexibility)
  ``sum_k x_k y_k^T / (s - lam_k)``).  O(n) per point, output and input once
  the eigen-data are known: faster for many points; its accuracy follows the
  conditioning of the eigenvectors, which the error figure shows.  Its check
  costs O(n) per point too: the exact relative defect at
  :data:`pinlin.frf.modal.CHECK_SAMPLES` points spread over those given (all of
  them when there are no more), an upper bound of it at the others, from the
  eigen-residuals and the samples (:mod:`pinlin.frf.modal`); ``error``, their
  maximum, bounds the defect at every point.

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
from typing import TYPE_CHECKING

import numpy as np

from ..errors import AccuracyWarning, ParameterError
from ..linearization.system import LinearizedSystem
from ..numerics import EPS, chunks, system_scaling
from .expansion import check_modes
from .measures import residuals, stiffness_norms, stiffness_stack
from .modal import RESIDUAL_ROUNDING, linear_part_bound, modal_solution, near_eigenvalue
from .schur import schur_pays, schur_pencil, schur_solve

if TYPE_CHECKING:
    from .expansion import ModalExpansion

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
    exact : (len(s),) bool ndarray or None
        Where ``defects`` holds the exact relative defect (elsewhere an upper bound of it:
        the modal method on more than CHECK_SAMPLES points); None when all are exact.
    """

    X: np.ndarray
    defects: np.ndarray | None
    distance: np.ndarray | None
    expansion: ModalExpansion | None
    projection_residual: float | None
    exact: np.ndarray | None = None

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
        distance = near_eigenvalue(s, np.asarray(modes.eigenvalues))
    exact = None
    if method == "direct":
        nL = stiffness_norms(sys, s, values, label)
        if schur_pays(sys.n, s.size, B.shape[1]):
            X = schur_solve(schur_pencil(sys), s, B)
        else:
            try:
                X = lu_solve(sys, s, B)
            except SingularPoint as exc:
                raise pole_error(label, values, exc.index, "L(s) is exactly singular") from None
        defects = _defects(X, B, nL, residuals(sys, s, X, B) if check else None, values, label)
    else:
        X, defects, expansion, projection, exact = _modal_method(sys, s, B, modes, rows, check, distance, values, label)
    if X.shape[1] == sys.n and not np.array_equal(rows, np.arange(sys.n)):
        X = X[:, rows]  # (the modal method without a check computed only these rows)
    return Solution(X=X, defects=defects, distance=distance, expansion=expansion, projection_residual=projection,
                    exact=exact)


def _modal_method(sys, s, B, modes, rows, check, distance, values, label):
    """X, defects (the bound of :mod:`pinlin.frf.modal`, or exact with Jordan blocks), expansion, projection."""
    lam = np.asarray(modes.eigenvalues)
    scale = max(float(np.max(np.abs(lam), initial=0.0)), system_scaling(sys.M, sys.C, sys.K).gamma)
    hit = distance <= POLE_TOL * scale
    if np.any(hit):
        raise pole_error(label, values, int(np.flatnonzero(hit)[0]), "within rounding of a computed eigenvalue")
    out = modal_solution(sys, s, B, modes, rows, check, lambda pts: stiffness_norms(sys, pts, values, label))
    X = out.X
    if out.bound is None:  # no check, or Jordan blocks: exact defects where every row was evaluated
        nL = stiffness_norms(sys, s, values, label) if out.rows_all else None
        res = residuals(sys, s, X, B) if check else None
        return X, _defects(X, B, nL, res, values, label), out.expansion, out.projection, None
    nL = stiffness_norms(sys, s, values, label)
    # the pole test and the denominator with the rows evaluated (a lower bound of ||X||: the bound stays a bound)
    _defects(X, B, nL, None, values, label)
    nB = float(np.linalg.norm(B))
    k = out.samples
    res = residuals(sys, s[k], out.exact, B)
    den_k = nL[k] * np.linalg.norm(out.exact.reshape(k.size, -1), axis=1) + nB
    rounding = (3 * sys.n + RESIDUAL_ROUNDING) * EPS * den_k
    bound = out.bound + linear_part_bound(s, k, res + out.bound[k] + rounding)
    nX = np.linalg.norm(X.reshape(s.size, -1), axis=1)
    if not out.rows_all:  # a lower bound of ||X|| over all rows keeps the bound a bound
        nX = np.maximum(nX, out.lower)
    den = nL * nX + nB
    defects = np.where(den > 0, bound / np.where(den > 0, den, 1.0), 0.0)
    defects[k] = res / den_k  # the exact relative defect where it was computed (the bound is at least that)
    exact = np.zeros(s.size, dtype=bool)
    exact[k] = True
    return X, defects, out.expansion, out.projection, None if exact.all() else exact


def warn_inaccurate(
    function: str, method: str, defects: np.ndarray | None, tol: float, label: str, values, exact=None
) -> None:
    """An AccuracyWarning when the largest relative defect exceeds ``tol`` (the same text from every function).

    ``exact`` (a mask, see :class:`Solution`) marks where ``defects`` are exact; the
    message says when the largest is an upper bound instead.
    """
    if defects is None or not np.max(defects) > tol:
        return
    k = int(np.argmax(defects))
    hint = "; method='direct' is backward stable" if method != "direct" else ""
    what = f"relative defect {defects[k]:.1e}"
    if exact is not None and not exact[k]:
        what = (
            f"relative defect at most {defects[k]:.1e} (an upper bound from the eigen-residuals; the exact "
            f"defect at the {int(np.sum(exact))} sampled points is at most {np.max(defects[exact]):.1e})"
        )
    warnings.warn(
        f"{function} ({method}): {what} > tol {tol:g} at {label}[{k}] = {values[k]:.6g}{hint}",
        AccuracyWarning,
        stacklevel=3,
    )


def per_point(values, scalar: bool):
    """A per-point figure shaped as the caller gave the points: a Python scalar for a scalar point."""
    if values is None:
        return None
    return values[0].item() if scalar else values
