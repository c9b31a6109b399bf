"""Floquet analysis of linear T-periodic equations: :func:`floquet_from_first_order` (y' = A(t) y) and
:func:`floquet_analysis_matrices` (M(t) x'' + C(t) x' + K(t) x = 0) (theory: Floquet).

The pipeline: step transitions by Gauss-Legendre collocation with step doubling (:mod:`.collocation`),
grouped into well-conditioned segments; multipliers and periodic eigenvectors of the segment product from the
lifted block-cyclic matrix (:mod:`.cyclic`); error bounds (:mod:`.bounds`); frequencies by harmonic content
(:mod:`.harmonics`); the verdict (:mod:`.floquet_verdict`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..errors.deprecated import renamed_keywords
from ..numerics.arrays import readonly
from .bounds import jordan_bound, monodromy_perturbation, multiplier_bounds, relative_condition
from .cyclic import cyclic_eigen
from .floquet_verdict import floquet_verdict
from .harmonics import harmonic_content
from .inputs import check_period, coefficient
from .options import (GROWTH, HARMONICS, MAX_SAMPLES, MAX_STEPS, MAX_TIME, RTOL, SAFETY, SAMPLING, STAGES,
                      STRUCTURE_TOL, FloquetOptions)
from .result import FloquetAnalysis
from .sampled import Integrated, first_order_transitions, second_order_transitions

__all__ = ["floquet_from_first_order", "floquet_analysis_matrices", "SYMPLECTIC_TOL"]

#: Relative defect ||Phi^T Omega Phi - Omega|| / (||Phi||^2 ||Omega||) allowed for ``conservative=True``
#: (the integration's own error is about rtol per step; a damping of 1e-8 relative already exceeds it).
SYMPLECTIC_TOL = 1e-9

_EPS = float(np.finfo(float).eps)


def _trivial_mask(mu: np.ndarray, autonomous: bool, conservative: bool) -> tuple[np.ndarray, str]:
    """An autonomous orbit's multiplier 1 (two of them, the Jordan pair, when conservative)."""
    mask = np.zeros(mu.size, bool)
    if not autonomous:
        return mask, ""
    count = min(2 if conservative else 1, mu.size)
    mask[np.argsort(np.abs(mu - 1))[:count]] = True
    shown = ", ".join(f"{complex(x):.6g}" for x in mu[mask])
    return mask, f"; trivial multiplier(s) of the autonomous orbit set apart: {shown}"


