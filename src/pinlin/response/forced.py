"""Forced response by exact discretization of the first-order form (issue 5 part 2).

Between two samples the force is a polynomial of the time (a first-order hold,
or a cubic spline); for such an input the state at the next sample is an exact
matrix-exponential expression (Van Loan's block exponential), so the response
has no time-step error at all, whatever the step, stiff or not, damped or not,
defective or not.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..errors import AccuracyWarning, ParameterError
from ..linearization.system import LinearizedSystem
from ._inputs import check_samples, check_system, check_times, check_tolerance, check_vector
from .energy import EnergyBudget, energy_budget
from .signal import INTERPOLATIONS, SampledForce
from .state import first_order

__all__ = ["ForcedResponse", "forced_response", "sample_callable", "hold_matrices"]


@dataclass(frozen=True, repr=False, eq=False)
class ForcedResponse:
    """The response of M x'' + C x' + K x = f(t) at the output times.

    Attributes
    ----------
    system : LinearizedSystem
    t : (K,) ndarray
        Output times [s].
    x, xdot : (K, n) ndarray
        Displacements and velocities.
    f : (K, n) ndarray
        The force at the output times.
    interpolation : str
        How the force was read between samples (``"linear"`` or ``"cubic"``).
    substeps : int
        Samples of a callable force per output interval.
    t_internal, x_internal, xdot_internal, f_internal : ndarray
        The same on the internal grid (equal to the output when substeps = 1).
    distinct_steps : int
        Number of different step lengths (one block exponential each).
    exponential_defect : float
        ||exp(A h/2)^2 - exp(A h)|| / ||exp(A h)|| for the longest step h: a
        check of the matrix exponentials (rounding level when they are accurate).
    input_error : float or None
        For a callable force: max |f(t_mid) - interpolant(t_mid)| / max |f| over
        the interval midpoints, the only approximation of the method.  None for
        sampled input (then the interpolant *is* the input).
    elapsed : float
        Seconds.
    method : str
    """

    system: LinearizedSystem
    t: np.ndarray
    x: np.ndarray
    xdot: np.ndarray
    f: np.ndarray
    interpolation: str
    substeps: int
    t_internal: np.ndarray
    x_internal: np.ndarray
    xdot_internal: np.ndarray
    f_internal: np.ndarray
    distinct_steps: int
    exponential_defect: float
    input_error: float | None
    elapsed: float
    method: str

    def energy(self) -> EnergyBudget:
        """The energy budget of this response (on the internal grid), see :func:`energy_budget`."""
        return energy_budget(
            self.system, self.t_internal, self.x_internal, self.xdot_internal, self.f_internal,
            interpolation=self.interpolation,
        )

    def __repr__(self) -> str:
        inp = "" if self.input_error is None else f", input_error={self.input_error:.1e}"
        return (
            f"ForcedResponse(n={self.x.shape[1]}, points={len(self.t)}, interpolation={self.interpolation!r}, "
            f"exponential_defect={self.exponential_defect:.1e}{inp}, elapsed={self.elapsed * 1e3:.2f} ms)"
        )


def sample_callable(f, times: np.ndarray, n: int, label: str = "f") -> np.ndarray:
    """Evaluate ``f(t) -> (n,)`` at each time; check shape and finiteness."""
    out = np.empty((len(times), n))
    for i, ti in enumerate(times):
        try:
            val = np.asarray(f(float(ti)), dtype=float)
        except (TypeError, ValueError) as exc:
            raise ParameterError(label, f"calling f({ti!r}) did not give real numbers: {exc}") from None
        if val.shape != (n,):
            raise ParameterError(label, f"f(t) must return shape ({n},), got {val.shape} at t = {ti!r}")
        if not np.all(np.isfinite(val)):
            raise ParameterError(label, f"f(t) is not finite at t = {ti!r}: {val}")
        out[i] = val
    return out


def hold_matrices(A: np.ndarray, B: np.ndarray, h: float, degree: int) -> tuple[np.ndarray, list[np.ndarray]]:
    """exp(A h) and the input matrices of a polynomial hold of ``degree`` over one step h.

    With the input u(t_k + h s) = sum_j d_j (h s)^j / j!, s in [0, 1] (d_j the
    j-th derivative at the left end),

    .. math::  z(t_k + h) = e^{A h} z(t_k) + \\sum_j \\Psi_j\\, h^j d_j

    where Phi and Psi_j are blocks of the exponential of the block matrix
    [[A h, B h, 0, ...], [0, 0, I, ...], ..., [0, ..., 0]] (Van Loan 1978):
    the state of the augmented system is (z, u, du/ds, d^2u/ds^2, ...).
    """
    nz, m = B.shape
    size = nz + (degree + 1) * m
    E = np.zeros((size, size))
    E[:nz, :nz] = A * h
    E[:nz, nz : nz + m] = B * h
    for j in range(degree):
        r = nz + j * m
        E[r : r + m, r + m : r + 2 * m] = np.eye(m)
    X = scipy.linalg.expm(E)
    Phi = X[:nz, :nz]
    Psi = [X[:nz, nz + j * m : nz + (j + 1) * m] for j in range(degree + 1)]
    return Phi, Psi


def forced_response(
    sys: LinearizedSystem,
    f,
    t,
    x0=None,
    v0=None,
    *,
    interpolation: str = "linear",
    substeps: int = 1,
    input_tol: float = 1e-4,
) -> ForcedResponse:
    """Response of M x'' + (D + G) x' + (S + N) x = f(t), exact for piecewise-polynomial f.

    In first-order form z' = A z + B f (:func:`~pinlin.response.state.first_order`),
    over a step h from t_k with the input a polynomial of degree p there,

    .. math::
        z_{k+1} = e^{A h} z_k + \\sum_{j=0}^{p} \\Psi_j(h)\\, h^j f^{(j)}(t_k^+),

    with e^{Ah} and Psi_j blocks of one block exponential (:func:`hold_matrices`).
    There is no time-step error: for ``interpolation="linear"`` the result is
    the exact response to the force that is linear between the samples (a
    first-order hold), for ``"cubic"`` to its not-a-knot cubic spline.  One
    block exponential is computed per distinct step length.

    Parameters
    ----------
    sys : LinearizedSystem
    f : None, (len(t), n) array, or callable
        Generalized force [N, N m]: samples at t, or ``f(t) -> (n,)`` which is
        sampled ``substeps`` times per output interval.  None: free response.
    t : (len(t),) array
        Strictly increasing output times [s]; the initial state is at t[0].
    x0, v0 : (n,) arrays, optional
        Initial displacement and velocity; default zero.
    interpolation : {"linear", "cubic"}
        How the force is read between samples.
    substeps : int
        Samples of a callable force per output interval (>= 1); must be 1 for
        sampled force.
    input_tol : float
        An :class:`~pinlin.AccuracyWarning` is issued when the callable force's
        relative interpolation error at the interval midpoints exceeds it.

    Returns
    -------
    ForcedResponse
        ``x``, ``xdot`` (len(t), n), error figures and elapsed time.

    Raises
    ------
    ParameterError
        Wrong shapes, non-finite values, non-increasing t, a callable returning
        the wrong shape, substeps with sampled input, unknown interpolation.
    """
    t_start = time.perf_counter()
    check_system(sys)
    n = sys.n
    times = check_times(t)
    if interpolation not in INTERPOLATIONS:
        raise ParameterError("interpolation", f"expected one of {sorted(INTERPOLATIONS)}, got {interpolation!r}")
    if isinstance(substeps, bool) or not isinstance(substeps, (int, np.integer)) or substeps < 1:
        raise ParameterError("substeps", f"must be an integer >= 1, got {substeps!r}")
    input_tol = check_tolerance(input_tol, "input_tol")
    x0 = check_vector(x0, n, "x0")
    v0 = check_vector(v0, n, "v0")
    degree = INTERPOLATIONS[interpolation]

    if callable(f):
        s = np.linspace(0.0, 1.0, substeps + 1)[:-1]
        tau = np.concatenate([(times[:-1, None] + np.diff(times)[:, None] * s).ravel(), times[-1:]])
        F = sample_callable(f, tau, n)
    else:
        if substeps != 1:
            raise ParameterError("substeps", "applies to a callable force only; sampled force is used as given")
        tau = times
        F = np.zeros((len(times), n)) if f is None else check_samples(f, len(times), n, "f")
    if degree == 3 and len(tau) < 4:
        raise ParameterError("interpolation", f"'cubic' needs at least 4 force samples, got {len(tau)}")

    A, B = first_order(sys)
    Z = np.empty((len(tau), 2 * n))
    Z[0] = np.concatenate([x0, v0])
    defect = 0.0
    distinct = 0
    input_error = None
    if len(tau) > 1:
        h = np.diff(tau)
        steps, which = np.unique(h, return_inverse=True)
        distinct = len(steps)
        forcing = f is not None and np.any(F)
        taylor = SampledForce(tau, F, interpolation).taylor() if forcing else None
        Phis = []
        G = np.zeros((len(h), 2 * n))
        for j, hs in enumerate(steps):
            if forcing:
                Phi, Psi = hold_matrices(A, B, hs, degree)
                idx = np.flatnonzero(which == j)
                for p, Psi_p in enumerate(Psi):
                    G[idx] += (hs**p * taylor[idx, p]) @ Psi_p.T
            else:
                Phi = scipy.linalg.expm(A * hs)
            Phis.append(Phi)
        for k in range(len(h)):
            Z[k + 1] = Phis[which[k]] @ Z[k] + G[k]
        longest = int(np.argmax(steps))
        half = scipy.linalg.expm(A * (steps[longest] / 2))
        ref = Phis[longest]
        defect = float(np.linalg.norm(half @ half - ref) / max(np.linalg.norm(ref), np.finfo(float).tiny))
        if callable(f):
            mid = (tau[:-1] + tau[1:]) / 2
            f_mid = sample_callable(f, mid, n)
            interp = SampledForce(tau, F, interpolation)(mid)
            size = max(float(np.max(np.abs(F))), float(np.max(np.abs(f_mid))))
            input_error = float(np.max(np.abs(f_mid - interp)) / size) if size > 0 else 0.0
            if input_error > input_tol:
                warnings.warn(
                    f"forced_response: the {interpolation} interpolation of the callable force is off by "
                    f"{input_error:.1e} (relative, at interval midpoints) > input_tol {input_tol:g}; "
                    f"increase substeps (now {substeps}) or use interpolation='cubic'",
                    AccuracyWarning,
                    stacklevel=2,
                )
    out = np.arange(0, len(tau), substeps)
    return ForcedResponse(
        system=sys,
        t=times,
        x=Z[out, :n].copy(),
        xdot=Z[out, n:].copy(),
        f=F[out].copy(),
        interpolation=interpolation,
        substeps=int(substeps),
        t_internal=tau,
        x_internal=Z[:, :n],
        xdot_internal=Z[:, n:],
        f_internal=F,
        distinct_steps=distinct,
        exponential_defect=defect,
        input_error=input_error,
        elapsed=time.perf_counter() - t_start,
        method=f"exact discretization, {interpolation} hold, Van Loan block exponential",
    )
