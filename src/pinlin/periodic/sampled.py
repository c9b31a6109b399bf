"""The step transitions of a Floquet analysis, from coefficients sampled once per period or evaluated at every
collocation node (theory: Floquet).

``sampling="spectral"``: the coefficients (A, or M, C and K together) are sampled at equispaced times and
replaced by their trigonometric interpolant (:mod:`.sampling`), whose measured error enters every step's
error bound (:mod:`.bounds`); the interpolant is integrated on a grid refined in rounds
(:mod:`.collocation_grid`).  ``"nodes"``: the coefficients are evaluated at every node of the step-doubling
integrator (:mod:`.collocation`), three per stage and step.  ``"auto"`` (the default) samples first and
evaluates at the nodes when the interpolant does not converge.  Exact trigonometric polynomials (a turning
inertia, an effective gravity g + z''(t)) take 16 samples where the nodes take hundreds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import AccuracyWarning, ParameterError, SamplingError, warn_user
from ..linearization.state_form import first_order_form
from .collocation import Transitions, integrate_transitions
from .collocation_grid import integrate_on_grid
from .jumps import find_jumps
from .options import FloquetOptions
from .sampling import PeriodicSamples, group_norms, sample_periodic
from .second_order import SecondOrderA, lagrangian_defect, structure_defect

__all__ = ["Integrated", "first_order_transitions", "second_order_transitions", "second_order_scales",
           "counted_errors", "block_errors", "SAMPLING_FLOOR"]

#: Smallest relative interpolation tolerance, in units of eps: the samples' own rounding (a Pinocchio pass
#: is accurate to a few eps of its norms) must not decide whether the interpolant converged.
SAMPLING_FLOOR = 64.0

_EPS = float(np.finfo(float).eps)


@dataclass(frozen=True)
class Integrated:
    """Transitions with how they were made: ``evaluations`` (coefficient calls), ``samples`` (the
    interpolant's, or None when the nodes were used), ``defect`` (the conservative-structure defect seen, for
    second-order systems: constant M and G), ``lagrangian`` (the defect of the identities of a time-varying
    Lagrangian system, from the interpolant's derivatives; nan where not measured), ``description`` (for the
    result's ``method``).

    Examples
    --------
    >>> from pinlin.periodic.options import FloquetOptions
    >>> from pinlin.periodic.sampled import first_order_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])
    >>> integrated = first_order_transitions(A, 2 * np.pi, 2, FloquetOptions())
    >>> print(integrated.evaluations, integrated.samples is not None, integrated.description[:32])
    16 True coefficients from 16 equispaced
    """

    transitions: Transitions
    evaluations: int
    samples: PeriodicSamples | None
    defect: float
    description: str
    lagrangian: float = float("nan")


def second_order_scales(samples: np.ndarray) -> np.ndarray:
    """Scales of the M, C, K groups: ||M||, max(||C||, sqrt(||M|| ||K||)), ||K|| (largest Frobenius norms
    over the samples).  sqrt(||M|| ||K||) has the units of C: a light damping is computed from terms of that
    size (the gyroscopic and Coriolis parts of a moving support), whose rounding is not an error of the
    interpolant.

    Examples
    --------
    >>> from pinlin.periodic.sampled import second_order_scales
    >>> samples = np.array([[[[4.0]], [[0.0]], [[9.0]]]])       # one sample: M = 4, C = 0, K = 9
    >>> second_order_scales(samples)
    array([4., 6., 9.])
    """
    M, C, K = group_norms(samples)
    return np.array([M, max(C, np.sqrt(M * K)), K])


@dataclass(frozen=True)
class _Sampled:
    """What the sampling found: the interpolant (None on the nodes path), and where it did not converge the
    jumps located in the samples (:mod:`.jumps`), the step boundaries they need and the calls the search made."""

    samples: PeriodicSamples | None
    jumps: tuple = ()
    breaks: tuple = ()
    calls: int = 0


def _sample(F, T, options: FloquetOptions, names, scales=group_norms) -> _Sampled:
    if options.sampling == "nodes":
        return _Sampled(None)
    tol = max(options.rtol, SAMPLING_FLOOR * _EPS)
    samples = sample_periodic(F, T, tol=tol, max_samples=options.max_samples, scales=scales)
    finite = np.isfinite(samples.samples).all(axis=(2, 3))                  # (N, groups)
    if not finite.all():
        j, g = np.argwhere(~finite)[0]
        raise ParameterError(names[g], f"non-finite entries at t = {j * T / samples.samples.shape[0]:.6g} s")
    if samples.converged:
        return _Sampled(samples)
    jumps, breaks, calls = find_jumps(F, T, samples.samples, samples.scale, tol)
    found = (f"; jumps of the coefficients located at t = {', '.join(f'{t!r}' for t in jumps)} s"
             if jumps else "")
    errors = ", ".join(f"{e:.1e}" for e in samples.history)
    if options.sampling == "spectral":
        raise SamplingError(
            f"sampling='spectral': the trigonometric interpolant of the coefficients did not reach the relative "
            f"error {tol:.2g} with {samples.evaluations} samples (measured errors after each doubling: "
            f"{errors}){found}; the coefficients are not smooth enough: use sampling='nodes'",
            samples.evaluations, samples.history, tol)
    warn_user(f"Floquet: the coefficients' trigonometric interpolant did not reach the relative error {tol:.2g} "
              f"with {samples.evaluations} samples (measured errors after each doubling: {errors}){found}: "
              f"evaluating them at every collocation node instead"
              f"{' with a step boundary at each jump' if jumps else ''} (slower; the interpolant's error does "
              f"not enter the bounds)", AccuracyWarning)
    return _Sampled(samples, tuple(jumps), tuple(breaks), calls)


def _at_nodes(tr: Transitions, sampled: _Sampled, defect: float) -> Integrated:
    """The transitions of the nodes path, counting the samples spent first where sampling did not converge."""
    if sampled.samples is None:
        return Integrated(tr, tr.evaluations, None, defect, "coefficients at every node")
    spent = sampled.samples.evaluations + sampled.calls
    at = (f"; steps end at the jumps located at t = {', '.join(f'{t:.17g}' for t in sampled.jumps)} s"
          if sampled.jumps else "")
    return Integrated(tr, tr.evaluations + spent, None, defect,
                      f"coefficients at every node (sampling did not converge: {spent} samples "
                      f"spent first{at})")


def _described(samples: PeriodicSamples, tr: Transitions) -> str:
    return (f"coefficients from {samples.evaluations} equispaced samples per period (trigonometric interpolant, "
            f"measured relative error {float(samples.error.max()):.1e}), integrated on a grid of "
            f"{len(tr.steps)} steps")


def _integration(options: FloquetOptions) -> dict:
    """The integrators' keywords from the options (the same for both integrators)."""
    return dict(rtol=options.rtol, stages=options.stages, growth=options.growth, max_steps=options.max_steps,
                max_time=options.max_time)