def floquet_from_first_order(A, period, *, rtol: float = RTOL, stages: int = STAGES, growth: float = GROWTH,
                             harmonics: int = HARMONICS, autonomous: bool = False, symplectic_form=None,
                             rows=None, safety: float = SAFETY, max_steps: int = MAX_STEPS,
                             max_time: float = MAX_TIME, sampling: str = SAMPLING,
                             max_samples: int = MAX_SAMPLES) -> FloquetAnalysis:
    """Floquet multipliers, exponents, frequencies and verdict of y' = A(t) y with A T-periodic.

    .. math::  \\Phi' = A(t)\\,\\Phi,\\quad \\Phi(0) = I, \\qquad \\mu_k \\in \\mathrm{eig}\\,\\Phi(T),
               \\qquad \\lambda_k = \\log(\\mu_k)/T.

    Parameters
    ----------
    A : callable or array_like
        t [s] -> (m, m) real array [1/s] (or a constant array).
    period : float
        T [s].
    rtol : float
        Local error per step relative to the step transition's 2-norm.
    stages : int
        Gauss-Legendre stages s (order 2 s).
    growth : float
        Condition number at which a segment closes.
    harmonics : int
        J of the reported harmonic content (j = -J..J).
    autonomous : bool
        The system is an autonomous orbit's variational equation: set the multiplier 1 apart.
    symplectic_form : (m, m) array or None
        Omega with Phi(T)^T Omega Phi(T) = Omega, when the caller knows the system conservative.
    rows : index array or None
        Components whose energy counts in the harmonic content (None: all).
    safety : float
        Factor on the bounds before they decide the verdict.
    max_steps, max_time : int, float
        Integration budget (steps, wall time [s]).
    sampling : {"auto", "spectral", "nodes"}
        "spectral": A sampled at equispaced times and replaced by its trigonometric interpolant, whose
        measured error enters the bounds (:mod:`pinlin.periodic.sampling`); "nodes": A evaluated at every
        collocation node; "auto": spectral where the interpolant converges, else nodes.
    max_samples : int
        Most samples per period the interpolant may use (16..65536).

    Raises
    ------
    ParameterError
        A not callable nor a square matrix, values of the wrong shape or non-finite, bad period or option.
    IntegrationBudgetError, IntegrationError
        The integration could not meet ``rtol`` within the budget.
    SamplingError
        ``sampling="spectral"`` and the interpolant did not converge within ``max_samples``.

    Examples
    --------
    The damped Mathieu equation in first-order form; Liouville's formula gives det Phi(T) = exp(-0.1 T):

    >>> A = lambda t: [[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), -0.1]]
    >>> flo = pinlin.floquet_from_first_order(A, 2 * np.pi)
    >>> print(flo.stability.kind, f"{np.prod(flo.multipliers).real:.6f}", f"{np.exp(-0.1 * 2 * np.pi):.6f}")
    asymptotically_stable 0.533488 0.533488
    """
    start = time.perf_counter()
    T = check_period(period)
    options = FloquetOptions(rtol=rtol, stages=stages, growth=growth, harmonics=harmonics, safety=safety,
                             max_steps=max_steps, max_time=max_time, sampling=sampling, max_samples=max_samples)
    func, shape = coefficient("A", A)
    m = shape[0]
    form = None
    if symplectic_form is not None:
        form = np.asarray(symplectic_form, dtype=float)
        if form.shape != (m, m) or not np.all(np.isfinite(form)):
            raise ParameterError("symplectic_form", f"expected a finite ({m}, {m}) array, got shape {form.shape}")
    if rows is not None:
        rows = np.asarray(rows)
        if rows.ndim != 1 or rows.size == 0 or rows.dtype.kind not in "iu" or rows.min() < 0 or rows.max() >= m:
            raise ParameterError("rows", f"expected a non-empty 1-d array of indices in 0..{m - 1}, got {rows!r}")
    integrated = first_order_transitions(func, T, m, options)
    return _analyse(integrated, T, m, lambda monodromy: form, options, rows=rows, autonomous=autonomous,
                    start=start, what="first-order A(t)")


def _analyse(integrated: Integrated, T, m, form_after, options: FloquetOptions, *, rows, autonomous, start, what,
             orbit_errors=None):
    """The pipeline on the integrated transitions; ``form_after(monodromy)`` gives Omega (or None);
    ``orbit_errors(tr, eig, monodromy)``: the reference orbit's part of the bound and per-step norm bounds
    on its dA (:func:`~.orbit_error.orbit_bound`), or None."""
    tr = integrated.transitions
    eig = cyclic_eigen(tr.factors)
    monodromy = np.eye(m)
    for factor in tr.factors:
        monodromy = factor @ monodromy
    form = form_after(monodromy)
    trivial, note = _trivial_mask(eig.multipliers, autonomous, form is not None)
    bound, b_int, b_eig, b_orbit = multiplier_bounds(tr, eig)
    norms = None
    if orbit_errors is not None:
        b_orbit, norms = orbit_errors(tr, eig, monodromy)
        bound = bound + b_orbit
    if np.count_nonzero(trivial) == 2:      # the Jordan block of a conservative family: a square-root bound
        jordan = jordan_bound(monodromy, eig.multipliers, trivial, monodromy_perturbation(tr, norms))
        bound[trivial] = np.maximum(bound[trivial], jordan)
    stability = floquet_verdict(eig.multipliers, bound, trivial=trivial, form=form, vectors=eig.right[:, 0, :].T,
                                condition=relative_condition(tr, eig), safety=options.safety, trivial_note=note)
    step_errors = np.array([s.error for s in tr.steps])
    rel = step_errors / np.array([s.norm for s in tr.steps])
    times = np.array([s.t0 for s in tr.steps] + [T])
    stages = options.stages
    method = (f"Floquet ({what}): {integrated.description}; Gauss-Legendre collocation s = {stages} (order "
              f"{2 * stages}) with step doubling, rtol = {options.rtol:g}; multipliers of the "
              f"{len(tr.factors)}-segment product from the lifted block-cyclic eigenproblem")
    return FloquetAnalysis(
        multipliers=readonly(eig.multipliers), error_bound=readonly(bound), integration_bound=readonly(b_int),
        eigensolver_bound=readonly(b_eig), orbit_bound=readonly(b_orbit),
        exponents=readonly(np.log(eig.multipliers.astype(complex)) / T),
        trivial=readonly(trivial), conservative=form is not None, stability=stability,
        monodromy=readonly(monodromy), period=T, segments=len(tr.factors), steps=len(tr.steps),
        evaluations=integrated.evaluations, step_times=readonly(times), step_errors=readonly(step_errors),
        integration_error=float(rel.max()), elapsed=time.perf_counter() - start, method=method,
        deferred=_DeferredHarmonics(tr, eig, T, options.harmonics, rows))


