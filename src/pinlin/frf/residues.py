"""Residues of the dynamic flexibility at a root of any multiplicity (theory: flexibility, paper Sec. 10).

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
eigenvalue beyond ``r_out``; both ratios are kept at most 1/2).  For one pole
outside at q r the N-point rule's error is exactly q^(N/2) times the difference
between the N/2- and N-point rules: the error bounds use that difference times
x >= |q|^(N/2) from the geometry (an estimate from the difference alone
is not a bound).  A computed multiple root is a cluster of nearby
eigenvalues (a double root splits by about sqrt(eps)); the contour integral sees
the whole cluster and is insensitive to the splitting, which is why it is
robust where residues of the individual computed poles are not.

The number of eigenvalues inside a circle comes from the argument principle,
``m = (1/2 pi i) oint p'/p ds = (1/2 pi i) oint trace(H(s) L'(s)) ds``, with the same
samples: no eigensolver is involved (:mod:`pinlin.frf.contour`).
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import ParameterError
from ..linearization.system import check_system
from ..numerics import (
    CLUSTER_TOL,
    EPS,
    check_integer,
    check_tolerance,
    complex_scalar,
    natural_scale,
)
from ..results import Result
from .contour import automatic_contour, fixed_contour

__all__ = ["Residues", "residues", "principal_part_residual", "aliasing_ratio", "GEOMETRY_SAFETY"]

# Default cluster_tol: eigenvalues within CLUSTER_TOL * max(|lam0|, scale) of lam0 are the root lam0
# (pinlin.numerics.CLUSTER_TOL, the spectral module's default too).
#: Default number of trapezoidal points on the contour.
N_POINTS = 64
#: A shift of the center below this many rounding units of the integrand is rounding, not a
#: displaced root (the center then stays at lam0).
SHIFT_ROUNDING = 10.0
#: Trailing residues smaller than this multiple of their error bound are zero: the pole order
#: is the longest Jordan chain.
ZERO_RESIDUE_FACTOR = 2.0
#: The distances of the other eigenvalues from lam0 are taken GEOMETRY_SAFETY error bounds
#: closer (and those inside farther): the bounds are first-order estimates, and the
#: stability verdict trusts them with the same factor (pinlin.spectral.STABILITY_SAFETY).
GEOMETRY_SAFETY = 10.0


class Residues(list, Result):
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
        ``x ||R_j(N/2) - R_j(N)|| + rounding r^j``, with the aliasing ratio
        x = max((r / R)^(N/2), (rho / r)^(N/2)) from the geometry (R a lower bound
        of the distance of the nearest eigenvalue outside the circle, rho an upper
        bound of those inside; :func:`aliasing_ratio`) and the rounding of the
        solves.  For one simple pole outside at q r, the N-point rule's error is
        exactly q^(N/2) (R(N/2) - R(N)), so this is the error itself when R is exact
        and one pole is nearest, and a bound with x an upper bound of |q|^(N/2).
    error : float
        ``max_j errors_j / r^j`` relative to ``max_j ||R_j|| / r^j`` (relative
        error of the principal part on the contour).
    residual : float
        Relative residual of the principal-part equations
        ``sum_i L^{(i)}(c)/i! R_{q+i} = 0`` (q = 1 ... m) from ``L H = H L = I``
        (:func:`principal_part_residual`).
    method : str
        The quadrature: trapezoidal rule on a circle, H by LU (the direct
        method of :mod:`pinlin.frf.engine`).
    elapsed : float
        Seconds.

    ``to_dict()`` gives these and the residues themselves (``"residues"``).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> R = pinlin.residues(sys, pinlin.modal_analysis(sys).eigenvalues[0])
    >>> R.order, bool(R.error < 1e-10)
    (1, True)
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
        "method",
        "elapsed",
    )
    _dict_fields = _meta

    def __init__(self, items=(), **meta):
        super().__init__(items)
        for key in self._meta:
            setattr(self, key, meta.get(key))

    def principal_part(self, s) -> np.ndarray:
        """``sum_j R_j / (s - center)^j`` at a scalar s [1/s].

        Raises
        ------
        ParameterError
            s is not a finite complex number, or is the center (the pole).

        Examples
        --------
        Close to the pole, H(s) = L(s)^-1 is its principal part:

        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> R = pinlin.residues(sys, pinlin.modal_analysis(sys).eigenvalues[0])
        >>> s = R.center + 1e-4
        >>> P, H = R.principal_part(s), np.linalg.inv(sys.dynamic_stiffness(s))
        >>> P.shape, bool(np.linalg.norm(P - H) < 1e-3 * np.linalg.norm(H))
        ((2, 2), True)
        """
        s = complex_scalar(s, "s")
        if s == self.center:
            raise ParameterError("s", "the principal part has a pole at its center")
        out = np.zeros_like(self[0]) if len(self) else None
        for j, R in enumerate(self, start=1):
            out = out + R / (s - self.center) ** j
        return out

    def to_dict(self) -> dict:
        return Result.to_dict(self, extra={"residues": list(self)})

    @classmethod
    def _from_values(cls, values: dict) -> Residues:
        return cls(values["residues"], **{k: values.get(k) for k in cls._meta})

    def __repr__(self) -> str:
        return (
            f"Residues(lam0={self.lam0:.6g}, multiplicity={self.multiplicity}, order={self.order}, "
            f"radius={self.radius:.2e}, error={self.error:.1e}, residual={self.residual:.1e})"
        )


def principal_part_residual(sys, center, R) -> float:
    """Relative residual of the principal-part equations of ``L H = H L = I`` at ``center``.

    .. math::
        \\max_{q=1..m} \\frac{\\|\\sum_{i=0}^{2} L_i R_{q+i}\\|}{\\sum_{i} \\ell_i \\|R_{q+i}\\|},
        \\quad L_0 = L(c),\\ L_1 = 2 c M + C,\\ L_2 = M,\\ R_{k>m} = 0

    and the same with the products reversed (Frobenius norms), with the
    coefficient scales ``l_0 = |c|^2 ||M|| + |c| ||C|| + ||K||``,
    ``l_1 = 2 |c| ||M|| + ||C||``, ``l_2 = ||M||`` (as in the backward error).

    Raises
    ------
    ParameterError
        ``sys`` is not a LinearizedSystem or ``center`` not a finite complex number.
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