def first_order_transitions(func, T: float, m: int, options: FloquetOptions) -> Integrated:
    """The transitions of y' = A(t) y, A = ``func`` (checked callable).

    Examples
    --------
    >>> from pinlin.periodic.options import FloquetOptions
    >>> from pinlin.periodic.sampled import first_order_transitions
    >>> A = lambda t: np.array([[0.0, 1.0], [-(1.3 + 0.4 * np.cos(t)), 0.0]])
    >>> nodes = first_order_transitions(A, 2 * np.pi, 2, FloquetOptions(sampling="nodes"))
    >>> print(nodes.samples is None, nodes.description)
    True coefficients at every node
    """
    sampled = _sample(lambda t: func(t)[None], T, options, ("A",))
    samples = sampled.samples
    if samples is None or not samples.converged:
        tr = integrate_transitions(func, T, m, breaks=sampled.breaks, **_integration(options))
        return _at_nodes(tr, sampled, float("nan"))
    n = m // 2
    top = np.hstack([np.zeros((n, n)), np.eye(n)]) if m % 2 == 0 else None
    second = top is not None and bool(np.all(samples.samples[:, 0, :n] == top))

    def A(times):
        values = samples(times)[:, 0]
        if second:
            values[:, :n] = top
        return values

    counted = float(counted_errors(samples.error)[0])
    error = np.array([[counted * float(samples.scale[0])]]) if counted else None
    tr = integrate_on_grid(A, T, m, second_order=second, coefficient_error=error, probe=samples.samples[:, 0],
                           A0=samples.samples[0, 0], **_integration(options))
    return Integrated(tr, samples.evaluations, samples, float("nan"), _described(samples, tr))


def _mass_inverse_norms(M: np.ndarray) -> np.ndarray:
    return 1.0 / np.linalg.svd(M, compute_uv=False)[:, -1]