@dataclass(frozen=True, eq=False)
class _DeferredHarmonics:
    """What a :class:`FloquetAnalysis` keeps to form its frequencies and harmonic content on first access
    (immutable: threads that form them at once compute the same values)."""

    transitions: object
    eig: object
    period: float
    harmonics: int
    rows: np.ndarray | None

    def __call__(self) -> tuple:
        freq, content, dominant = harmonic_content(self.transitions, self.eig, self.period,
                                                   harmonics=self.harmonics, rows=self.rows)
        return readonly(freq), readonly(content), readonly(dominant)


def _symplectic_defect(monodromy: np.ndarray, form: np.ndarray) -> float:
    """||Phi^T Omega Phi - Omega|| / (||Phi||^2 ||Omega||) (2-norms)."""
    defect = np.linalg.norm(monodromy.T @ form @ monodromy - form, 2)
    return float(defect / (np.linalg.norm(monodromy, 2) ** 2 * np.linalg.norm(form, 2)))


def _check_symplectic(monodromy: np.ndarray, form: np.ndarray) -> None:
    """ParameterError unless ||Phi^T Omega Phi - Omega|| <= SYMPLECTIC_TOL ||Phi||^2 ||Omega||."""
    defect = _symplectic_defect(monodromy, form)
    if not defect <= SYMPLECTIC_TOL:
        raise ParameterError("conservative", f"the monodromy is not symplectic for Omega = [[G, M], [-M, 0]] at "
                                             f"t = 0 (relative defect {defect:.2e} > {SYMPLECTIC_TOL:g}):"
                                             f" the system is not conservative")


