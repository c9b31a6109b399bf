"""Newton's method on a transversal crossing of a stability boundary (theory: boundaries).

Where an eigenvalue crosses the imaginary axis with a nonzero speed, the signed
distance phi(p) of the critical eigenvalue to the boundary is smooth and has a
simple root at p*:

- ``"abscissa"``: phi = max_k Re lam_k (the spectral abscissa; a damped system
  losing stability by flutter);
- ``"stiffness"``: phi = the largest real eigenvalue mu of the pencil (-K, M)
  (negative while K is positive definite).  A real root lam of L reaches zero
  exactly where K turns singular, so divergence (from stability, or beside a
  flutter pair) is the root of phi,
  whatever the damping; phi is smooth there even when lam is not (undamped:
  lam = +-sqrt(mu); damped: the root that crosses is often born just before from
  a complex pair landing on the real axis).  For D = G = 0, mu = lam^2.

phi' comes from the eigenvalue sensitivity (:mod:`.sensitivity`:
-y^T L_p x / (y^T L' x); for mu, -y^T (K' + mu M') x / (y^T M x)), with L_p from
the user's derivative or a secant between evaluated systems.  The step is the
root of the cubic Hermite interpolant of phi, phi' at the two ends of the verdict
bracket when it has one there (a curved phi is modelled far better than by one
tangent), else Newton's -phi / phi'; steps that leave the bracket or stop
shrinking are replaced by regula falsi or bisection, so the search always
converges.  It stops when Newton's correction is within the rounding floor.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from ..errors import BoundaryNotIsolatedError, ConvergenceError
from .bracket import Bracket, PlanMismatch
from .derivatives import EPS, MatrixDerivatives, exact_derivatives, secant_derivatives
from .evaluation import Evaluator
from .sensitivity import cluster_derivatives, simple_derivative
from .verify import NOT_ISOLATED_RTOL

__all__ = ["TRACKERS", "Track", "CrossingResult", "track", "newton_crossing", "derivative_at", "REAL_SAFETY",
           "SHRINK", "FALSI_CLIP", "BISECTION_LAG"]

TRACKERS = ("abscissa", "stiffness")

#: An eigenvalue counts as real when |Im lam| is within this many of its error bounds (the verdict's own factor).
REAL_SAFETY = 10.0
#: A Newton step is trusted while it shrinks at least by this factor from the previous one; otherwise the
#: iteration is not in its quadratic regime and a bracketing step is taken instead.
SHRINK = 0.5
#: The iteration never falls more than this many steps behind bisection (a step that halves the bracket):
#: beyond it a bisection step is forced.  Where phi is smooth the fast steps converge within it; where it is
#: flat on one side and rises like a square root on the other (a crossing just beyond a near-coalescence of a
#: lightly damped system) the models mislead, and the cost stays within that of bisection plus this lag.
BISECTION_LAG = 6
#: Regula falsi points are kept this fraction of the bracket away from its ends, so every bracketing
#: step removes at least that much of it even when phi is far from linear.
FALSI_CLIP = 0.1
#: Rounding of mu's first-order error: a few eps of ||K|| + |mu| ||M|| through its condition number.
MU_ROUNDING = 4.0


@dataclass
class Track:
    """The critical eigenvalue at one parameter value: phi, d phi / dp and phi's rounding-level uncertainty."""

    p: float
    phi: float
    slope: float | None
    floor: float
    eigenvalue: complex
    dlam: complex | None


@dataclass
class CrossingResult:
    value: float
    bound: float
    eigenvalue: complex
    converged: bool
    floor: float
    steps: list[str] = field(default_factory=list)
    reason: str = ""


def derivative_at(ev: Evaluator, p: float, derivative: Callable | None) -> MatrixDerivatives:
    """L_p at p: the user's exact derivative, or the secant to the nearest other evaluated system."""
    if derivative is not None:
        return exact_derivatives(derivative, p, ev.system(p).n)
    other = ev.nearest(p, exclude=p)
    return secant_derivatives(ev.matrices(other), other, ev.matrices(p), p)


