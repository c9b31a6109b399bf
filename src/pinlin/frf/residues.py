"""Residues of the dynamic flexibility at a root of any multiplicity (SPEC section 4, paper Sec. 10).

Near a root lam0 of p of algebraic multiplicity m (paper Theorem 10.2):

.. math::
    H(s) = L(s)^{-1} = \\sum_{j=1}^{m_0} \\frac{R_j}{(s - \\lambda_0)^j} + E(s),
    \\qquad E \\text{ holomorphic near } \\lambda_0,

with ``m_0 <= m`` the length of the longest Jordan chain.  The residues are
contour integrals over a circle that encloses lam0 and no other eigenvalue,

.. math::
    R_j = \\frac{1}{2\\pi i}\\oint H(s)\\,(s - \\lambda_0)^{j-1}\\,ds,

evaluated by the trapezoidal rule (exponentially convergent: the error decays
like ``(r_in / r)^N + (r / r_out)^N`` for a cluster inside ``r_in`` and the next
eigenvalue beyond ``r_out``; both ratios are kept at most 1/2).  A computed multiple root is a cluster of nearby
eigenvalues (a double root splits by about sqrt(eps)); the contour integral sees
the whole cluster and is insensitive to the splitting, which is why it is
robust where residues of the individual computed poles are not.

The number of eigenvalues inside a circle comes from the argument principle,
``m = (1/2 pi i) oint p'/p ds = (1/2 pi i) oint trace(H(s) L'(s)) ds``, with the same
samples: no eigensolver is involved.
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import EigenvalueNotIsolatedError, NotAnEigenvalueError, ParameterError
from ..adjoint._circle import chunks
from ..adjoint._util import EPS, check_system, complex_scalar, natural_scale, positive

__all__ = ["Residues", "residues", "principal_part_residual"]

#: Default: eigenvalues within cluster_tol * max(|lam0|, scale) of lam0 are the root lam0 (the
#: spectral module's default too: rounding splits a root with chains of length p by about
#: eps^(1/p), 1.5e-8 for p = 2 and 6e-6 for p = 3).
CLUSTER_TOL = 1e-5
#: Default number of trapezoidal points on the contour.
N_POINTS = 64
#: Ratio between successive radii when looking for the next eigenvalue.
GROWTH = 4.0
#: Largest radius searched, in units of the scale max(|lam0|, natural scale).
MAX_RADIUS = 1e4
#: A contour count is accepted as an integer when within this of one.
COUNT_TOL = 0.05


class Residues(list):
    """``[R_1, ..., R_m0]``: the principal part of H at a root, with its error figures.

    A plain list of (n, n) complex arrays; ``H(s) ~ sum_j R_j / (s - center)^j``.

    Attributes
    ----------
    lam0 : complex
        The point asked for [1/s].
    center : complex
        Expansion point: the mean of the eigenvalues inside the contour (the
        exact root when lam0 is one; lam0 itself when that mean is within
        rounding of it).
    multiplicity : int
        Algebraic multiplicity m of the root (eigenvalues counted inside the
        contour by the argument principle).
    order : int
        Pole order m0 <= m (the longest Jordan chain): trailing residues that are
        zero to their error bound are dropped, so ``len(self) == order``.
    count : float
        The argument-principle integral before rounding (an integer up to
        quadrature and rounding error).
    radius : float
        Contour radius [1/s].
    inner, outer : float
        Cluster radius and the radius where the next eigenvalue was detected [1/s].
    n_points : int
    errors : (m,) ndarray
        A-posteriori absolute error bounds of ``R_1 ... R_m`` (Frobenius):
        difference between N- and N/2-point rules plus the rounding of the
        solves.
    error : float
        ``max_j errors_j / r^j`` relative to ``max_j ||R_j|| / r^j`` (relative
        error of the principal part on the contour).
    residual : float
        Relative residual of the principal-part equations
        ``sum_i L^{(i)}(c)/i! R_{q+i} = 0`` (q = 1 ... m) from ``L H = H L = I``
        (:func:`principal_part_residual`).
    elapsed : float
        Seconds.
    """

    _meta = (
        "lam0",
        "center",
        "multiplicity",
        "order",
        "count",
        "radius",
        "inner",
        "outer",
        "n_points",
        "errors",
        "error",
        "residual",
        "elapsed",
    )

    def __init__(self, items=(), **meta):
        super().__init__(items)
        for key in self._meta:
            setattr(self, key, meta.get(key))

    def principal_part(self, s) -> np.ndarray:
        """``sum_j R_j / (s - center)^j`` at a scalar s [1/s]."""
        s = complex_scalar(s, "s")
        if s == self.center:
            raise ParameterError("s", "the principal part has a pole at its center")
        out = np.zeros_like(self[0]) if len(self) else None
        for j, R in enumerate(self, start=1):
            out = out + R / (s - self.center) ** j
        return out

    def __repr__(self) -> str:
        return (
            f"Residues(lam0={self.lam0:.6g}, multiplicity={self.multiplicity}, order={self.order}, "
            f"radius={self.radius:.2e}, error={self.error:.1e}, residual={self.residual:.1e})"
        )


def _samples(sys, center: complex, r: float, N: int):
    """H(s_l), trace(H L'), ||L||, ||H|| on the circle ``s_l = center + r exp(2 pi i l / N)``."""
    n = sys.n
    M, C, K = (np.asarray(a, dtype=complex) for a in (sys.M, sys.C, sys.K))
    s = center + r * np.exp(2j * np.pi * np.arange(N) / N)
    H = np.empty((N, n, n), dtype=complex)
    trace = np.empty(N, dtype=complex)
    nL = np.empty(N)
    eye = np.eye(n)
    for sl in chunks(N, n):
        z = s[sl, None, None]
        L = z * z * M + z * C + K
        try:
            Hs = np.linalg.solve(L, np.broadcast_to(eye, L.shape))
        except np.linalg.LinAlgError:
            # an eigenvalue exactly on the contour: the caller moves the circle
            return None
        H[sl] = Hs
        dL = 2 * z * M + C
        trace[sl] = np.einsum("kij,kji->k", Hs, dL)
        nL[sl] = np.linalg.norm(L.reshape(len(z), -1), axis=1)
    nH = np.linalg.norm(H.reshape(N, -1), axis=1)
    return s, H, trace, nL, nH


def _count(sys, center, r, N, strict: bool = True):
    """Argument-principle count of eigenvalues inside ``|s - center| < r`` and the samples.

    When eigenvalues lie near every circle tried (the count is not an integer),
    raise, or return None with ``strict=False``.
    """
    for factor in (1.0, 1.137, 0.891, 1.291):
        rr = r * factor
        out = _samples(sys, center, rr, N)
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


def principal_part_residual(sys, center, R) -> float:
    """Relative residual of the principal-part equations of ``L H = H L = I`` at ``center``.

    .. math::
        \\max_{q=1..m} \\frac{\\|\\sum_{i=0}^{2} L_i R_{q+i}\\|}{\\sum_{i} \\ell_i \\|R_{q+i}\\|},
        \\quad L_0 = L(c),\\ L_1 = 2 c M + C,\\ L_2 = M,\\ R_{k>m} = 0

    and the same with the products reversed (Frobenius norms), with the
    coefficient scales ``l_0 = |c|^2 ||M|| + |c| ||C|| + ||K||``,
    ``l_1 = 2 |c| ||M|| + ||C||``, ``l_2 = ||M||`` (as in the backward error).
    """
    sys = check_system(sys)
    c = complex_scalar(center, "center")
    Ls = [sys.dynamic_stiffness(c), 2 * c * sys.M + sys.C, np.asarray(sys.M, dtype=complex)]
    # scales of the coefficients (not their values, which vanish at a critically damped root)
    m_, c_, k_ = (np.linalg.norm(x) for x in (sys.M, sys.C, sys.K))
    a = abs(c)
    nL = [a * a * m_ + a * c_ + k_, 2 * a * m_ + c_, m_]
    m = len(R)
    worst = 0.0
    for q in range(1, m + 1):
        left = np.zeros_like(R[0])
        right = np.zeros_like(R[0])
        den = 0.0
        for i in range(3):
            if q + i <= m:
                Rq = R[q + i - 1]
                left = left + Ls[i] @ Rq
                right = right + Rq @ Ls[i]
                den += nL[i] * np.linalg.norm(Rq)
        if den > 0:
            worst = max(worst, float(max(np.linalg.norm(left), np.linalg.norm(right)) / den))
    return worst


def residues(
    sys,
    lam0,
    *,
    cluster_tol: float = CLUSTER_TOL,
    n_points: int = N_POINTS,
    radius: float | None = None,
) -> Residues:
    """Residues ``[R_1, ..., R_m0]`` of ``H = L^{-1}`` at a root lam0 of any multiplicity.

    .. math::
        H(s) \\approx \\sum_{j=1}^{m_0} \\frac{R_j}{(s-\\lambda_0)^j},\\qquad
        R_j = \\frac{1}{2\\pi i}\\oint H(s)(s-\\lambda_0)^{j-1} ds

    (SPEC section 4, paper Theorem 10.2).  For a simple root ``R_1 = x y^T`` with
    ``y^T L'(lam0) x = 1`` (Lancaster) ``= adj L(lam0) / p'(lam0)``.

    The contour: eigenvalues within ``r_in = cluster_tol * max(|lam0|, scale)``
    of lam0 form the root (counted by the argument principle, m of them); the
    circle grows by factors of 4 until the count changes; the contour radius is
    half the last radius with an unchanged count, so that both aliasing ratios
    are at most 1/2 (error ~ 2^-N).  Residues are then computed
    about the mean of the enclosed eigenvalues (``.center``).

    Parameters
    ----------
    sys : LinearizedSystem
    lam0 : complex
        The root [1/s], for example from :func:`pinlin.modal_analysis`.
    cluster_tol : float
        Relative radius of the cluster taken as one root (default 1e-5, as in
        :func:`pinlin.modal_analysis`: a root with a chain of length p computed
        in double precision splits by about eps^(1/p), 1.5e-8 for p = 2 and 6e-6
        for p = 3; raise it for longer chains, lower it to separate distinct
        eigenvalues closer than that).
    n_points : int
        Trapezoidal points on the contour (default 64, even).
    radius : float, optional
        Contour radius [1/s] to use instead of the automatic choice (the count
        at this radius is the multiplicity).

    Returns
    -------
    Residues
        A list ``[R_1, ..., R_m0]`` of (n, n) complex arrays with ``center``,
        ``multiplicity``, ``errors``, ``error``, ``residual`` and more.

    Raises
    ------
    ParameterError
        Bad arguments.
    NotAnEigenvalueError
        No eigenvalue within ``cluster_tol`` of lam0.
    EigenvalueNotIsolatedError
        Another eigenvalue lies within 4 r_in: no contour separates the root.
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam0 = complex_scalar(lam0, "lam0")
    positive(cluster_tol, "cluster_tol")
    if not isinstance(n_points, (int, np.integer)) or n_points < 8 or n_points % 2:
        raise ParameterError("n_points", f"expected an even integer >= 8, got {n_points!r}")
    N = int(n_points)
    scale = max(abs(lam0), natural_scale(sys))
    if radius is not None:
        r = positive(radius, "radius")
        m, count, r, samples = _count(sys, lam0, r, N)
        if m == 0:
            raise NotAnEigenvalueError(
                f"no eigenvalue inside the circle of radius {r:.3e} around lam0 = {lam0:.10g}",
                lam=lam0,
                distance=r / scale,
            )
        inner = outer = r
    else:
        inner = cluster_tol * scale
        m, count, inner, samples = _count(sys, lam0, inner, N)
        if m == 0:
            L = sys.dynamic_stiffness(lam0)
            sv = np.linalg.svd(L, compute_uv=False)
            raise NotAnEigenvalueError(
                f"lam0 = {lam0:.10g} is not an eigenvalue: none lies within cluster_tol * scale = "
                f"{inner:.3e} of it (the smallest singular value of L(lam0) is {sv[-1] / sv[0]:.2e} of "
                f"the largest)",
                lam=lam0,
                distance=float(sv[-1] / sv[0]),
            )
        last = inner
        outer = np.inf
        rr = inner
        while rr < MAX_RADIUS * scale:
            rr *= GROWTH
            found = _count(sys, lam0, rr, N, strict=False)
            if found is None or found[0] != m:  # (no integer count: eigenvalues near this circle)
                outer = rr
                break
            last = found[2]
            rr = last
        if last == inner:
            raise EigenvalueNotIsolatedError(
                f"the root at lam0 = {lam0:.10g} ({m} eigenvalue(s) within {inner:.3e}) is not isolated: "
                f"another eigenvalue lies within {outer:.3e}; a larger cluster_tol merges it into the root, "
                f"a smaller one may separate them",
                lam=lam0,
                inner=inner,
                outer=outer,
            )
        # the next eigenvalue is beyond `last`, the cluster inside `inner <= last / 4`: half of
        # `last` keeps both aliasing ratios (inner / r, r / outer) <= 1/2 and H on the contour small
        # (with no other eigenvalue up to the scale, a contour larger than the scale only
        # adds rounding to the center)
        r = min(0.5 * last, scale)
        m_final, count, r, samples = _count(sys, lam0, r, N)
        if m_final != m:
            raise EigenvalueNotIsolatedError(
                f"the eigenvalue count around lam0 = {lam0:.10g} is {m} at radius {inner:.3e} but "
                f"{m_final} at {r:.3e} inside the region found free of other eigenvalues",
                lam=lam0,
                inner=inner,
                outer=outer,
            )
    s, H, trace, nL, nH = samples
    w = s - lam0  # ds / (2 pi i) = (s - lam0) dtheta / (2 pi) on this circle
    shift = complex(np.mean(trace * w * w)) / m
    shift_rounding = 10 * EPS * float(np.max(np.abs(trace * w * w))) * N**0.5 / m
    center = lam0 + shift if abs(shift) > shift_rounding else lam0
    d = s - center
    R_full, R_half = [], []
    for j in range(1, m + 1):
        f = H * (d ** (j - 1) * w)[:, None, None]
        R_full.append(f.mean(axis=0))
        R_half.append(f[::2].mean(axis=0))
    rounding = EPS * float(np.max(nL * nH * nH)) * N**0.5
    norms = np.array([np.linalg.norm(R) for R in R_full])
    powers = r ** np.arange(1, m + 1, dtype=float)
    size = float(np.max(norms / powers))
    # the trapezoidal error decays geometrically in N: from the N/2-point difference d, the
    # N-point error is about d^2 / (size of the integrand's contribution)
    diff = np.array([np.linalg.norm(a - b) for a, b in zip(R_full, R_half)])
    ref = np.maximum(size * powers, diff)
    with np.errstate(invalid="ignore", divide="ignore"):
        quad = np.where(ref > 0, diff * diff / ref, 0.0)
    errors = quad + rounding * powers
    # drop trailing residues that are zero to their error: the pole order is the longest chain
    order = m
    while order > 1 and norms[order - 1] <= 2 * errors[order - 1]:
        order -= 1
    error = float(np.max(errors / powers) / size) if size > 0 else float("inf")
    R = [np.asarray(x) for x in R_full[:order]]
    return Residues(
        R,
        lam0=lam0,
        center=center,
        multiplicity=m,
        order=order,
        count=count,
        radius=r,
        inner=inner,
        outer=float(outer),
        n_points=N,
        errors=errors,
        error=error,
        residual=principal_part_residual(sys, center, R),
        elapsed=time.perf_counter() - t0,
    )