@renamed_keywords(structure_tolerance="structure_tol")
def floquet_analysis_matrices(M, C, K, period, *, rtol: float = RTOL, stages: int = STAGES, growth: float = GROWTH,
                              harmonics: int = HARMONICS, autonomous: bool = False,
                              conservative: bool | None = None, safety: float = SAFETY,
                              structure_tol: float = STRUCTURE_TOL, max_steps: int = MAX_STEPS,
                              max_time: float = MAX_TIME, sampling: str = SAMPLING,
                              max_samples: int = MAX_SAMPLES) -> FloquetAnalysis:
    """Floquet analysis of M(t) x'' + C(t) x' + K(t) x = 0 with T-periodic M, C, K.

    In first-order form y = (x, x'), A = [[0, I], [-M^-1 K, -M^-1 C]] (solves with M, no inverse).  The
    system counts as conservative when, at every time sampled (the samples of the interpolant, or the
    integrator's nodes), M is symmetric and constant,
    C = G is skew and constant and K symmetric, each within ``structure_tol`` eps (relative): then
    Phi(T) is symplectic for Omega = [[G, M], [-M, 0]] (y1^T Omega y2 = x1^T M v2 - v1^T M x2 + x1^T G x2,
    the canonical form with p = M v + G x / 2) and the verdict uses it.  A time-varying M or G with the
    matching D = M', N = G' / 2 (the variational equation of a Lagrangian system: C = M' + F - F^T,
    K = S + F') is conservative too, with the same Omega at t = 0: where the coefficients were sampled
    (their interpolant exact to rounding) the identities sym(C) = M' and skew(K) = skew(C)' / 2 are tested
    on the interpolant's derivatives at every sample (a trigonometric polynomial of degree below N that
    vanishes at 2 N points vanishes), confirmed by Phi^T Omega Phi = Omega to :data:`SYMPLECTIC_TOL`;
    evaluated at the nodes there are no derivatives: pass ``conservative=True`` (checked the same way).
    Harmonic content counts the position components.  Other parameters as :func:`floquet_from_first_order`.

    Parameters
    ----------
    M, C, K : callable or array_like
        t [s] -> (n, n) real arrays (mass [kg], damping+gyroscopic [N s/m], stiffness+circulatory [N/m] or
        the rotational units), or constant arrays; C and K may be None (zero).
    period : float
        T [s].
    conservative : bool or None
        None: detect the constant-M structure above; True: the caller asserts a Lagrangian (conservative)
        system; False: never use structure in the verdict.
    rtol, stages, growth, harmonics, autonomous, safety, max_steps, max_time, sampling, max_samples
        As :func:`floquet_from_first_order` (M, C and K are sampled together: one evaluation is one triple).
    structure_tol : float
        Relative threshold, in units of eps, of the tests of the conservative structure
        (``structure_tolerance`` is its deprecated spelling).

    Raises
    ------
    ParameterError
        Bad callables, shapes, values, period or options (the argument is named); ``conservative=True`` with a
        monodromy that is not symplectic for Omega.
    SingularMassError
        M(t) singular at a sampled time.
    IntegrationBudgetError, IntegrationError, SamplingError
        As :func:`floquet_from_first_order`.

    Examples
    --------
    Mathieu's equation x'' + (1.3 + 0.4 cos t) x = 0, conservative and stable:

    >>> flo = pinlin.floquet_analysis_matrices([[1.0]], None, lambda t: [[1.3 + 0.4 * np.cos(t)]], 2 * np.pi)
    >>> print(flo.stability.kind, flo.conservative, np.round(np.abs(flo.multipliers), 6))
    marginally_stable True [1. 1.]
    """
    start = time.perf_counter()
    fM, shape = coefficient("M", M)
    n = shape[0]
    zero = np.zeros((n, n))
    fC, _ = coefficient("C", zero if C is None else C, shape)
    fK, _ = coefficient("K", zero if K is None else K, shape)
    options = FloquetOptions(rtol=rtol, stages=stages, growth=growth, harmonics=harmonics, safety=safety,
                             max_steps=max_steps, max_time=max_time, sampling=sampling, max_samples=max_samples,
                             structure_tol=structure_tol)
    return floquet_second_order(lambda t: np.stack([fM(t), fC(t), fK(t)]), lambda: (fM, fC, fK), n, period,
                                options, start=start, autonomous=autonomous, conservative=conservative)


def floquet_second_order(triple, fallback, n: int, period, options: FloquetOptions, *, start: float,
                         autonomous: bool = False, conservative: bool | None = None,
                         what: str = "M, C, K", orbit_errors=None) -> FloquetAnalysis:
    """:func:`floquet_analysis_matrices` on validated coefficients: ``triple(t)`` -> (3, n, n) stacked M, C, K
    (one evaluation), ``fallback()`` -> (M, C, K) checked callables for the integrator's nodes; ``start`` the
    ``time.perf_counter()`` the run's elapsed time counts from; ``orbit_errors`` as ``_analyse`` takes it
    (a scene's orbit)."""
    T = check_period(period)
    if conservative not in (None, True, False):
        raise ParameterError("conservative", f"expected None, True or False, got {conservative!r}")
    M0, C0, _ = triple(0.0)
    form = np.block([[(C0 - C0.T) / 2, M0], [-M0, np.zeros((n, n))]])
    integrated = second_order_transitions(triple, fallback, T, n, options)
    structure_tol = options.structure_tol * _EPS

    def form_after(monodromy):
        if conservative is None:
            if integrated.defect <= structure_tol:
                return form
            # a time-varying Lagrangian system (from the interpolant's derivatives), confirmed on Phi(T)
            if integrated.lagrangian <= structure_tol and _symplectic_defect(monodromy, form) <= SYMPLECTIC_TOL:
                return form
            return None
        if conservative:
            _check_symplectic(monodromy, form)
            return form
        return None

    return _analyse(integrated, T, 2 * n, form_after, options, rows=np.arange(n), autonomous=autonomous,
                    start=start, what=what, orbit_errors=orbit_errors)
