"""Floquet analysis of linear T-periodic equations: :func:`floquet_from_first_order` (y' = A(t) y) and
:func:`floquet_analysis_matrices` (M(t) x'' + C(t) x' + K(t) x = 0) (SPEC section 13).

The pipeline: step transitions by Gauss-Legendre collocation with step doubling (:mod:`.collocation`),
grouped into well-conditioned segments; multipliers and periodic eigenvectors of the segment product from the
lifted block-cyclic matrix (:mod:`.cyclic`); error bounds (:mod:`.bounds`); frequencies by harmonic content
(:mod:`.harmonics`); the verdict (:mod:`.floquet_verdict`).
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import ParameterError, SingularMassError
from ..numerics.arrays import readonly
from .bounds import multiplier_bounds
from .collocation import integrate_transitions
from .cyclic import cyclic_eigen
from .floquet_verdict import floquet_verdict
from .harmonics import harmonic_content
from .inputs import check_period, coefficient
from .result import FloquetAnalysis

__all__ = ["floquet_from_first_order", "floquet_analysis_matrices", "STRUCTURE_TOLERANCE"]

#: Relative size [units of eps] below which an asymmetric part of K, a symmetric part of C or a change of
#: M or C over time counts as rounding in the conservative-structure test.
STRUCTURE_TOLERANCE = 100.0

_EPS = float(np.finfo(float).eps)


def _check_options(rtol, stages, growth, harmonics, safety):
    checks = (("rtol", rtol, 1e-16 <= rtol < 1e-2, "in [1e-16, 1e-2)"),
              ("stages", stages, isinstance(stages, (int, np.integer)) and 2 <= stages <= 12, "an int in 2..12"),
              ("growth", growth, 10.0 <= growth <= 1e8, "in [10, 1e8]"),
              ("harmonics", harmonics, isinstance(harmonics, (int, np.integer)) and harmonics >= 0, "an int >= 0"),
              ("safety", safety, 1.0 <= safety < 1e6, "in [1, 1e6)"))
    for name, value, ok, expected in checks:
        if not (isinstance(value, (int, float, np.integer, np.floating)) and np.isfinite(value) and ok):
            raise ParameterError(name, f"expected {expected}, got {value!r}")


def _trivial_mask(mu: np.ndarray, autonomous: bool, conservative: bool) -> tuple[np.ndarray, str]:
    """An autonomous orbit's multiplier 1 (two of them, the Jordan pair, when conservative)."""
    mask = np.zeros(mu.size, bool)
    if not autonomous:
        return mask, ""
    count = min(2 if conservative else 1, mu.size)
    mask[np.argsort(np.abs(mu - 1))[:count]] = True
    shown = ", ".join(f"{complex(x):.6g}" for x in mu[mask])
    return mask, f"; trivial multiplier(s) of the autonomous orbit set apart: {shown}"


