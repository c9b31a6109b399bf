"""The contour of the residues: circles around a root, sampled H, the argument-principle count (theory: flexibility).

On a circle ``s_l = c + r exp(2 pi i l / N)`` the H(s) engine's direct method
(:func:`pinlin.frf.engine.lu_solve`) gives H(s_l); the number of eigenvalues
inside is ``m = (1/2 pi i) oint trace(H(s) L'(s)) ds`` (the argument principle for
``p = det L``), evaluated with the same samples, so no eigensolver is involved.
:func:`automatic_contour` grows the circle from the cluster radius until the count
changes and takes a fraction of the last radius with the root's count alone.
"""

from __future__ import annotations

import numpy as np

from ..errors import EigenvalueNotIsolatedError, NotAnEigenvalueError
from ..numerics import check_tolerance
from .engine import SingularPoint, lu_solve, stiffness_norms

__all__ = [
    "circle_samples",
    "eigenvalue_count",
    "fixed_contour",
    "automatic_contour",
    "GROWTH",
    "MAX_RADIUS",
    "COUNT_TOL",
    "RADIUS_FACTORS",
    "CONTOUR_FRACTION",
]

#: Ratio between successive radii when looking for the next eigenvalue.
GROWTH = 4.0
#: Largest radius searched, in units of the scale max(|lam0|, natural scale).
MAX_RADIUS = 1e4
#: A contour count is accepted as an integer when within this of one (the quadrature error of the
#: count decays like the residues' own, so a correct count is far closer than this).
COUNT_TOL = 0.05
#: Radii factors tried in turn when an eigenvalue lies on or near a circle: irregular ratios, so
#: that no two tries meet the same eigenvalue, within 30 % of the radius asked for.
RADIUS_FACTORS = (1.0, 1.137, 0.891, 1.291)
#: The contour radius is this fraction of the largest radius with an unchanged count: both
#: aliasing ratios (cluster / r and r / next eigenvalue) are then at most 1/2 (error ~ 2^-N).
CONTOUR_FRACTION = 0.5


def circle_samples(sys, center: complex, r: float, N: int):
    """H(s_l), trace(H L'), ||L||, ||H|| on the circle ``s_l = center + r exp(2 pi i l / N)``; None when
    an eigenvalue lies exactly on it."""
    s = center + r * np.exp(2j * np.pi * np.arange(N) / N)
    try:
        H = lu_solve(sys, s, np.eye(sys.n))
    except SingularPoint:
        return None  # the caller moves the circle
    nL = stiffness_norms(sys, s)
    dL = 2 * s[:, None, None] * sys.M + sys.C
    trace = np.einsum("kij,kji->k", H, dL)
    nH = np.linalg.norm(H.reshape(N, -1), axis=1)
    return s, H, trace, nL, nH


def eigenvalue_count(sys, center, r, N, strict: bool = True):
    """Argument-principle count of eigenvalues inside ``|s - center| < r`` and the samples.

    When eigenvalues lie near every circle tried (the count is not an integer),
    raise, or return None with ``strict=False``.

    Raises
    ------
    EigenvalueNotIsolatedError
        No circle of the radii tried gives an integer count (``strict``).
    """
    for factor in RADIUS_FACTORS:
        rr = r * factor
        out = circle_samples(sys, center, rr, N)
        if out is None:
            continue
        s, H, trace, nL, nH = out
        value = complex(np.mean(trace * (s - center)))
        if abs(value - round(value.real)) < COUNT_TOL and np.all(np.isfinite(H)):
            return int(round(value.real)), value.real, rr, out
    if not strict:
        return None
    raise EigenvalueNotIsolatedError(
        f"the eigenvalue count on circles of radius ~{r:.3e} around {center:.10g} is not an integer "
        f"(eigenvalues on or near every contour tried); try another cluster_tol",
        lam=center,
        inner=r,
        outer=r,
    )



def fixed_contour(sys, lam0, radius, N, scale):
    """The contour of a radius given by the caller: (m, count, r, inner, free, outer, samples) (all radii r).

    Raises
    ------
    ParameterError
        ``radius`` is not a finite positive number.
    NotAnEigenvalueError
        No eigenvalue inside the circle.
    EigenvalueNotIsolatedError
        No integer count on the circles tried.
    """
    r = check_tolerance(radius, "radius")
    m, count, r, samples = eigenvalue_count(sys, lam0, r, N)
    if m == 0:
        raise NotAnEigenvalueError(
            f"no eigenvalue inside the circle of radius {r:.3e} around lam0 = {lam0:.10g}",
            lam=lam0,
            distance=r / scale,
        )
    return m, count, r, r, r, r, samples


def automatic_contour(sys, lam0, cluster_tol, N, scale):
    """Cluster radius, growth until the count changes, contour radius: (m, count, r, inner, free, outer, samples).

    ``free`` is the largest radius found with the root's count (no other eigenvalue
    inside it), ``outer`` the first with another count.

    Raises
    ------
    NotAnEigenvalueError
        No eigenvalue within ``cluster_tol * scale`` of lam0.
    EigenvalueNotIsolatedError
        Another eigenvalue lies within ``GROWTH`` times the cluster radius, or
        the count changes inside the region found free of other eigenvalues.
    """
    inner = cluster_tol * scale
    m, count, inner, samples = eigenvalue_count(sys, lam0, inner, N)
    if m == 0:
        sv = np.linalg.svd(sys.dynamic_stiffness(lam0), compute_uv=False)
        raise NotAnEigenvalueError(
            f"lam0 = {lam0:.10g} is not an eigenvalue: none lies within cluster_tol * scale = "
            f"{inner:.3e} of it (the smallest singular value of L(lam0) is {sv[-1] / sv[0]:.2e} of "
            f"the largest)",
            lam=lam0,
            distance=float(sv[-1] / sv[0]),
        )
    last, outer, rr = inner, np.inf, inner
    while rr < MAX_RADIUS * scale:
        rr *= GROWTH
        found = eigenvalue_count(sys, lam0, rr, N, strict=False)
        if found is None or found[0] != m:  # (no integer count: eigenvalues near this circle)
            outer = rr
            break
        last = rr = found[2]
    if last == inner:
        raise EigenvalueNotIsolatedError(
            f"the root at lam0 = {lam0:.10g} ({m} eigenvalue(s) within {inner:.3e}) is not isolated: "
            f"another eigenvalue lies within {outer:.3e}; a larger cluster_tol merges it into the root, "
            f"a smaller one may separate them",
            lam=lam0,
            inner=inner,
            outer=outer,
        )
    # the next eigenvalue is beyond `last`, the cluster inside `inner <= last / GROWTH`; with no
    # other eigenvalue up to the scale, a contour larger than the scale only adds rounding
    m_final, count, r, samples = eigenvalue_count(sys, lam0, min(CONTOUR_FRACTION * last, scale), N)
    if m_final != m:
        raise EigenvalueNotIsolatedError(
            f"the eigenvalue count around lam0 = {lam0:.10g} is {m} at radius {inner:.3e} but "
            f"{m_final} at {r:.3e} inside the region found free of other eigenvalues",
            lam=lam0,
            inner=inner,
            outer=outer,
        )
    return m, count, r, inner, float(last), float(outer), samples
