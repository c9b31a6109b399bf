"""Frequency response ``H(i omega)`` of selected inputs and outputs (theory: responses, paper Sec. 12).

The steady state of ``M x'' + C x' + K x = Re(F exp(i omega t))`` is
``x(t) = Re(H(i omega) F exp(i omega t))``.  Inputs and outputs are coordinates
(generalized forces and displacements of ``sys.dof_names``); the data follow
python-control's convention: ``response[output, input, frequency]``.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..errors.deprecated import renamed_keywords
from ..extras import import_pandas
from ..linearization.system import check_system
from ..numerics import check_tolerance, dof_indices
from ..results import Result
from ._inputs import real_frequencies
from .control import frequency_response_data
from .engine import DEFAULT_METHOD, DEFAULT_TOL, solve, warn_inaccurate

__all__ = ["FrequencyResponse", "frequency_response"]


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class FrequencyResponse(Result):
    """``H(i omega)`` for chosen outputs and inputs, in python-control's axis order.

    ``mag, phase, omega = resp`` unpacks like python-control's
    ``frequency_response``.

    Attributes
    ----------
    response : (n_outputs, n_inputs, n_frequencies) complex ndarray
        ``H(i omega)[output, input]`` [m/N, rad/(N m), ...]; the frequency is
        the last axis (python-control), unlike the point-first stacks of
        :func:`pinlin.flexibility` and :func:`pinlin.harmonic_response`.
    omega : (n_frequencies,) ndarray
        Angular frequencies [rad/s].
    outputs, inputs : (k,) int ndarray
        Coordinate indices.
    output_names, input_names : tuple of str
    method : str
        ``"direct"``, ``"modal"`` or ``"modal + Jordan chains"``.
    defects : (n_frequencies,) ndarray or None
        Per frequency, the relative defect ``||L(i w) H_c - I_c|| / (||L(i w)||
        ||H_c|| + ||I_c||)`` over the input columns c (all n rows): the
        normwise backward error (theory: error figures, :mod:`pinlin.frf.engine`).
        The modal method on more frequencies than
        :data:`pinlin.frf.modal.CHECK_SAMPLES` computes it exactly at that many
        sampled frequencies and gives an upper bound of it at the others
        (``notes`` says which); ``error`` then bounds the defect at every
        frequency.  None when the check was skipped.
    distance : (n_frequencies,) ndarray or None
        Distance [1/s] of i omega to the nearest computed eigenvalue; None
        without a modal analysis.
    error : float or None
        ``max(defects)``; None when the check was skipped (``check=False``).
    elapsed : float
        Seconds.
    notes : tuple of str
    residual
        Deprecated alias of ``defects`` (pinlin 0.1).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> resp = pinlin.frequency_response(sys, [0.5, 1.0, 2.0], inputs=[0], outputs=[1])
    >>> resp.response.shape, resp.method
    ((1, 1, 3), 'direct')
    """

    response: np.ndarray
    omega: np.ndarray
    outputs: np.ndarray
    inputs: np.ndarray
    output_names: tuple[str, ...]
    input_names: tuple[str, ...]
    method: str
    defects: np.ndarray | None
    distance: np.ndarray | None
    error: float | None
    elapsed: float
    notes: tuple[str, ...] = field(default=())

    @property
    def residual(self) -> np.ndarray | None:
        warnings.warn("FrequencyResponse.residual is now .defects", DeprecationWarning, stacklevel=2)
        return self.defects

    @property
    def magnitude(self) -> np.ndarray:
        """``|H(i omega)|``, same shape as ``response``."""
        return np.abs(self.response)

    @property
    def phase(self) -> np.ndarray:
        """``arg H(i omega)`` [rad] in (-pi, pi], same shape as ``response``."""
        return np.angle(self.response)

    @property
    def frequency(self) -> np.ndarray:
        """``omega / (2 pi)`` [Hz]."""
        return self.omega / (2 * np.pi)

    def to_control(self, name: str | None = None):
        """This response as a python-control ``FrequencyResponseData`` (inputs ``"force:<dof>"``, outputs the dof names).

        Raises
        ------
        ParameterError
            Negative or non-increasing ``omega``.
        MissingDependencyError
            python-control is not installed (``pip install 'pinlin[control]'``).

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> frd = pinlin.frequency_response(sys, [0.5, 1.0, 2.0], inputs=[0], outputs=[1]).to_control()
        >>> frd.input_labels, frd.output_labels, frd.omega.tolist()
        (['force:x1'], ['x2'], [0.5, 1.0, 2.0])
        """
        return frequency_response_data(self, name)

    def __iter__(self):
        return iter((self.magnitude, self.phase, self.omega))

    def to_pandas(self):
        """The response in long format: one row per (frequency, output, input), frequency first.

        Columns ``omega`` [rad/s], ``frequency_hz`` [Hz], ``output``, ``input`` (coordinate
        names), ``magnitude``, ``phase`` [rad], ``re``, ``im`` of H(i omega)[output, input].

        Raises
        ------
        MissingDependencyError
            pandas is not installed (``pip install 'pinlin[pandas]'``).

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> df = pinlin.frequency_response(sys, [0.5, 1.0, 2.0], inputs=[0], outputs=[1]).to_pandas()
        >>> df.shape, df["output"][0], df["input"][0], round(float(df["magnitude"][1]), 6)
        ((3, 8), 'x2', 'x1', 4.993762)
        """
        pd = import_pandas()
        n_out, n_in, n_w = self.response.shape
        H = np.moveaxis(np.asarray(self.response), -1, 0).reshape(-1)  # frequency, output, input
        return pd.DataFrame({
            "omega": np.repeat(self.omega, n_out * n_in),
            "frequency_hz": np.repeat(self.frequency, n_out * n_in),
            "output": np.tile(np.repeat(np.asarray(self.output_names, dtype=object), n_in), n_w),
            "input": np.tile(np.asarray(self.input_names, dtype=object), n_out * n_w),
            "magnitude": np.abs(H), "phase": np.angle(H), "re": H.real, "im": H.imag,
        })

    def __repr__(self) -> str:
        err = "unchecked" if self.defects is None else f"{self.error:.1e}"
        return (
            f"FrequencyResponse(outputs={len(self.outputs)}, inputs={len(self.inputs)}, "
            f"frequencies={len(self.omega)}, method={self.method!r}, error={err}, elapsed={self.elapsed:.3g} s)"
        )


@renamed_keywords(tol="error_tol")
def frequency_response(
    sys,
    omega,
    inputs=None,
    outputs=None,
    *,
    method: str = DEFAULT_METHOD,
    modes=None,
    check: bool = True,
    error_tol: float = DEFAULT_TOL,
) -> FrequencyResponse:
    """Frequency response ``H(i omega) = L(i omega)^-1`` from ``inputs`` to ``outputs`` (theory: responses).

    .. math::
        H(i\\omega) = (-\\omega^2 M + i\\omega C + K)^{-1}
        = \\sum_k \\frac{x_k y_k^T}{i\\omega - \\lambda_k} + \\text{(Jordan-block terms)}

    Parameters
    ----------
    sys : LinearizedSystem
    omega : float or 1-D array of float
        Angular frequencies [rad/s], finite (negative values are allowed:
        ``H(-i w) = conj H(i w)``).
    inputs, outputs : int, str or sequence of them, optional
        Coordinates (indices or ``dof_names``) where the generalized force acts
        and which displacements are returned; default all.
    method : {"direct", "modal"}
        "direct" (default): one LU factorization of ``L(i omega)`` per
        frequency, O(n^3) each, backward stable.  "modal": the modal expansion
        of :func:`pinlin.modal_analysis` (Jordan chains included), O(n) per
        input-output pair and frequency after the eigensolution (see
        :mod:`pinlin.frf.engine`).
    modes : Modes, optional
        A precomputed modal analysis (for ``method="modal"``, or for ``distance``).
    check : bool
        Compute the relative defect per frequency (costs O(n^2) per input and
        frequency; on by default).
    error_tol : float
        An :class:`~pinlin.AccuracyWarning` is issued when ``error`` exceeds it
        (``tol`` is its deprecated spelling).

    Returns
    -------
    FrequencyResponse

    Raises
    ------
    ParameterError
        ``omega`` not a finite real scalar or 1-D array, unknown inputs or
        outputs, bad method, modes or error_tol, a frequency at an eigenvalue on the
        imaginary axis (an undamped resonance: a pole of H).
    ComputationError
        L(i omega) overflows; the modal expansion does not apply to these modes.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> resp = pinlin.frequency_response(sys, [0.5, 1.0, 2.0])
    >>> resp.response.shape
    (2, 2, 3)
    >>> np.round(resp.response[0, 0], 6)
    array([ 0.845475-0.047552j,  0.249377-5.012469j, -0.646698-0.107216j])
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    w, _ = real_frequencies(omega)
    ins = dof_indices(sys, inputs, "inputs")
    outs = dof_indices(sys, outputs, "outputs")
    error_tol = check_tolerance(error_tol, "error_tol")
    out = solve(sys, 1j * w, np.eye(sys.n)[:, ins], method=method, modes=modes, rows=outs, check=check,
                label="omega", values=w)
    name = method if out.expansion is None else out.expansion.method
    warn_inaccurate("frequency_response", name, out.defects, error_tol, "omega", w, exact=out.exact)
    notes = []
    if out.expansion is not None:
        notes.append(f"modes from {getattr(out.expansion.modes, 'method', 'modal_analysis')!s}")
    if out.exact is not None:
        notes.append(
            f"check: the exact relative defect at {int(out.exact.sum())} of {w.size} frequencies (at most "
            f"{np.max(out.defects[out.exact]):.1e}), an upper bound from the eigen-residuals at the others (at "
            f"most {np.max(out.defects[~out.exact]):.1e})"
        )
    return FrequencyResponse(
        response=np.moveaxis(out.X, 0, -1),
        omega=w,
        outputs=outs,
        inputs=ins,
        output_names=tuple(sys.dof_names[i] for i in outs),
        input_names=tuple(sys.dof_names[i] for i in ins),
        method=name,
        defects=out.defects,
        distance=out.distance,
        error=out.error,
        elapsed=time.perf_counter() - t0,
        notes=tuple(notes),
    )