def counted_errors(error: np.ndarray) -> np.ndarray:
    """The measured relative errors that count: at most :data:`SAMPLING_FLOOR` eps is the samples' own
    rounding (a Pinocchio pass or a user's function is accurate to a few eps of its norms), which neither
    path counts (the nodes path does not bound the rounding of its evaluations either).

    Examples
    --------
    >>> from pinlin.periodic.sampled import counted_errors
    >>> counted_errors(np.array([1e-15, 1e-9]))       # 1e-15 < 64 eps: the samples' own rounding
    array([0.e+00, 1.e-09])
    """
    return np.where(error <= SAMPLING_FLOOR * _EPS, 0.0, error)


def block_errors(samples: PeriodicSamples, A: np.ndarray, n: int) -> np.ndarray | None:
    """Block bound [[0, 0], [e_X, e_Y]] on the interpolant's error in -M^-1 K and -M^-1 C:
    d(M^-1 K) = M^-1 (dK - dM M^-1 K), each d from the measured relative error of its group times the group's
    largest Frobenius norm, the largest over the samples; None when every error is at rounding level.

    Examples
    --------
    >>> from pinlin.periodic.sampled import block_errors
    >>> from pinlin.periodic.sampling import sample_periodic
    >>> samples = sample_periodic(lambda t: np.array([[[1.0]], [[0.0]], [[2.0 + np.cos(t)]]]), 2 * np.pi, tol=1e-13)
    >>> print(block_errors(samples, np.zeros((16, 2, 2)), 1))        # every error at rounding level
    None
    """
    S = samples.samples
    counted = counted_errors(samples.error)
    if not counted.any():
        return None
    eM, eC, eK = counted * samples.scale
    inv = _mass_inverse_norms(S[:, 0])
    X, Y = np.linalg.norm(A[:, n:, :n], 2, axis=(1, 2)), np.linalg.norm(A[:, n:, n:], 2, axis=(1, 2))
    return np.array([[0.0, 0.0], [float(np.max(inv * (eK + eM * X))), float(np.max(inv * (eC + eM * Y)))]])


def second_order_transitions(triple, fallback, T: float, n: int, options: FloquetOptions) -> Integrated:
    """The transitions of M x'' + C x' + K x = 0: ``triple(t)`` -> (3, n, n) stacked M, C, K (one evaluation);
    ``fallback()`` -> (fM, fC, fK) checked callables for the nodes (made only when they are needed).  The
    conservative-structure defect is measured up to ``options.structure_tol`` eps.

    Examples
    --------
    >>> from pinlin.periodic.options import FloquetOptions
    >>> from pinlin.periodic.sampled import second_order_transitions
    >>> triple = lambda t: np.array([[[1.0]], [[0.0]], [[1.3 + 0.4 * np.cos(t)]]])     # M, C, K of Mathieu
    >>> integrated = second_order_transitions(triple, None, 2 * np.pi, 1, FloquetOptions())
    >>> print(integrated.evaluations, integrated.defect == 0.0)        # constant M, C = 0, symmetric K
    16 True
    """
    give_up = options.structure_tol * _EPS
    sampled = _sample(triple, T, options, ("M", "C", "K"), second_order_scales)
    samples = sampled.samples
    if samples is None or not samples.converged:
        A = SecondOrderA(*fallback(), n, give_up)
        tr = integrate_transitions(A, T, 2 * n, breaks=sampled.breaks, **_integration(options))
        return _at_nodes(tr, sampled, A.defect)
    S = samples.samples
    A_samples = first_order_form(S[:, 0], S[:, 1], S[:, 2], times=np.arange(S.shape[0]) * T / S.shape[0],
                                 residual=False)[0]
    defect = structure_defect(S[:, 0], S[:, 1], S[:, 2], S[0, 0], S[0, 1])
    errors = block_errors(samples, A_samples, n)
    lagrangian = float("nan")
    if defect > give_up and errors is None:     # the interpolant, and so its derivatives, exact to rounding
        dS = samples.derivative_at_samples()
        rate = S.shape[0] / 2 * 2 * np.pi / T
        lagrangian = lagrangian_defect(S[:, 0], S[:, 1], S[:, 2], dS[:, 0], dS[:, 1], rate)

    def A(times):
        F = samples(times)
        return first_order_form(F[:, 0], F[:, 1], F[:, 2], times=times, residual=False)[0]

    tr = integrate_on_grid(A, T, 2 * n, second_order=True, coefficient_error=errors, probe=A_samples,
                           A0=A_samples[0], **_integration(options))
    return Integrated(tr, samples.evaluations, samples, defect, _described(samples, tr), lagrangian)