def _lam_track(ev: Evaluator, p: float, dL: MatrixDerivatives) -> Track:
    modes = ev.modes(p)
    lam, bound = modes.eigenvalues, modes.error_bound
    k = max(range(lam.size), key=lambda i: (lam[i].real, lam[i].imag >= 0))
    cluster = next((c for c in modes.clusters if k in c.indices), None)
    if cluster is None:
        gaps = np.abs(np.delete(lam, k) - lam[k])
        dlam, _ = simple_derivative(modes, k, dL, float(gaps.min()) if gaps.size else np.inf)
    elif cluster.consistent and cluster.semisimple:
        values, _ = cluster_derivatives(modes, list(cluster.indices), complex(cluster.center), dL)
        dlam = max(values, key=lambda d: d.real)
    else:
        dlam = None
    slope = None if dlam is None or not np.isfinite(dlam) else float(np.real(dlam))
    return Track(p, float(lam[k].real), slope, float(bound[k]), complex(lam[k]), dlam)


def _mu_track(ev: Evaluator, p: float, dL: MatrixDerivatives) -> Track:
    sys = ev.system(p)
    mu, vl, vr = scipy.linalg.eig(-sys.K, sys.M, left=True, right=True)
    real = np.flatnonzero(np.abs(mu.imag) <= REAL_SAFETY * EPS * np.abs(mu).max())
    pool = real if real.size else np.arange(mu.size)
    k = int(pool[np.argmax(mu[pool].real)])
    x, y = vr[:, k], vl[:, k].conj()
    den = y @ (sys.M @ x)
    dM, _, dK = dL.stack
    dmu = -(y @ ((dK + mu[k] * dM) @ x)) / den
    scale = np.linalg.norm(x) * np.linalg.norm(y) / abs(den)
    floor = MU_ROUNDING * EPS * scale * (np.linalg.norm(sys.K) + abs(mu[k]) * np.linalg.norm(sys.M))
    slope = float(np.real(dmu)) if np.isfinite(dmu) else None
    return Track(p, float(mu[k].real), slope, float(floor), complex(np.sqrt(complex(mu[k]))), None)


def track(ev: Evaluator, p: float, mode: str, dL: MatrixDerivatives) -> Track:
    """The critical eigenvalue's phi, slope and floor at p for tracker ``mode`` (one of :data:`TRACKERS`)."""
    return _mu_track(ev, p, dL) if mode == "stiffness" else _lam_track(ev, p, dL)


def _boundary_eigenvalue(t: Track, step: float, mode: str) -> complex:
    if mode == "stiffness":
        return complex(np.sqrt(complex(max(t.phi + t.slope * step, 0.0))))
    lam = t.eigenvalue + (t.dlam * step if t.dlam is not None else 0.0)
    return complex(0.0, lam.imag)


def newton_crossing(ev: Evaluator, br: Bracket, mode: str, *, tol: float, derivative: Callable | None,
                    safety: float, max_evaluations: int) -> CrossingResult:
    """Safeguarded Newton on phi(p) = 0 inside the verdict bracket (see the module docstring).

    Converged when the Newton correction is below max(tol, safety floor / |phi'|, 2 eps |p|);
    the value is p plus that correction and its bound the correction plus
    ``safety`` times the rounding floor.

    Raises
    ------
    ConvergenceError
        More than ``max_evaluations`` modal analyses.
    """
    tracks: dict[float, Track] = {}

    def at(p: float) -> Track:
        if p not in tracks:
            tracks[p] = track(ev, p, mode, derivative_at(ev, p, derivative))
        return tracks[p]

    steps: list[str] = []
    lo, hi = at(br.lo), at(br.hi)
    if lo.phi * hi.phi > 0 and min(abs(lo.phi) - lo.floor, abs(hi.phi) - hi.floor) > 0:
        raise PlanMismatch(f"the tracked quantity has the same sign at both ends ({lo.phi:.3g}, {hi.phi:.3g})")
    p, name, falsi_width = _first_step(br, at)
    # as rtsafe (Numerical Recipes): a Newton step is taken only if it stays in the bracket and is at most
    # SHRINK times the step before the last one (at first: the bracket)
    dx = dxold = width0 = br.width
    history: list[float] = []
    for _ in range(max_evaluations):
        if ev.analyses >= max_evaluations:
            raise ConvergenceError(
                f"no convergence on the crossing in {max_evaluations} modal analyses; bracket [{br.lo!r}, {br.hi!r}]",
                history)
        br.judge(ev, p, name)
        steps.append(name)
        t = at(p)
        history.append(abs(t.phi))
        newton = -t.phi / t.slope if t.slope not in (None, 0.0) else None
        if newton is not None:
            floor_p = t.floor / abs(t.slope)
            # a correction within the safety band of the rounding floor cannot be resolved further
            if abs(newton) <= max(tol, safety * floor_p, 2 * EPS * abs(p)):
                return CrossingResult(p + newton, abs(newton) + safety * floor_p,
                                      _boundary_eigenvalue(t, newton, mode), True, floor_p, steps)
        if br.width <= max(tol, 2 * EPS * max(abs(br.lo), abs(br.hi))):
            return CrossingResult(0.5 * (br.lo + br.hi), 0.5 * br.width, _boundary_eigenvalue(t, 0.0, mode),
                                  False, 0.0, steps, "the bracket closed before Newton's correction did")
        hermite = _hermite_root(at(br.lo), at(br.hi))
        if len(steps) - np.log2(width0 / br.width) > BISECTION_LAG:
            q, name = 0.5 * (br.lo + br.hi), "bisection (falling behind bisection)"
        elif hermite is not None and hermite not in tracks and abs(hermite - p) <= SHRINK * dxold:
            q, name = hermite, "hermite"
        elif newton is not None and br.inside(p + newton) and abs(newton) <= SHRINK * dxold:
            q, name = p + newton, "newton"
        else:
            q, name, falsi_width = _bracketing_step(br, at, falsi_width)
        if q in tracks:  # evaluated before: undecided verdicts hold the bracket
            if br.width > max(tol, NOT_ISOLATED_RTOL * max(abs(br.lo), abs(br.hi))):
                raise BoundaryNotIsolatedError(
                    f"the stability verdict stays 'undecided' inside [{br.lo!r}, {br.hi!r}]: the boundary between "
                    f"{br.kind_lo} and {br.kind_hi} is not isolated", (br.lo, br.hi))
            return CrossingResult(0.5 * (br.lo + br.hi), 0.5 * br.width, _boundary_eigenvalue(t, 0.0, mode),
                                  False, 0.0, steps, "undecided verdicts inside the bracket stopped it shrinking")
        dxold, dx, p = dx, abs(q - p), q
    raise ConvergenceError(f"no convergence on the crossing in {max_evaluations} steps; bracket "
                           f"[{br.lo!r}, {br.hi!r}]", history)


