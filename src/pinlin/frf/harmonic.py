"""Steady-state response to harmonic forcing (SPEC section 6, issue 5 part 2)."""

from __future__ import annotations

import time
import warnings

import numpy as np
import scipy.linalg

from ..errors import AccuracyWarning, ComputationError, ParameterError
from ..linearization.system import LinearizedSystem
from ..response._array import ResponseArray
from ..response._inputs import check_system, check_tolerance, check_vector
from ..response.expansion import complex_matmul, modal_expansion

__all__ = ["HarmonicResponse", "harmonic_response", "HARMONIC_METHODS"]

#: ``"modal"``: the modal (and Jordan-chain) expansion of H(i omega);
#: ``"direct"``: an LU solve of L(i omega) X = F per frequency.
HARMONIC_METHODS = ("modal", "direct")


class HarmonicResponse(ResponseArray):
    """Complex amplitudes X, x(t) = Re(X exp(i omega t)): (n,) for one omega, (len(omega), n) for several.

    Attributes
    ----------
    omega : float or (len(omega),) ndarray
        Forcing frequencies [rad/s].
    defect : float or (len(omega),) ndarray
        ||L(i omega) X - F|| / (||L(i omega)|| ||X||) per frequency (Frobenius
        norm of L): a backward error of the amplitude.
    distance : float or (len(omega),) ndarray
        min_k |i omega - lam_k| [1/s]: how close the forcing is to resonance
        (near a root with a Jordan chain of length m the amplitude grows like
        distance^-m); NaN for ``method="direct"`` without ``modes``.
    projection_residual : float
        How well the modal coefficients reproduce the force's state (0, M^-1 F)
        in the basis of modes and chains (relative, after iterative refinement).
    method : str
    modes : Modes or None
    elapsed : float
        Seconds.
    """

    _fields = ("omega", "defect", "distance", "projection_residual", "method", "modes", "elapsed")

    def _summary(self) -> list[str]:
        return [f"method={self.method!r}", f"max defect={np.max(self.defect):.1e}", f"elapsed={self.elapsed * 1e3:.2f} ms"]


def _modal_amplitudes(expansion, F: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, float]:
    """H(s) F for each s: semisimple modes x_k (y_k^T F) / (s - lam_k), Jordan blocks through (sI - J)^-1."""
    n = F.shape[0]
    # A force F enters the first-order form as the state (0, M^-1 F).
    a = np.zeros(n, dtype=complex)
    b = scipy.linalg.cho_solve(scipy.linalg.cho_factor(expansion.system.M), F.astype(complex))
    c, d, residual = expansion.coefficients(a, b)
    X = complex_matmul(c / (s[:, None] - expansion.lam), expansion.right.T)
    for block, coef in zip(expansion.blocks, d):
        # (sI - J)^-1 coef for J = lam0 I + (superdiagonal ones): back substitution from the chain's end.
        r = block.length
        shift = s - block.lam0
        D = np.zeros((s.size, r), dtype=complex)
        D[:, r - 1] = coef[r - 1] / shift
        for i in range(r - 2, -1, -1):
            D[:, i] = (coef[i] + D[:, i + 1]) / shift
        X += complex_matmul(D, block.vectors.T)
    return X, residual


def _defects(sys: LinearizedSystem, s: np.ndarray, X: np.ndarray, F: np.ndarray, chunk: int = 256) -> np.ndarray:
    """||L(s) X - F|| / (||L(s)||_F ||X||) per frequency, a block of frequencies at a time."""
    out = np.empty(s.size)
    for start in range(0, s.size, chunk):
        L = sys.dynamic_stiffness(s[start : start + chunk])
        Xc = X[start : start + chunk]
        res = np.linalg.norm(np.einsum("kij,kj->ki", L, Xc) - F, axis=1)
        den = np.linalg.norm(L, axis=(1, 2)) * np.linalg.norm(Xc, axis=1)
        out[start : start + chunk] = np.where(den > 0, res / np.where(den > 0, den, 1.0), 0.0)
    return out


