"""Spectral sampling of periodic coefficients: a trigonometric interpolant from equispaced samples, with its
error measured on fresh samples (theory: Floquet).

A T-periodic matrix function F(t) sampled at N equispaced times t_j = j T / N has the trigonometric interpolant

.. math::  F_N(t) = \\frac{1}{N} \\Big( \\hat F_0 + 2 \\sum_{0 < k < N/2} \\mathrm{Re}\\,
           \\hat F_k e^{i k \\omega t} + \\hat F_{N/2} \\cos(\\tfrac{N}{2} \\omega t) \\Big), \\qquad
           \\hat F_k = \\sum_j F(t_j)\\, e^{-2 \\pi i j k / N}, \\quad \\omega = 2 \\pi / T

(the last term for even N only).  It reproduces a trigonometric polynomial of degree below N / 2 exactly, and
for an analytic F its error falls geometrically with N.  The error is measured, not assumed: F_N is compared
with F at the N midpoints t_j + T / (2 N), which then join the samples (N -> 2 N, every evaluation kept), and
the doubling stops when each group of matrices (M, C, K of a second-order system) matches its fresh samples to
``tol`` relative to that group's scale (its largest norm over the samples, or a scale the caller gives).  The accepted interpolant is F_2N; its error is
reported as the measured error of F_N at points F_N did not see, an over-estimate wherever the Fourier
coefficients decay (F_2N uses those points too).  The rotor and vibrating-support cases are trigonometric
polynomials of low degree (the inertia of a turning body, an effective gravity g + z''(t)): 8 + 8 samples
reproduce them to rounding, where integrating with the coefficients evaluated at every collocation node takes
hundreds.  Non-smooth coefficients (a motion given by a spline, a kink) do not converge: the doubling stops
at ``max_samples`` or when the error stops falling, and the caller evaluates at the nodes instead.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["PeriodicSamples", "sample_periodic", "group_norms", "stalled", "FIRST_SAMPLES", "STAGNATION"]

#: Samples of the first interpolant (doubled from there): a trigonometric polynomial of degree <= 3 is exact.
FIRST_SAMPLES = 8

#: From 32 samples on, a doubling that lowers the measured error by less than this factor ends the sampling
#: (algebraic convergence: a non-smooth coefficient, whose nodes are cheaper than its interpolant).
STAGNATION = 8.0

_TINY = float(np.finfo(float).tiny)


@dataclass(frozen=True)
class PeriodicSamples:
    """The trigonometric interpolant of a T-periodic stack of matrices and its measured error.

    Attributes
    ----------
    period : float
        T [s].
    samples : ndarray (N, g, k, k)
        F at t_j = j T / N: g groups of k x k matrices (read-only).
    spectrum : ndarray, complex (N // 2 + 1, g * k * k)
        The real FFT of the flattened samples (scaled, see :meth:`__call__`).
    error : ndarray (g,)
        Measured relative error of each group (largest Frobenius error over the check points, relative to
        ``scale``).
    scale : ndarray (g,)
        The groups' scales the errors are relative to (by default each group's largest Frobenius norm over
        the samples).
    converged : bool
        Every group within ``tol``.
    history : tuple of float
        The largest group error after each doubling.
    evaluations : int
        Calls of F (equals N).

    Examples
    --------
    >>> from pinlin.periodic.sampling import sample_periodic
    >>> samples = sample_periodic(lambda t: np.array([[[np.sin(t)]]]), 2 * np.pi, tol=1e-13)
    >>> print(samples.samples.shape, np.round(samples.derivative_at_samples()[0].ravel(), 12))
    (16, 1, 1, 1) [1.]
    """

    period: float
    samples: np.ndarray
    spectrum: np.ndarray
    error: np.ndarray
    scale: np.ndarray
    converged: bool
    history: tuple
    evaluations: int

    def __call__(self, times) -> np.ndarray:
        """F_N at ``times`` [s] (any shape of 1-d array): (len(times), g, k, k)."""
        times = np.asarray(times, dtype=float).ravel()
        N = self.samples.shape[0]
        k = np.arange(self.spectrum.shape[0])
        weights = np.full(k.size, 2.0)
        weights[0] = 1.0
        if N % 2 == 0:
            weights[-1] = 1.0
        basis = np.exp(1j * (2 * np.pi / self.period) * np.outer(times, k)) * (weights / N)
        flat = (basis @ self.spectrum).real
        return flat.reshape((times.size, *self.samples.shape[1:]))


    def derivative_at_samples(self) -> np.ndarray:
        """dF_N/dt at the N sample times [unit of F / s]: (N, g, k, k) (the Nyquist cosine's derivative
        vanishes there)."""
        N = self.samples.shape[0]
        k = np.arange(self.spectrum.shape[0])
        scaled = self.spectrum * (1j * k * 2 * np.pi / self.period)[:, None]
        if N % 2 == 0:
            scaled[-1] = 0.0
        return np.fft.irfft(scaled, n=N, axis=0).reshape(self.samples.shape)


def _spectrum(samples: np.ndarray) -> np.ndarray:
    return np.fft.rfft(samples.reshape(samples.shape[0], -1), axis=0)


def _midpoint_values(samples: np.ndarray) -> np.ndarray:
    """F_N at t_j + T / (2 N) from the samples at t_j (shift theorem; the Nyquist term, cos(pi j + pi / 2)
    = 0 there, drops out)."""
    N = samples.shape[0]
    spectrum = _spectrum(samples)
    k = np.arange(spectrum.shape[0])
    shifted = spectrum * np.exp(1j * np.pi * k / N)[:, None]
    if N % 2 == 0:
        shifted[-1] = 0.0
    return np.fft.irfft(shifted, n=N, axis=0).reshape(samples.shape)


def _group_errors(estimate: np.ndarray, exact: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """Largest Frobenius error of each group over the points, relative to ``scale``."""
    diff = np.sqrt(np.sum((estimate - exact) ** 2, axis=(2, 3)))          # (points, g)
    return diff.max(axis=0) / np.maximum(scale, _TINY)


def group_norms(samples: np.ndarray) -> np.ndarray:
    """Each group's largest Frobenius norm over the samples (N, g, k, k) -> (g,).

    Examples
    --------
    >>> from pinlin.periodic.sampling import group_norms
    >>> group_norms(np.array([[[[3.0]], [[1.0]]], [[[-4.0]], [[0.5]]]]))       # 2 samples of 2 groups
    array([4., 1.])
    """
    return np.sqrt(np.sum(samples ** 2, axis=(2, 3))).max(axis=0)


def stalled(history, samples: int) -> bool:
    """The doubling that gave ``samples`` samples (errors after each doubling in ``history``) lowered the error by
    less than :data:`STAGNATION`, from 64 samples on (32 checked against 32 fresh ones).

    Examples
    --------
    >>> from pinlin.periodic.sampling import stalled
    >>> stalled([1e-3, 5e-4], 64), stalled([1e-3, 1e-6], 64)
    (True, False)
    """
    return samples > 32 and len(history) > 1 and history[-1] > history[-2] / STAGNATION


def sample_periodic(F: Callable[[float], np.ndarray], period: float, *, tol: float, max_samples: int = 256,
                    first: int = FIRST_SAMPLES, scales: Callable[[np.ndarray], np.ndarray] = group_norms
                    ) -> PeriodicSamples:
    """The trigonometric interpolant of F over one period, doubled until it matches fresh samples.

    Parameters
    ----------
    F : callable
        t [s] -> (g, k, k) real array: g groups of matrices evaluated together (one call, one evaluation).
    period : float
        T [s].
    tol : float
        Relative error allowed in each group.
    max_samples : int
        Largest N tried (the evaluations then are at most ``max_samples``).
    first : int
        N of the first interpolant.
    scales : callable
        samples (N, g, k, k) -> (g,) the scale each group's error is relative to (a group that is small
        beside the others, as the damping of a lightly damped system, gets a scale that reflects the
        rounding of the computation it comes from).

    Returns
    -------
    PeriodicSamples
        ``converged`` False when ``max_samples`` or a stagnating error ended the doubling (its ``history``
        says which).

    Examples
    --------
    >>> from pinlin.periodic.sampling import sample_periodic
    >>> F = lambda t: np.array([[[2.0 + np.cos(t)]]])           # one group of 1 x 1 matrices
    >>> samples = sample_periodic(F, 2 * np.pi, tol=1e-13)
    >>> print(samples.converged, samples.evaluations, f"{samples([1.0])[0, 0, 0, 0]:.12f}", f"{2 + np.cos(1.0):.12f}")
    True 16 2.540302305868 2.540302305868
    """
    def values(times):
        return np.stack([np.asarray(F(float(t)), dtype=float) for t in times])

    N = first
    samples = values(np.arange(N) * period / N)
    history = []
    while True:
        mids = values((np.arange(N) + 0.5) * period / N)
        scale = scales(np.concatenate([samples, mids]))
        error = _group_errors(_midpoint_values(samples), mids, scale)
        history.append(float(error.max()))
        merged = np.empty((2 * N, *samples.shape[1:]))
        merged[0::2], merged[1::2] = samples, mids
        samples, N = merged, 2 * N
        converged = bool(np.all(error <= tol))
        if converged or stalled(history, N) or 2 * N > max_samples or not np.all(np.isfinite(error)):
            break
    samples.flags.writeable = False
    spectrum = _spectrum(samples)
    spectrum.flags.writeable = False
    error.flags.writeable = False
    scale.flags.writeable = False
    return PeriodicSamples(float(period), samples, spectrum, error, scale, converged, tuple(history), N)