def aliasing_ratio(sys, lam0: complex, r: float, N: int, m: int, inner: float, free: float) -> tuple[float, str]:
    """x = max((r / R)^(N/2), (rho / r)^(N/2)) from the contour's geometry, and how R and rho were found.

    R is a lower bound of the distance from lam0 to the nearest eigenvalue outside
    the circle, rho an upper bound of the distance of those inside: from the
    eigenvalues of :func:`pinlin.modal_analysis` with :data:`GEOMETRY_SAFETY` times
    their error bounds when they agree with the contour's count m, else from the
    contour's own counts (``free``, the largest radius with count m, and ``inner``,
    the cluster radius).
    """
    from ..spectral import modal_analysis  # the spectral package builds on frf: imported at use

    modes = modal_analysis(sys)
    dist = np.abs(np.asarray(modes.eigenvalues) - lam0)
    slack = GEOMETRY_SAFETY * np.asarray(modes.error_bound)
    inside = dist < r
    R, rho, how = free, inner, "the contour's argument-principle counts"
    if int(np.sum(inside)) == m and np.all(dist[~inside] - slack[~inside] > r) and np.all(dist[inside] + slack[inside] < r):
        R = float(np.min(dist[~inside] - slack[~inside], initial=np.inf))
        rho = float(np.max(dist[inside] + slack[inside], initial=0.0))
        how = f"the computed eigenvalues with {GEOMETRY_SAFETY:g} times their error bounds"
    x_out = 0.0 if not np.isfinite(R) else min(1.0, (r / R) ** (N / 2)) if R > 0 else 1.0
    x_in = min(1.0, (rho / r) ** (N / 2))
    return max(x_out, x_in), how


