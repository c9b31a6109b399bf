"""Frequency response ``H(i omega)`` of selected inputs and outputs (SPEC section 6, paper Sec. 12).

The steady state of ``M x'' + C x' + K x = Re(F exp(i omega t))`` is
``x(t) = Re(H(i omega) F exp(i omega t))``.  Inputs and outputs are coordinates
(generalized forces and displacements of ``sys.dof_names``); the data follow
python-control's convention: ``response[output, input, frequency]``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from ..adjoint._util import check_system, dof_indices
from .engine import METHODS, check_modes, flexibility_columns

__all__ = ["FrequencyResponse", "frequency_response"]


@dataclass(frozen=True, repr=False, eq=False)
class FrequencyResponse:
    """``H(i omega)`` for chosen outputs and inputs, python-control's shape convention.

    ``mag, phase, omega = resp`` unpacks like python-control's
    ``frequency_response``.

    Attributes
    ----------
    response : (n_outputs, n_inputs, n_frequencies) complex ndarray
        ``H(i omega)[output, input]`` [m/N, rad/(N m), ...].
    omega : (n_frequencies,) ndarray
        Angular frequencies [rad/s].
    outputs, inputs : (k,) int ndarray
        Coordinate indices.
    output_names, input_names : tuple of str
    method : str
        "direct" or "modal".
    residual : (n_frequencies,) ndarray or None
        Per frequency, ``||L(i w) H_c - I_c|| / (||L(i w)|| ||H_c||)`` over the input
        columns c (all n rows): the defect of the equation (SPEC section 8).
        None when the check was skipped.
    error : float or None
        ``max(residual)``.
    elapsed : float
        Seconds.
    notes : tuple of str
    """

    response: np.ndarray
    omega: np.ndarray
    outputs: np.ndarray
    inputs: np.ndarray
    output_names: tuple[str, ...]
    input_names: tuple[str, ...]
    method: str
    residual: np.ndarray | None
    error: float | None
    elapsed: float
    notes: tuple[str, ...] = field(default=())

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

    def __iter__(self):
        return iter((self.magnitude, self.phase, self.omega))

    def __repr__(self) -> str:
        err = "unchecked" if self.error is None else f"{self.error:.1e}"
        return (
            f"FrequencyResponse(outputs={len(self.outputs)}, inputs={len(self.inputs)}, "
            f"frequencies={len(self.omega)}, method={self.method!r}, error={err}, elapsed={self.elapsed:.3g} s)"
        )


def frequency_response(
    sys,
    omega,
    inputs=None,
    outputs=None,
    *,
    method: str = "direct",
    modes=None,
    check: bool = True,
) -> FrequencyResponse:
    """Frequency response ``H(i omega) = L(i omega)^-1`` from ``inputs`` to ``outputs``.

    .. math::
        H(i\\omega) = (-\\omega^2 M + i\\omega C + K)^{-1}
        = \\sum_k \\frac{x_k y_k^T}{i\\omega - \\lambda_k}

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
        "direct": one LU factorization of ``L(i omega)`` per frequency, O(n^3)
        each.  "modal": the spectral sum over the 2n Lancaster-normalized modes
        of :func:`pinlin.modal_analysis`, O(n) per input-output pair and
        frequency after the eigensolution; needs a simple dynamic stiffness.
    modes : Modes, optional
        A precomputed modal analysis for ``method="modal"``.
    check : bool
        Compute the residual of the equation per frequency (costs O(n^2) per
        input and frequency; on by default).

    Returns
    -------
    FrequencyResponse

    Raises
    ------
    ParameterError
        ``omega`` not a finite real 1-D array, unknown inputs or outputs, bad
        method, a frequency at an eigenvalue on the imaginary axis.
    NotSimpleError
        ``method="modal"`` and the dynamic stiffness is not simple.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    try:
        w = np.asarray(omega)
    except (TypeError, ValueError):
        raise ParameterError("omega", "expected real angular frequencies [rad/s]") from None
    if w.dtype == object or not np.issubdtype(w.dtype, np.number) or np.iscomplexobj(w) or w.dtype == bool:
        raise ParameterError("omega", f"expected real angular frequencies [rad/s], got dtype {w.dtype}")
    if w.ndim > 1:
        raise ParameterError("omega", f"expected a scalar or a 1-D array, got shape {w.shape}")
    w = np.atleast_1d(w).astype(float)
    if w.size == 0:
        raise ParameterError("omega", "expected at least one frequency")
    if not np.all(np.isfinite(w)):
        raise ParameterError("omega", f"must be finite; entry {int(np.flatnonzero(~np.isfinite(w))[0])} is not")
    ins = dof_indices(sys, inputs, "inputs")
    outs = dof_indices(sys, outputs, "outputs")
    if method not in METHODS:
        raise ParameterError("method", f"expected one of {METHODS}, got {method!r}")
    notes = []
    if method == "modal":
        modes = check_modes(sys, modes)
        notes.append(f"modes from {getattr(modes, 'method', 'modal_analysis')!s}")
    H, residual = flexibility_columns(sys, 1j * w, rows=outs, cols=ins, method=method, modes=modes, check=check)
    response = np.moveaxis(H, 0, -1)
    return FrequencyResponse(
        response=response,
        omega=w,
        outputs=outs,
        inputs=ins,
        output_names=tuple(sys.dof_names[i] for i in outs),
        input_names=tuple(sys.dof_names[i] for i in ins),
        method=method,
        residual=residual,
        error=None if residual is None else float(np.max(residual)),
        elapsed=time.perf_counter() - t0,
        notes=tuple(notes),
    )
