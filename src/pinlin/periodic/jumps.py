"""Jumps in periodic coefficients, found from their equispaced samples and located by bisection (theory:
Floquet).

A Gauss step whose nodes all lie on one side of a jump of A(t) never sees it, and neither do its halves: the
step-doubling estimate stays small while the transition is wrong by the jump times the step.  The samples of the
spectral interpolant (:mod:`.sampling`) show a jump as a difference between neighbouring samples out of
proportion to its neighbours' (a smooth F changes by about h ||F'|| from one sample to the next, so that
neighbouring differences agree to O(h)).  Each such candidate is bisected: the half with the larger difference
is kept, and a jump keeps its difference as the interval shrinks, where a smooth F halves it.  A candidate whose
difference keeps :data:`JUMP_KEEP` of its first value down to an interval of a few ulps is a jump, located there;
the integrator then steps to it exactly (:func:`.collocation.integrate_transitions` ``breaks``).  Without
samples (``sampling="nodes"``) :class:`EdgeWatch` looks at the integrator's own nodes: in the gap between two
steps' outer nodes, and between consecutive nodes of a rejected step.  A steep but
continuous feature halves its difference once the interval is below its width: its bracket becomes two step
boundaries, so that the steps inside it see the feature at their nodes.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["find_jumps", "EdgeWatch", "JUMP_RATIO", "JUMP_KEEP", "JUMP_ULPS"]

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


def _distance(Fa: np.ndarray, Fb: np.ndarray, scale: np.ndarray) -> float:
    return float(np.sum(np.sqrt(np.sum((Fb - Fa) ** 2, axis=(1, 2))) / np.maximum(scale, np.finfo(float).tiny)))


def _bisect(F, a: float, b: float, Fa: np.ndarray, Fb: np.ndarray, scale: np.ndarray) -> tuple[str, tuple, int]:
    """(kind, bracket, calls): "jump" with (b,) the time of a jump located to a few ulps, "steep" with the
    bracket of a continuous feature narrower than [a, b], or "smooth" (bracket empty)."""
    d = d0 = _distance(Fa, Fb, scale)
    feature, level, calls = (a, b), 0, 0
    while b - a > JUMP_ULPS * np.spacing(b):
        m = 0.5 * (a + b)
        Fm = np.asarray(F(float(m)), dtype=float)
        calls += 1
        left, right = _distance(Fa, Fm, scale), _distance(Fm, Fb, scale)
        if max(left, right) < JUMP_KEEP * d:
            break
        if left >= right:
            b, Fb, d = m, Fm, left
        else:
            a, Fa, d = m, Fm, right
        if d >= JUMP_KEEP * d0:
            feature, level = (a, b), level + 1
    else:
        if d >= JUMP_KEEP * d0:     # the difference kept down to a few ulps: a jump
            return "jump", (float(b),), calls
    return ("steep", tuple(float(t) for t in feature), calls) if level > 0 else ("smooth", (), calls)


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
    for j in candidates:
        kind, bracket, spent = _bisect(F, j * period / N, (j + 1) * period / N, samples[j], samples[(j + 1) % N],
                                       scale)
        calls += spent
        inside = [t for t in bracket if 0.0 < t < period * (1 - 1e-15)]
        if kind == "jump":
            jumps.extend(inside)
        breaks.extend(inside)
    return sorted(jumps), sorted(set(breaks)), calls


class EdgeWatch:
    """The nodes path's watch over the gaps between consecutive steps: a jump between the last node of one
    step and the first node of the next is seen by neither step's error estimate.  After each accepted step,
    :meth:`check` compares the values at the two nodes around the gap with the largest rate of change inside
    the steps (a difference over :data:`JUMP_RATIO` times that rate times the gap, and above ``floor``
    relative to ||A||, is bisected) and returns the located jump's time, or None; :meth:`inside` looks for
    one between the nodes of a rejected step.

    Examples
    --------
    >>> from pinlin.periodic.jumps import EdgeWatch
    >>> A = lambda t: np.array([[1.0 if t < 0.5 else 3.0]])
    >>> watch = EdgeWatch(A, 1e-13)
    >>> watch.check(np.array([0.1, 0.2, 0.48]), np.array([[[1.0]], [[1.0]], [[1.0]]]))     # the first step
    >>> print(watch.check(np.array([0.52, 0.6, 0.9]), np.array([[[3.0]], [[3.0]], [[3.0]]])))
    0.5
    >>> print(watch.inside(np.array([0.4, 0.45, 0.55, 0.6]), np.array([[[1.0]], [[1.0]], [[3.0]], [[3.0]]])))
    0.5
    """

    def __init__(self, A, floor: float):
        self.A, self.floor = A, float(floor)      # A counts its own calls
        self.previous = None

    def forget(self) -> None:
        """No step before the next one (after a restart at a jump).

        Examples
        --------
        >>> from pinlin.periodic.jumps import EdgeWatch
        >>> watch = EdgeWatch(lambda t: np.array([[1.0 if t < 0.5 else 3.0]]), 1e-13)
        >>> watch.check(np.array([0.1, 0.48]), np.array([[[1.0]], [[1.0]]]))
        >>> watch.forget()
        >>> print(watch.check(np.array([0.52, 0.9]), np.array([[[3.0]], [[3.0]]])))     # no step before it
        None
        """
        self.previous = None

    def check(self, times: np.ndarray, values: np.ndarray) -> float | None:
        """The located jump in the gap between the previous accepted step's last node and this accepted
        step's first node (``times`` (k,) [s] and ``values`` (k, m, m) of A at this step's nodes), or None.

        Examples
        --------
        >>> from pinlin.periodic.jumps import EdgeWatch
        >>> watch = EdgeWatch(lambda t: np.array([[2.0 * t]]), 1e-13)        # smooth: the gap is in proportion
        >>> watch.check(np.array([0.1, 0.4]), np.array([[[0.2]], [[0.8]]]))
        >>> print(watch.check(np.array([0.6, 0.9]), np.array([[[1.2]], [[1.8]]])))
        None
        """
        order = np.argsort(times)
        times, values = times[order], values[order]
        rates = np.linalg.norm(np.diff(values, axis=0), axis=(1, 2)) / np.maximum(np.diff(times), 1e-300)
        rate = float(rates.max()) if rates.size else 0.0
        previous, self.previous = self.previous, (float(times[-1]), values[-1], rate)
        if previous is None:
            return None
        t_last, A_last, rate_last = previous
        scale = np.array([max(float(np.linalg.norm(A_last)), float(np.linalg.norm(values[0])), 1e-300)])
        gap = float(times[0]) - t_last
        difference = float(np.linalg.norm(values[0] - A_last)) / scale[0]
        if not (difference > self.floor and difference * scale[0] > JUMP_RATIO * max(rate, rate_last) * gap):
            return None
        kind, bracket, _ = _bisect(lambda t: self.A(t)[None], t_last, float(times[0]), A_last[None],
                                   values[0][None], scale)
        return bracket[0] if kind == "jump" else None

    def inside(self, times: np.ndarray, values: np.ndarray) -> float | None:
        """The located jump between two consecutive nodes of a rejected step (the largest rate of change
        over :data:`JUMP_RATIO` times the next largest, the difference above ``floor``), or None.

        Examples
        --------
        >>> from pinlin.periodic.jumps import EdgeWatch
        >>> watch = EdgeWatch(lambda t: np.array([[1.0 if t < 0.3 else -1.0]]), 1e-13)
        >>> print(f"{watch.inside(np.array([0.0, 0.2, 0.4]), np.array([[[1.0]], [[1.0]], [[-1.0]]])):.15f}")
        0.300000000000000
        """
        order = np.argsort(times)
        times, values = times[order], values[order]
        differences = np.linalg.norm(np.diff(values, axis=0), axis=(1, 2))
        rates = differences / np.maximum(np.diff(times), 1e-300)
        if rates.size < 2:
            return None
        k = int(np.argmax(rates))
        scale = np.array([max(float(np.linalg.norm(values[k])), float(np.linalg.norm(values[k + 1])), 1e-300)])
        if not (differences[k] > self.floor * scale[0] and rates[k] > JUMP_RATIO * np.sort(rates)[-2]):
            return None
        kind, bracket, _ = _bisect(lambda t: self.A(t)[None], float(times[k]), float(times[k + 1]),
                                   values[k][None], values[k + 1][None], scale)
        return bracket[0] if kind == "jump" else None
