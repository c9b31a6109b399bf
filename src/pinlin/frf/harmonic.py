"""Steady-state response to harmonic forcing (theory: responses): X = H(i omega) F."""

from __future__ import annotations

import time
import warnings

from ..errors.deprecated import renamed_keywords
from ..linearization.system import check_system
from ..numerics import check_tolerance
from ..numerics.arrays import check_vector
from ..results import ResultArray
from ._inputs import real_frequencies
from .engine import DEFAULT_METHOD, DEFAULT_TOL, METHODS, per_point, solve, warn_inaccurate

__all__ = ["HarmonicResponse", "harmonic_response", "HARMONIC_METHODS"]

#: The methods of :func:`harmonic_response` (those of the engine, :mod:`pinlin.frf.engine`).
HARMONIC_METHODS = METHODS


class HarmonicResponse(ResultArray):
    """Complex amplitudes X, x(t) = Re(X exp(i omega t)): (n,) for one omega, (len(omega), n) for several.

    Frequencies first, coordinates last (like a time response, (len(t), n)).
    A read-only ndarray; the figures live on the returned array only.

    Attributes
    ----------
    omega : float or (len(omega),) ndarray
        Forcing frequencies [rad/s].
    defects : float or (len(omega),) ndarray
        Relative defect ``||L(i omega) X - F|| / (||L(i omega)|| ||X|| + ||F||)``
        per frequency (Frobenius norm of L): the normwise backward error of the
        amplitude (:mod:`pinlin.frf.engine`; the modal method on many frequencies
        gives it exactly at sampled ones and an upper bound elsewhere).
    distance : float, (len(omega),) ndarray or None
        min_k |i omega - lam_k| [1/s]: how close the forcing is to resonance
        (near a root with a Jordan chain of length m the amplitude grows like
        distance^-m); None for ``method="direct"`` without ``modes``.
    projection_residual : float or None
        How well the modal coefficients reproduce the force's state (0, M^-1 F)
        in the basis of modes and chains (relative, after iterative
        refinement); None for ``method="direct"``.
    method : str
        ``"direct"``, ``"modal"`` or ``"modal + Jordan chains"``.
    error : float
        ``max(defects)``.
    modes : Modes or None
        The modal analysis used (reuse it through ``modes=``).
    elapsed : float
        Seconds.
    defect
        Deprecated alias of ``defects`` (pinlin 0.1).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> X = pinlin.harmonic_response(sys, [1.0, 0.0], 1.0)
    >>> X.shape, bool(X.error < 1e-12)
    ((2,), True)
    """

    _fields = ("omega", "defects", "distance", "projection_residual", "method", "error", "elapsed", "modes")
    _dict_exclude = ("modes",)

    @property
    def defect(self):
        warnings.warn("HarmonicResponse.defect is now .defects", DeprecationWarning, stacklevel=2)
        return self.defects


@renamed_keywords(tol="error_tol")
def harmonic_response(
    sys,
    F,
    omega,
    *,
    method: str = DEFAULT_METHOD,
    modes=None,
    error_tol: float = DEFAULT_TOL,
) -> HarmonicResponse:
    """Steady-state amplitude of M x'' + C x' + K x = Re(F exp(i omega t)) (theory: responses).

    .. math::
        X = H(i\\omega) F = L(i\\omega)^{-1} F
          = \\sum_k \\frac{x_k\\, y_k^T F}{i\\omega - \\lambda_k}
            + \\text{(Jordan-chain terms of defective roots)},
        \\qquad x(t) = \\mathrm{Re}\\left(X e^{i\\omega t}\\right)

    ``method="direct"`` (default) solves L(i omega) X = F by LU per frequency;
    ``method="modal"`` uses one modal analysis for all frequencies (the engine
    of :mod:`pinlin.frf.engine`).  Near a root of multiplicity m reached by a
    chain of length m the amplitude grows like |i omega - lam_k|^-m (a defective
    root with a chain of length two resonates with the square of the simple
    amplitude).  Every amplitude comes with its relative defect.

    Parameters
    ----------
    sys : LinearizedSystem
    F : (n,) array, real or complex
        Generalized force amplitude [N, N m] (complex for phase lags).
    omega : float or (len(omega),) array
        Forcing frequencies [rad/s], finite (any sign).
    method : {"direct", "modal"}
    modes : Modes, optional
        A modal analysis of ``sys`` to reuse (modal method; with "direct" it
        only gives ``distance``).
    error_tol : float
        An :class:`~pinlin.AccuracyWarning` is issued when ``error`` exceeds it
        (``tol`` is its deprecated spelling).

    Returns
    -------
    HarmonicResponse
        Complex X of shape (n,) for a scalar omega, (len(omega), n) for an array.

    Raises
    ------
    ParameterError
        Wrong shapes, non-finite values, unknown method, bad modes or error_tol, or a
        frequency at an eigenvalue on the imaginary axis (an undamped
        resonance: L(i omega) is singular, the steady state does not exist).
    ComputationError
        L(i omega) overflows; the modal expansion does not apply to these modes.

    Examples
    --------
    A unit force on the first mass at 0.5 and 1 rad/s: one amplitude vector per frequency:

    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> X = pinlin.harmonic_response(sys, [1.0, 0.0], [0.5, 1.0])
    >>> np.round(np.asarray(X), 6)
    array([[ 0.845475-0.047552j,  0.481959-0.040943j],
           [ 0.249377-5.012469j, -0.249377-4.987531j]])
    """
    t_start = time.perf_counter()
    sys = check_system(sys)
    F = check_vector(F, sys.n, "F", complex_ok=True, allow_none=False)
    w, scalar = real_frequencies(omega)
    error_tol = check_tolerance(error_tol, "error_tol")
    out = solve(sys, 1j * w, F[:, None], method=method, modes=modes, label="omega", values=w)
    name = method if out.expansion is None else out.expansion.method
    warn_inaccurate("harmonic_response", name, out.defects, error_tol, "omega", w, exact=out.exact)
    X = out.X[:, :, 0]

    used = out.expansion.modes if out.expansion is not None else modes
    return HarmonicResponse(
        X[0] if scalar else X,
        omega=per_point(w, scalar),
        defects=per_point(out.defects, scalar),
        distance=per_point(out.distance, scalar),
        projection_residual=out.projection_residual,
        method=name,
        error=out.error,
        modes=used,
        elapsed=time.perf_counter() - t_start,
    )