def _principal_part(lam0, m, r, N, samples, x):
    """Center, residues R_1..R_m (N-point rule), their error bounds, the pole order and the relative error."""
    s, H, trace, nL, nH = samples
    w = s - lam0  # ds / (2 pi i) = (s - lam0) dtheta / (2 pi) on this circle
    shift = complex(np.mean(trace * w * w)) / m
    shift_rounding = SHIFT_ROUNDING * EPS * float(np.max(np.abs(trace * w * w))) * N**0.5 / m
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
    # the N-point rule's error e_N = q^(N/2) (R_{N/2} - R_N) for a pole outside at q r (inside at r / q),
    # |q|^(N/2) <= x from the geometry: exact for one nearest pole, a bound with x an upper bound
    diff = np.array([np.linalg.norm(a - b) for a, b in zip(R_full, R_half)])
    errors = x * diff + rounding * powers
    order = m
    while order > 1 and norms[order - 1] <= ZERO_RESIDUE_FACTOR * errors[order - 1]:
        order -= 1
    error = float(np.max(errors / powers) / size) if size > 0 else float("inf")
    return center, [np.asarray(v) for v in R_full[:order]], errors, order, error


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

    (theory: flexibility, paper Theorem 10.2).  For a simple root ``R_1 = x y^T`` with
    ``y^T L'(lam0) x = 1`` (Lancaster) ``= adj L(lam0) / p'(lam0)``.  H on the
    contour is evaluated by the direct method of the H(s) engine
    (:func:`pinlin.frf.engine.lu_solve`).

    The contour: eigenvalues within ``r_in = cluster_tol * max(|lam0|, scale)``
    of lam0 form the root (counted by the argument principle, m of them); the
    circle grows by factors of ``GROWTH`` until the count changes; the contour
    radius is ``CONTOUR_FRACTION`` of the last radius with an unchanged count, so
    that both aliasing ratios are at most 1/2 (error ~ 2^-N).  Residues are then
    computed about the mean of the enclosed eigenvalues (``.center``).

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
        Trapezoidal points on the contour (default 64, even, at least 8).
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
        Another eigenvalue lies within ``GROWTH`` r_in: no contour separates the root.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> lam = pinlin.modal_analysis(sys).eigenvalues[0]
    >>> R = pinlin.residues(sys, lam)
    >>> len(R), R.multiplicity
    (1, 1)
    >>> np.round(np.asarray(R[0]), 6)
    array([[0.-0.250313j, 0.-0.250313j],
           [0.-0.250313j, 0.-0.250313j]])
    """
    t0 = time.perf_counter()
    sys = check_system(sys)
    lam0 = complex_scalar(lam0, "lam0")
    cluster_tol = check_tolerance(cluster_tol, "cluster_tol")
    N = check_integer(n_points, "n_points", low=8)
    if N % 2:
        raise ParameterError("n_points", f"expected an even integer >= 8, got {n_points!r}")
    scale = max(abs(lam0), natural_scale(sys))
    if radius is not None:
        m, count, r, inner, free, outer, samples = fixed_contour(sys, lam0, radius, N, scale)
    else:
        m, count, r, inner, free, outer, samples = automatic_contour(sys, lam0, cluster_tol, N, scale)
    x, geometry = aliasing_ratio(sys, lam0, r, N, m, inner, free)
    center, R, errors, order, error = _principal_part(lam0, m, r, N, samples, x)
    return Residues(
        R,
        lam0=lam0,
        center=center,
        multiplicity=m,
        order=order,
        count=count,
        radius=r,
        inner=inner,
        outer=outer,
        n_points=N,
        errors=errors,
        error=error,
        residual=principal_part_residual(sys, center, R),
        method=(
            f"contour integral: trapezoidal rule, {N} points on a circle of radius {r:.3g}, H by LU; error bounds "
            f"with aliasing ratio {x:.2e} from {geometry}"
        ),
        elapsed=time.perf_counter() - t0,
    )