def _hermite_root(a: Track, b: Track) -> float | None:
    """The root inside (a.p, b.p) of the cubic matching phi and phi' at both ends, or None.

    With the slopes of both ends of a bracket, the cubic Hermite interpolant of phi is a far better model
    of a curved phi than Newton's tangent at one point (it converges faster from afar, and as fast near
    the root); it is used only when it has exactly one root in the bracket.
    """
    if a.slope is None or b.slope is None or a.phi * b.phi >= 0:
        return None
    h = b.p - a.p
    fa, fb, ga, gb = a.phi, b.phi, a.slope * h, b.slope * h
    coefficients = [2 * fa + ga - 2 * fb + gb, -3 * fa - 2 * ga + 3 * fb - gb, ga, fa]
    roots = np.roots(coefficients)
    inside = [r.real for r in roots if abs(r.imag) <= 1e-12 and 0.0 < r.real < 1.0]
    return a.p + h * inside[0] if len(inside) == 1 else None


def _first_step(br: Bracket, at):
    """Newton from the bracket end predicted nearest the root if it stays well inside, else the midpoint.

    The ends of a wide bracket often lie on other branches of phi (another mode is the rightmost, or a
    divergent root dominates), so neither interpolation nor regula falsi between them is trusted yet.
    """
    ends = sorted((at(br.lo), at(br.hi)), key=lambda t: abs(t.phi / t.slope) if t.slope else np.inf)
    for t in ends:
        if t.slope:
            q = t.p - t.phi / t.slope
            if br.inside(q) and abs(q - t.p) <= SHRINK * br.width:
                return q, "newton", None
    return 0.5 * (br.lo + br.hi), "bisection", None


def _bracketing_step(br: Bracket, at, falsi_width):
    """Regula falsi on the ends' phi, kept FALSI_CLIP of the bracket away from its ends; bisection instead
    when the previous regula falsi step did not halve the bracket (one end stuck, as Illinois avoids)."""
    a, b = at(br.lo), at(br.hi)
    stuck = falsi_width is not None and br.width > 0.5 * falsi_width
    if a.phi * b.phi < 0 and not stuck:
        q = br.lo - a.phi * br.width / (b.phi - a.phi)
        q = min(max(q, br.lo + FALSI_CLIP * br.width), br.hi - FALSI_CLIP * br.width)
        return q, "regula falsi", br.width
    return 0.5 * (br.lo + br.hi), "bisection", None
