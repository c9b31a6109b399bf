"""Jumps in periodic coefficients, found from their equispaced samples and located by bisection (theory:
Floquet).

A Gauss step whose nodes all lie on one side of a jump of A(t) never sees it, and neither do its halves: the
step-doubling estimate stays small while the transition is wrong by the jump times the step.  The samples of the
spectral interpolant (:mod:`.sampling`) show a jump as a difference between neighbouring samples out of
proportion to its neighbours' (a smooth F changes by about h ||F'|| from one sample to the next, so that
neighbouring differences agree to O(h)).  Each such candidate is bisected: the half with the larger difference
is kept, and a jump keeps its difference as the interval shrinks, where a smooth F halves it.  A candidate whose
difference keeps :data:`JUMP_KEEP` of its first value down to an interval of a few ulps is a jump, located there;
the integrator then steps to it exactly (:func:`.collocation.integrate_transitions` ``breaks``).  A steep but
continuous feature halves its difference once the interval is below its width: its bracket becomes two step
boundaries, so that the steps inside it see the feature at their nodes.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["find_jumps", "JUMP_RATIO", "JUMP_KEEP", "JUMP_ULPS"]

#: A difference between neighbouring samples this many times larger than the smaller of its neighbours'
#: makes a candidate (a smooth F gives ratios 1 + O(h); extrema give false candidates, which the bisection
#: rejects after a few evaluations).
JUMP_RATIO = 8.0

#: A bisection level keeps a candidate when its larger half still has this share of the difference
#: (a jump: about 1; a smooth F: about 1 / 2).
JUMP_KEEP = 0.75

#: A bracket at most this many ulps of its end wide is a located jump.
JUMP_ULPS = 4


def _differences(samples: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """Relative difference from sample j to sample j + 1 (cyclic), summed over the groups: (N,)."""
    diff = np.roll(samples, -1, axis=0) - samples
    return np.sum(np.sqrt(np.sum(diff ** 2, axis=(2, 3))) / np.maximum(scale, np.finfo(float).tiny), axis=1)


def find_jumps(F: Callable[[float], np.ndarray], period: float, samples: np.ndarray, scale: np.ndarray,
               floor: float) -> tuple[list[float], list[float], int]:
    """(jumps, breaks, evaluations): the jumps of F located to a few ulps, the step boundaries the integrator
    must keep (each jump, and both ends of a steep continuous feature's bracket), both sorted in (0, T), and
    the calls of F the bisections made.

    Parameters
    ----------
    F : callable
        t [s] -> (g, k, k) array, the sampled function.
    period : float
        T [s].
    samples : ndarray (N, g, k, k)
        F at t_j = j T / N.
    scale : ndarray (g,)
        Each group's scale (the differences are relative to it).
    floor : float
        Relative differences below this are not looked at (rounding, or jumps below the accuracy asked for).

    Examples
    --------
    A square wave with jumps at 0.25 and 0.75 of the period, sampled 16 times:

    >>> from pinlin.periodic.jumps import find_jumps
    >>> F = lambda t: np.array([[[2.0 if 0.25 <= t % 1.0 < 0.75 else -1.0]]])
    >>> samples = np.stack([F(t) for t in np.arange(16) / 16])
    >>> jumps, breaks, calls = find_jumps(F, 1.0, samples, np.array([2.0]), 1e-13)
    >>> print(jumps, breaks)
    [0.25, 0.75] [0.25, 0.75]
    """
    N = samples.shape[0]
    D = _differences(samples, scale)
    smaller = np.minimum(np.roll(D, 1), np.roll(D, -1))
    candidates = np.flatnonzero((D > floor) & (D > JUMP_RATIO * smaller))
    jumps, breaks, calls = [], [], 0

    def distance(Fa, Fb):
        return float(np.sum(np.sqrt(np.sum((Fb - Fa) ** 2, axis=(1, 2))) / np.maximum(scale, np.finfo(float).tiny)))

    for j in candidates:
        a, b = j * period / N, (j + 1) * period / N
        Fa, Fb, d = samples[j], samples[(j + 1) % N], float(D[j])
        d0, feature, level = d, (a, b), 0
        while b - a > JUMP_ULPS * np.spacing(b):
            m = 0.5 * (a + b)
            Fm = np.asarray(F(float(m)), dtype=float)
            calls += 1
            left, right = distance(Fa, Fm), distance(Fm, Fb)
            if max(left, right) < JUMP_KEEP * d:
                break
            if left >= right:
                b, Fb, d = m, Fm, left
            else:
                a, Fa, d = m, Fm, right
            if d >= JUMP_KEEP * d0:
                feature, level = (a, b), level + 1
        else:
            if d >= JUMP_KEEP * d0:     # the difference kept to a few ulps: a jump
                if b < period * (1 - 1e-15):
                    jumps.append(float(b))
                    breaks.append(float(b))
                continue
        if level > 0:           # steep but continuous: narrower than the samples' spacing
            breaks.extend(float(t) for t in feature if 0.0 < t < period * (1 - 1e-15))
    return sorted(jumps), sorted(set(breaks)), calls
