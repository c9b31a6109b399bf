"""Forced response by exact discretization of the first-order form (theory: responses).

Between two samples the force is a polynomial of the time (a first-order hold,
or a cubic spline); for such an input the state at the next sample is an exact
matrix-exponential expression (Van Loan's block exponential), so the response
has no time-step error at all, whatever the step, stiff or not, damped or not,
defective or not.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..errors import AccuracyWarning, ParameterError, warn_user
from ..errors.deprecated import reordered_arguments
from ..linearization.system import LinearizedSystem, check_system
from ..numerics import check_integer, check_tolerance
from ..numerics.arrays import check_samples, check_times, check_vector
from ..results import Result
from .energy import EnergyBudget, energy_budget
from .sampled_force import INTERPOLATIONS, SampledForce, check_interpolation, sample_callable

__all__ = ["ForcedResponse", "forced_response", "sample_callable", "hold_matrices", "DEFAULT_INPUT_TOL"]

#: Default threshold of the AccuracyWarning on the interpolation error of a callable force:
#: a hold that misses the force by 1e-4 (relative) at the interval midpoints is a deliberate
#: choice of a coarse grid, not an accident.
DEFAULT_INPUT_TOL = 1e-4


@dataclass(frozen=True, repr=False, eq=False)
class ForcedResponse(Result):
    """The response of M x'' + C x' + K x = f(t) at the output times (times first: (K, n) arrays).

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
        The discretization: exact for the piecewise-polynomial force.
    error : float
        The headline figure: ``max(exponential_defect, input_error)`` (the
        latter counted only for a callable force), relative: the two
        approximations of the method, the matrix exponentials and the reading
        of the force between samples.

    ``to_dict()`` leaves out ``system`` and the ``*_internal`` arrays (equal to
    the outputs unless ``substeps > 1``).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])
    >>> resp = pinlin.forced_response(sys, np.linspace(0.0, 1.0, 11), lambda t: [np.sin(t)], substeps=4)
    >>> resp.x.shape, resp.t_internal.shape, resp.interpolation
    ((11, 1), (41,), 'linear')
    >>> print(f"{resp.x[-1, 0]:.6f}")
    0.123068
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

    _dict_exclude = ("system", "t_internal", "x_internal", "xdot_internal", "f_internal")

    @property
    def error(self) -> float:
        return max(float(self.exponential_defect), 0.0 if self.input_error is None else float(self.input_error))

    def energy(self) -> EnergyBudget:
        """The energy budget of this response (on the internal grid), see :func:`energy_budget`.

        Examples
        --------
        A unit step force on x'' + 0.2 x' + 4 x = f: its work is the energy stored plus the energy damped.

        >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])
        >>> budget = pinlin.forced_response(sys, np.linspace(0.0, 1.0, 11), np.ones((11, 1))).energy()
        >>> print(f"E = {budget.energy[-1]:.6f} J, force work {budget.work_force[-1]:.6f} J, "
        ...       f"damping work {budget.work_damping[-1]:.6f} J")
        E = 0.307218 J, force work 0.333312 J, damping work -0.026094 J
        """
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


