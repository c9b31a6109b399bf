"""Getting close to a coalescence: the critical pair and its squared distance (theory: boundaries).

Newton on the defining system (:mod:`.coalescence`) needs a start near the
double eigenvalue.  Two eigenvalues s_i, s_j about to meet on an axis of
symmetry of the spectrum (the real axis for mu = lam^2 or for a complex pair
landing on it; the imaginary axis for an undamped gyroscopic or circulatory
system) have a squared distance

.. math::  \\delta(p) = \\pm (s_i - s_j)^2

that is an analytic function of p through p* (a symmetric function of the two
eigenvalues), positive while they lie apart on the axis and negative once they
have left it as a mirror pair (the sign fixed so).  Regula falsi on delta, kept
inside the verdict bracket, predicts p*; the pair's midpoint on the axis and one
eigenvector start the Newton iteration.  If Newton does not converge from that
start, the prediction's verdict shrinks the bracket and the next prediction is
tried.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..errors import ConvergenceError
from .bracket import Bracket, PlanMismatch
from .coalescence import DoubleEigenvalue, solve_double
from .crossing import REAL_SAFETY
from .derivatives import EPS
from .evaluation import Evaluator

__all__ = ["PairData", "pair_data", "coalescence_search"]


@dataclass
class PairData:
    """The critical pair at one parameter value: signed squared distance, midpoint on the axis, an eigenvector."""

    delta: float
    s0: complex
    x0: np.ndarray


def _spectrum(ev: Evaluator, p: float, squared: bool):
    """Eigenvalues s, right vectors and the tolerance under which s lies on its axis."""
    if squared:
        sys = ev.system(p)
        mu, X = scipy.linalg.eig(-sys.K, sys.M)
        return mu, X, np.full(mu.shape, REAL_SAFETY * EPS * np.abs(mu).max())
    modes = ev.modes(p)
    return modes.eigenvalues, modes.right, REAL_SAFETY * modes.error_bound


def _real_vector(x: np.ndarray) -> np.ndarray:
    """The real vector nearest to x up to a complex factor (its phase chosen to make x^T x real)."""
    x = x * np.exp(-0.5j * np.angle(x @ x))
    return np.real(x) / np.linalg.norm(np.real(x))


def pair_data(ev: Evaluator, p: float, *, squared: bool, axis: str, on_axis: bool) -> PairData | None:
    """The critical pair at p: two eigenvalues nearest on the axis (``on_axis``) or the mirror pair nearest it.

    ``axis`` is "real" (mu, or lam meeting on the real axis) or "imaginary".
    Returns None when no candidate pair exists.
    """
    s, X, tol = _spectrum(ev, p, squared)
    along, across = (s.real, s.imag) if axis == "real" else (s.imag, s.real)
    scale = max(np.abs(s).max(), np.finfo(float).tiny)
    on = np.flatnonzero(np.abs(across) <= tol)
    if on_axis:
        if on.size < 2:
            return None
        order = on[np.argsort(along[on])]
        gaps = np.diff(along[order])
        i = int(np.argmin(gaps))
        a, b = order[i], order[i + 1]
        mid = 0.5 * (along[a] + along[b])
        s0 = mid if axis == "real" else 1j * mid
        x0 = X[:, a] / np.linalg.norm(X[:, a])
        return PairData(float(gaps[i] / scale) ** 2, s0, _real_vector(x0) if squared else x0)
    off = np.setdiff1d(np.arange(s.size), on)
    off = off[(across[off] > 0)]
    if off.size == 0:
        return None
    k = off[np.argmin(np.abs(across[off]) / np.maximum(np.abs(s[off]), scale * EPS))]
    s0 = along[k] if axis == "real" else 1j * along[k]
    x0 = X[:, k] / np.linalg.norm(X[:, k])
    return PairData(-float(2 * across[k] / scale) ** 2, s0, _real_vector(x0) if squared else x0)


def coalescence_search(ev: Evaluator, br: Bracket, *, squared: bool, axis: str, on_class: str, tol: float,
                       derivative: Callable | None, max_evaluations: int) -> tuple[DoubleEigenvalue, list[str]]:
    """Regula falsi on delta inside the verdict bracket, each prediction tried as a start of the defining system.

    Returns the converged double eigenvalue and the steps taken.

    Raises
    ------
    ConvergenceError
        More than ``max_evaluations`` modal analyses, or the bracket closed to
        rounding without a converged double eigenvalue.
    """
    steps: list[str] = []
    weights = {"lo": 1.0, "hi": 1.0}
    kept = None
    failures: list[str] = []
    for _ in range(max_evaluations):
        ends = {}
        for name, p in (("lo", br.lo), ("hi", br.hi)):
            cls = br.class_lo if name == "lo" else br.class_hi
            ends[name] = pair_data(ev, p, squared=squared, axis=axis, on_axis=cls == on_class)
        d_lo, d_hi = ends["lo"], ends["hi"]
        if not steps and (d_lo is None or d_hi is None or d_lo.delta * d_hi.delta >= 0):
            raise PlanMismatch("no pair of eigenvalues approaches the axis from one end and leaves it at the other")
        if d_lo is not None and d_hi is not None and d_lo.delta * d_hi.delta < 0:
            f_lo, f_hi = weights["lo"] * d_lo.delta, weights["hi"] * d_hi.delta
            p_pred = br.lo - f_lo * br.width / (f_hi - f_lo)
            name = "regula falsi on the pair's squared distance"
        else:
            p_pred, name = 0.5 * (br.lo + br.hi), "bisection"
        if not br.inside(p_pred):
            p_pred, name = 0.5 * (br.lo + br.hi), "bisection"
        start = min((d for d in (d_lo, d_hi) if d is not None), default=None,
                    key=lambda d: abs(p_pred - (br.lo if d is d_lo else br.hi)))
        steps.append(name)
        if start is not None:
            sol = solve_double(ev, p_pred, start.s0, start.x0, squared=squared, interval=(br.lo, br.hi),
                               derivative=derivative, tol=tol)
            steps.append(f"newton on the defining system ({sol.steps} steps{'' if sol.converged else ', failed'})")
            if sol.converged:
                return sol, steps
            failures.append(sol.reason)
        if ev.analyses >= max_evaluations or br.width <= 4 * EPS * max(abs(br.lo), abs(br.hi)):
            raise ConvergenceError(
                f"no double eigenvalue found in [{br.lo!r}, {br.hi!r}] after {ev.analyses} modal analyses; "
                f"Newton on the defining system: {'; '.join(failures[-3:]) or 'never started'}", [])
        before = br.lo, br.hi
        br.judge(ev, p_pred, name)
        moved = "lo" if br.lo != before[0] else "hi" if br.hi != before[1] else None
        # Illinois: an end kept twice in a row has its delta halved, so regula falsi does not stall
        if moved is not None:
            other = "hi" if moved == "lo" else "lo"
            weights[moved] = 1.0
            weights[other] = 0.5 * weights[other] if kept == other else 1.0
            kept = other
    raise ConvergenceError(f"no double eigenvalue found in [{br.lo!r}, {br.hi!r}] in {max_evaluations} steps", [])