def harmonic_response(
    sys: LinearizedSystem,
    F,
    omega,
    *,
    method: str = "modal",
    modes=None,
    tol: float = 1e-8,
) -> HarmonicResponse:
    """Steady-state amplitude of M x'' + C x' + K x = Re(F exp(i omega t)) (SPEC section 6).

    .. math::
        X = H(i\\omega) F = L(i\\omega)^{-1} F
          = \\sum_k \\frac{x_k\\, y_k^T F}{i\\omega - \\lambda_k}
            + \\text{(Jordan-chain terms of defective roots)},
        \\qquad x(t) = \\mathrm{Re}\\left(X e^{i\\omega t}\\right)

    The modal form (default) uses :func:`pinlin.modal_analysis` once for all
    frequencies; near a root of multiplicity m reached by a chain of length m
    the amplitude grows like |i omega - lam_k|^-m (a defective root with a
    chain of length two resonates with the square of the simple amplitude).
    ``method="direct"`` solves L(i omega) X = F by LU per frequency instead.
    Every amplitude comes with its defect ||L(i omega) X - F|| / (||L|| ||X||).

    Parameters
    ----------
    sys : LinearizedSystem
    F : (n,) array, real or complex
        Generalized force amplitude [N, N m] (complex for phase lags).
    omega : float or (len(omega),) array
        Forcing frequencies [rad/s], finite (any sign).
    method : {"modal", "direct"}
    modes : Modes, optional
        A modal analysis of ``sys`` to reuse (modal method).
    tol : float
        An :class:`~pinlin.AccuracyWarning` is issued when a defect exceeds it.

    Returns
    -------
    HarmonicResponse
        Complex X of shape (n,) for a scalar omega, (len(omega), n) for an array.

    Raises
    ------
    ParameterError
        Wrong shapes, non-finite values, unknown method.
    ComputationError
        i omega is an eigenvalue (exact resonance of an undamped mode): L is singular there.
    """
    t_start = time.perf_counter()
    check_system(sys)
    n = sys.n
    F = check_vector(F, n, "F", allow_none=False, complex_ok=True)
    try:
        w = np.array(omega, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("omega", f"expected real frequencies [rad/s], got {omega!r:.80}") from None
    scalar = w.ndim == 0
    w = np.atleast_1d(w)
    if w.ndim != 1 or w.size == 0:
        raise ParameterError("omega", f"expected a number or a non-empty 1-D array, got shape {np.shape(omega)}")
    if not np.all(np.isfinite(w)):
        raise ParameterError("omega", "frequencies must be finite")
    if method not in HARMONIC_METHODS:
        raise ParameterError("method", f"expected one of {HARMONIC_METHODS}, got {method!r}")
    tol = check_tolerance(tol, "tol")
    s = 1j * w

    expansion = None
    projection = 0.0
    if method == "modal" or modes is not None:
        expansion = modal_expansion(sys, modes)
        lam_all = np.asarray(expansion.modes.eigenvalues)
        distance = np.min(np.abs(s[:, None] - lam_all[None, :]), axis=1)
        scale = np.maximum(np.abs(lam_all).max(initial=0.0), expansion.gamma)
        hit = distance <= 1e2 * np.finfo(float).eps * scale
        if np.any(hit):
            raise ComputationError(
                f"harmonic_response: i omega = {s[hit][0]:.6g} is an eigenvalue of the system (an undamped "
                f"resonance): L(i omega) is singular and the steady state does not exist"
            )
    else:
        distance = np.full(w.size, np.nan)

    if method == "modal":
        X, projection = _modal_amplitudes(expansion, F, s)
    else:
        X = np.empty((w.size, n), dtype=complex)
        for i in range(w.size):
            lu = scipy.linalg.lu_factor(sys.dynamic_stiffness(s[i]), check_finite=False)
            X[i] = scipy.linalg.lu_solve(lu, F, check_finite=False)
        if not np.all(np.isfinite(X)):
            raise ComputationError("harmonic_response: L(i omega) is singular at some frequency (undamped resonance)")
    defect = _defects(sys, s, X, F)
    if np.max(defect) > tol:
        k = int(np.argmax(defect))
        warnings.warn(
            f"harmonic_response ({method}): defect {defect[k]:.1e} > tol {tol:g} at omega = {w[k]:.6g} rad/s; "
            f"try method='direct'",
            AccuracyWarning,
            stacklevel=2,
        )
    return HarmonicResponse(
        X[0] if scalar else X,
        omega=float(w[0]) if scalar else w,
        defect=float(defect[0]) if scalar else defect,
        distance=float(distance[0]) if scalar else distance,
        projection_residual=projection,
        method=method,
        modes=None if expansion is None else expansion.modes,
        elapsed=time.perf_counter() - t_start,
    )