def hold_matrices(A: np.ndarray, B: np.ndarray, h: float, degree: int) -> tuple[np.ndarray, list[np.ndarray]]:
    """exp(A h) and the input matrices of a polynomial hold of ``degree`` over one step h.

    With the input u(t_k + h s) = sum_j d_j (h s)^j / j!, s in [0, 1] (d_j the
    j-th derivative at the left end),

    .. math::  z(t_k + h) = e^{A h} z(t_k) + \\sum_j \\Psi_j\\, h^j d_j

    where Phi and Psi_j are blocks of the exponential of the block matrix
    [[A h, B h, 0, ...], [0, 0, I, ...], ..., [0, ..., 0]] (Van Loan 1978):
    the state of the augmented system is (z, u, du/ds, d^2u/ds^2, ...).

    Examples
    --------
    >>> import scipy.linalg
    >>> from pinlin.response.forced import hold_matrices
    >>> A, B = np.array([[0.0, 1.0], [-4.0, -0.2]]), np.array([[0.0], [1.0]])
    >>> Phi, Psi = hold_matrices(A, B, 0.1, 1)  # a first-order hold: Psi_0 and Psi_1
    >>> bool(np.allclose(Phi, scipy.linalg.expm(0.1 * A))), [p.shape for p in Psi]
    (True, [(2, 1), (2, 1)])
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


def _old_order(args: tuple, kwargs: dict) -> bool:
    """Whether a call uses the 0.3 order ``(sys, f, t, x0, v0)``: ``t`` given by keyword after a positional
    force, or a first argument that is no time grid (None, a callable, a 2-D array of samples)."""
    rest = args[1:]
    if not rest:
        return False
    if "t" in kwargs:
        return True
    first = rest[0]
    if first is None or callable(first):
        return True
    try:
        return np.ndim(first) == 2
    except ValueError:  # ragged: the checks of the new order name what is wrong
        return False


@reordered_arguments(("sys", "f", "t", "x0", "v0"), _old_order)
def forced_response(
    sys: LinearizedSystem,
    t,
    f=None,
    x0=None,
    v0=None,
    *,
    interpolation: str = "linear",
    substeps: int = 1,
    input_tol: float = DEFAULT_INPUT_TOL,
) -> ForcedResponse:
    """Response of M x'' + (D + G) x' + (S + N) x = f(t), exact for piecewise-polynomial f.

    In first-order form z' = A z + B f (:meth:`~pinlin.LinearizedSystem.first_order`),
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
    t : (len(t),) array
        Strictly increasing output times [s]; the initial state is at t[0].
    f : None, (len(t), n) array, or callable
        Generalized force [N, N m]: samples at t, or ``f(t) -> (n,)`` which is
        sampled ``substeps`` times per output interval.  None: free response.
        The 0.3 order ``(sys, f, t, x0, v0)`` still works with a
        :class:`DeprecationWarning` (``t`` second, as in :func:`free_response`).
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

    Examples
    --------
    A unit step force on x'' + 0.2 x' + 4 x = f, from rest (static limit 1/4):

    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])
    >>> t = np.linspace(0.0, 1.0, 5)
    >>> resp = pinlin.forced_response(sys, t, np.ones((5, 1)))
    >>> np.round(resp.x[:, 0], 6)
    array([0.      , 0.030103, 0.111252, 0.221579, 0.333312])
    >>> resp.distinct_steps, bool(resp.error < 1e-12)
    (1, True)
    """
    t_start = time.perf_counter()
    check_system(sys)
    n = sys.n
    times = check_times(t)
    degree = check_interpolation(interpolation)
    substeps = check_integer(substeps, "substeps", low=1)
    input_tol = check_tolerance(input_tol, "input_tol")
    x0 = check_vector(x0, n, "x0")
    v0 = check_vector(v0, n, "v0")
    tau, F = _force_samples(f, times, substeps, n)
    if degree == 3 and len(tau) < 4:
        raise ParameterError("interpolation", f"'cubic' needs at least 4 force samples, got {len(tau)}")
    forcing = f is not None and bool(np.any(F))
    Z, distinct, defect = _propagate(sys, np.concatenate([x0, v0]), tau, F, interpolation, forcing)
    input_error = None
    if callable(f) and len(tau) > 1:
        input_error = _input_error(f, tau, F, interpolation, n)
        if input_error > input_tol:
            warn_user(
                f"forced_response: the {interpolation} interpolation of the callable force is off by "
                f"{input_error:.1e} (relative, at interval midpoints) > input_tol {input_tol:g}; "
                f"increase substeps (now {substeps}) or use interpolation='cubic'",
                AccuracyWarning,
            )
    out = np.arange(0, len(tau), substeps)
    return ForcedResponse(
        system=sys,
        t=times,
        x=Z[out, :n].copy(),
        xdot=Z[out, n:].copy(),
        f=F[out].copy(),
        interpolation=interpolation,
        substeps=substeps,
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


def _force_samples(f, times: np.ndarray, substeps: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The internal time grid and the force samples on it (a callable is sampled ``substeps`` per interval)."""
    if callable(f):
        s = np.linspace(0.0, 1.0, substeps + 1)[:-1]
        tau = np.concatenate([(times[:-1, None] + np.diff(times)[:, None] * s).ravel(), times[-1:]])
        return tau, sample_callable(f, tau, n)
    if substeps != 1:
        raise ParameterError("substeps", "applies to a callable force only; sampled force is used as given")
    return times, (np.zeros((len(times), n)) if f is None else check_samples(f, len(times), n, "f"))


def _propagate(sys, z0: np.ndarray, tau: np.ndarray, F: np.ndarray, interpolation: str, forcing: bool):
    """States Z (len(tau), 2n) by the exact step maps, the number of distinct steps and the exponential check."""
    A, B, _ = sys.first_order()
    Z = np.empty((len(tau), z0.size))
    Z[0] = z0
    if len(tau) < 2:
        return Z, 0, 0.0
    degree = INTERPOLATIONS[interpolation]
    h = np.diff(tau)
    steps, which = np.unique(h, return_inverse=True)
    taylor = SampledForce(tau, F, interpolation).taylor() if forcing else None
    Phis = []
    G = np.zeros((len(h), z0.size))
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
    # exp(A h/2)^2 against exp(A h) for the longest step: rounding level when the exponentials are accurate
    longest = int(np.argmax(steps))
    half = scipy.linalg.expm(A * (steps[longest] / 2))
    ref = Phis[longest]
    defect = float(np.linalg.norm(half @ half - ref) / max(np.linalg.norm(ref), np.finfo(float).tiny))
    return Z, len(steps), defect


def _input_error(f, tau: np.ndarray, F: np.ndarray, interpolation: str, n: int) -> float:
    """max |f(t_mid) - interpolant(t_mid)| / max |f| over the interval midpoints."""
    mid = (tau[:-1] + tau[1:]) / 2
    f_mid = sample_callable(f, mid, n)
    interp = SampledForce(tau, F, interpolation)(mid)
    size = max(float(np.max(np.abs(F))), float(np.max(np.abs(f_mid))))
    return float(np.max(np.abs(f_mid - interp)) / size) if size > 0 else 0.0