def floquet_from_first_order(A, period, *, rtol: float = 1e-13, stages: int = 6, growth: float = 1e3,
                             harmonics: int = 16, autonomous: bool = False, symplectic_form=None, rows=None,
                             safety: float = 10.0, max_steps: int = 20000,
                             max_time: float = 600.0) -> FloquetAnalysis:
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

    Raises
    ------
    ParameterError
        A not callable nor a square matrix, values of the wrong shape or non-finite, bad period or option.
    IntegrationBudgetError, IntegrationError
        The integration could not meet ``rtol`` within the budget.
    """
    start = time.perf_counter()
    T = check_period(period)
    _check_options(rtol, stages, growth, harmonics, safety)
    func, shape = coefficient("A", A)
    m = shape[0]
    form = None
    if symplectic_form is not None:
        form = np.asarray(symplectic_form, dtype=float)
        if form.shape != (m, m) or not np.all(np.isfinite(form)):
            raise ParameterError("symplectic_form", f"expected a finite ({m}, {m}) array, got shape {form.shape}")
    options = dict(rtol=rtol, stages=int(stages), growth=growth, max_steps=max_steps, max_time=max_time)
    return _analyse(func, T, m, lambda: form, options, harmonics=int(harmonics), rows=rows,
                    autonomous=autonomous, safety=safety, start=start, what="first-order A(t)")


def _analyse(func, T, m, form_after, options, *, harmonics, rows, autonomous, safety, start, what):
    """The pipeline on a checked A(t); ``form_after()`` gives Omega (or None) once the integration sampled A."""
    tr = integrate_transitions(func, T, m, **options)
    eig = cyclic_eigen(tr.factors)
    bound, b_int, b_eig = multiplier_bounds(tr, eig)
    freq, content, dominant = harmonic_content(tr, eig, T, harmonics=harmonics, rows=rows)
    form = form_after()
    trivial, note = _trivial_mask(eig.multipliers, autonomous, form is not None)
    stability = floquet_verdict(eig.multipliers, bound, trivial=trivial, form=form, vectors=eig.right[:, 0, :].T,
                                safety=safety, trivial_note=note)
    monodromy = np.eye(m)
    for factor in tr.factors:
        monodromy = factor @ monodromy
    step_errors = np.array([s.error for s in tr.steps])
    rel = step_errors / np.array([np.linalg.norm(s.P, 2) for s in tr.steps])
    times = np.array([s.t0 for s in tr.steps] + [T])
    stages = options["stages"]
    method = (f"Floquet ({what}): Gauss-Legendre collocation s = {stages} (order {2 * stages}) with step "
              f"doubling, rtol = {options['rtol']:g}; multipliers of the {len(tr.factors)}-segment product from "
              f"the lifted block-cyclic eigenproblem")
    return FloquetAnalysis(
        readonly(eig.multipliers), readonly(bound), readonly(b_int), readonly(b_eig),
        readonly(np.log(eig.multipliers.astype(complex)) / T), readonly(freq), readonly(content),
        readonly(dominant), readonly(trivial), form is not None, stability, readonly(monodromy), T,
        len(tr.factors), len(tr.steps), tr.evaluations, readonly(times), readonly(step_errors),
        float(rel.max()), time.perf_counter() - start, method)


def _structure(M, C, K) -> dict:
    """Relative defects of the conservative structure at one time: asym(M), sym(C), asym(K)."""
    scale = lambda X: max(float(np.linalg.norm(X)), np.finfo(float).tiny)  # noqa: E731
    big = scale(M) + scale(C) + scale(K)
    return {"M": np.linalg.norm(M - M.T) / scale(M), "C": np.linalg.norm(C + C.T) / big,
            "K": np.linalg.norm(K - K.T) / scale(K)}


class _SecondOrder:
    """A(t) = [[0, I], [-M^-1 K, -M^-1 C]] from checked M, C, K, recording the conservative-structure defects."""

    def __init__(self, fM, fC, fK, n):
        self.fM, self.fC, self.fK, self.n = fM, fC, fK, n
        self.M0, self.C0 = fM(0.0), fC(0.0)
        self.defect = 0.0

    def __call__(self, t: float) -> np.ndarray:
        M, C, K = self.fM(t), self.fC(t), self.fK(t)
        n = self.n
        try:
            X = np.linalg.solve(M, np.hstack([K, C]))
        except np.linalg.LinAlgError:
            raise SingularMassError(f"M is singular at t = {t:.6g} s", ()) from None
        d = _structure(M, C, K)
        drift = max(np.linalg.norm(M - self.M0) / max(np.linalg.norm(self.M0), 1e-300),
                    np.linalg.norm(C - self.C0) / (np.linalg.norm(M) + np.linalg.norm(C) + np.linalg.norm(K)))
        self.defect = max(self.defect, d["M"], d["C"], d["K"], drift)
        A = np.zeros((2 * n, 2 * n))
        A[:n, n:] = np.eye(n)
        A[n:, :n], A[n:, n:] = -X[:, :n], -X[:, n:]
        return A


def floquet_analysis_matrices(M, C, K, period, *, rtol: float = 1e-13, stages: int = 6, growth: float = 1e3,
                              harmonics: int = 16, autonomous: bool = False, safety: float = 10.0,
                              structure_tolerance: float = STRUCTURE_TOLERANCE, max_steps: int = 20000,
                              max_time: float = 600.0) -> FloquetAnalysis:
    """Floquet analysis of M(t) x'' + C(t) x' + K(t) x = 0 with T-periodic M, C, K.

    In first-order form y = (x, x'), A = [[0, I], [-M^-1 K, -M^-1 C]] (solves with M, no inverse).  The
    system counts as conservative when, at every time the integrator sampled, M is symmetric and constant,
    C = G is skew and constant and K symmetric, each within ``structure_tolerance`` eps (relative): then
    Phi(T) is symplectic for Omega = [[G, M], [-M, 0]] (y1^T Omega y2 = x1^T M v2 - v1^T M x2 + x1^T G x2,
    the canonical form with p = M v + G x / 2) and the verdict uses it.  A time-varying M or G with the
    matching D = M', N = G' / 2 (a Lagrangian variational equation) is conservative too but is not detected.
    Harmonic content counts the position components.  Other parameters as :func:`floquet_from_first_order`.

    Parameters
    ----------
    M, C, K : callable or array_like
        t [s] -> (n, n) real arrays (mass [kg], damping+gyroscopic [N s/m], stiffness+circulatory [N/m] or
        the rotational units), or constant arrays; C and K may be None (zero).
    period : float
        T [s].

    Raises
    ------
    ParameterError
        Bad callables, shapes, values, period or options (the argument is named).
    SingularMassError
        M(t) singular at a sampled time.
    IntegrationBudgetError, IntegrationError
        As :func:`floquet_from_first_order`.
    """
    start = time.perf_counter()
    T = check_period(period)
    _check_options(rtol, stages, growth, harmonics, safety)
    fM, shape = coefficient("M", M)
    n = shape[0]
    zero = np.zeros((n, n))
    fC, _ = coefficient("C", zero if C is None else C, shape)
    fK, _ = coefficient("K", zero if K is None else K, shape)
    A = _SecondOrder(fM, fC, fK, n)
    form = np.block([[A.C0, A.M0], [-A.M0, zero]])
    options = dict(rtol=rtol, stages=int(stages), growth=growth, max_steps=max_steps, max_time=max_time)
    return _analyse(A, T, 2 * n, lambda: form if A.defect <= structure_tolerance * _EPS else None, options,
                    harmonics=int(harmonics), rows=np.arange(n), autonomous=autonomous, safety=safety,
                    start=start, what="M, C, K")
