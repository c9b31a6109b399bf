"""How the eigenvalues move with a parameter: d lambda / dp (theory: boundaries).

For L(lam, p) = lam^2 M(p) + lam C(p) + K(p) and L_p = dL/dp at fixed lam:

- a simple eigenvalue with right x and left y (y^T L(lam) = 0):

  .. math::  \\frac{d\\lambda}{dp} = -\\frac{y^T L_p(\\lambda) x}{y^T L'(\\lambda) x},
             \\qquad L'(\\lambda) = 2\\lambda M + C;

- a semisimple eigenvalue of multiplicity m, right basis X, left basis Y: the m
  derivatives are the eigenvalues of -(Y^T L' X)^{-1} Y^T L_p X (the projected
  problem; with Y^T L' X = I as :func:`pinlin.modal_analysis` normalizes it);
- a defective eigenvalue (a Jordan chain of length k) is not differentiable:
  lam(p) - lam0 ~ c (p - p0)^(1/k) (a Puiseux series).  No number is given for
  its derivative; for k = 2 (one chain x0, x1, left null vector y) the
  coefficient is reported,

  .. math::  c^2 = -\\frac{y^T L_p x_0}{y^T (L' x_1 + M x_0)},
             \\qquad \\lambda - \\lambda_0 \\approx \\pm c \\sqrt{p - p_0}.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..numerics.arrays import readonly
from ..results import Result
from ..spectral import Modes, jordan_chains
from .derivatives import (
    EPS,
    RICHARDSON_LEVELS,
    STEP_FRACTION,
    MatrixDerivatives,
    exact_derivatives,
    richardson_derivatives,
)
from .evaluation import Evaluator, check_parameter

__all__ = ["EigenvalueSensitivity", "eigenvalue_sensitivity", "eigen_derivatives", "EigenDerivatives",
           "simple_derivative", "cluster_derivatives", "FORMULA_ROUNDING"]

#: Rounding of the sensitivity formula itself: a few eps times the size of its terms (two inner products
#: and a division, each a few ulps).
FORMULA_ROUNDING = 4.0

_SIMPLE = "simple"


@dataclass(frozen=True, kw_only=True)
class EigenDerivatives:
    """d lam / dp for every eigenvalue of one modal analysis (see :func:`eigen_derivatives`)."""

    derivatives: np.ndarray
    error: np.ndarray
    differentiable: np.ndarray
    status: tuple[str, ...]
    puiseux: tuple[dict, ...]


def _dynamic(sys, lam):
    return lam * lam * sys.M + lam * sys.C + sys.K


def _gaps(lam: np.ndarray) -> np.ndarray:
    d = np.abs(lam[:, None] - lam[None, :])
    np.fill_diagonal(d, np.inf)
    return d.min(axis=1) if lam.size > 1 else np.full(lam.shape, np.inf)


def simple_derivative(modes: Modes, k: int, dL: MatrixDerivatives, gap: float) -> tuple[complex, float]:
    """d lam_k / dp of a simple eigenvalue and its estimated absolute error (``gap``: distance to the nearest other)."""
    sys = modes.system
    lam, x, y = modes.eigenvalues[k], modes.right[:, k], modes.left[:, k]
    Lp = dL.dynamic(lam)
    den = y @ ((2 * lam) * (sys.M @ x) + sys.C @ x)
    d = -(y @ (Lp @ x)) / den
    scale = np.linalg.norm(x) * np.linalg.norm(y) / abs(den)
    err = scale * (dL.dynamic_error(lam) + FORMULA_ROUNDING * EPS * np.linalg.norm(Lp))
    # first order: x and y are off by about (eigenvalue error) / (distance to the nearest other eigenvalue)
    err += abs(d) * min(1.0, modes.error_bound[k] / gap)
    return complex(d), float(err)


def cluster_derivatives(modes: Modes, idx: list[int], center: complex, dL: MatrixDerivatives):
    """The derivatives of a semisimple cluster (eigenvalues of the projected problem), sorted, and their error."""
    sys = modes.system
    X, Y = modes.right[:, idx], modes.left[:, idx]
    A = Y.T @ ((2 * center) * (sys.M @ X) + sys.C @ X)
    Lp = dL.dynamic(center)
    B = Y.T @ (Lp @ X)
    values = np.linalg.eigvals(-np.linalg.solve(A, B))
    scale = np.linalg.norm(np.linalg.inv(A), 2) * np.linalg.norm(X, 2) * np.linalg.norm(Y, 2)
    err = scale * (dL.dynamic_error(center) + FORMULA_ROUNDING * EPS * np.linalg.norm(Lp))
    return np.sort_complex(values), float(err)


def _puiseux(modes: Modes, cluster, dL: MatrixDerivatives) -> dict:
    """Order and (for a single chain of length 2) coefficient of the Puiseux series of a defective eigenvalue."""
    sys, lam0 = modes.system, complex(cluster.center)
    entry: dict[str, Any] = {"indices": tuple(int(i) for i in cluster.indices), "center": lam0,
                             "order": int(cluster.index), "coefficient": None}
    if tuple(cluster.partial) != (2,):
        return entry
    chains = jordan_chains(sys, lam0)
    if len(chains) != 1 or len(chains[0]) != 2:
        return entry
    x0, x1 = chains[0]
    U, _, _ = np.linalg.svd(_dynamic(sys, lam0))
    y = U[:, -1].conj()  # y^T L(lam0) = 0
    den = y @ ((2 * lam0) * (sys.M @ x1) + sys.C @ x1 + sys.M @ x0)
    entry["coefficient"] = complex(np.sqrt(-(y @ (dL.dynamic(lam0) @ x0)) / den))
    return entry


def eigen_derivatives(modes: Modes, dL: MatrixDerivatives, *, puiseux: bool = True) -> EigenDerivatives:
    """d lam_k / dp for every eigenvalue of ``modes`` given L_p (see the module docstring).

    Defective and undecided clusters get NaN with ``differentiable`` False and a
    status saying why; their Puiseux order (and coefficient for one chain of
    length 2, when ``puiseux``) is listed instead.
    """
    lam = modes.eigenvalues
    m = lam.shape[0]
    der = np.full(m, np.nan + 0j)
    err = np.full(m, np.nan)
    ok = np.zeros(m, dtype=bool)
    status = [_SIMPLE] * m
    series = []
    in_cluster = np.zeros(m, dtype=bool)
    for c in modes.clusters:
        idx = list(c.indices)
        in_cluster[idx] = True
        if not c.consistent:
            for i in idx:
                status[i] = f"undetermined: the Jordan structure of this cluster could not be decided ({c.note})"
        elif c.semisimple:
            values, e = cluster_derivatives(modes, idx, complex(c.center), dL)
            order = sorted(idx, key=lambda i: (lam[i].real, lam[i].imag))
            der[order], err[order], ok[order] = values, e, True
            for i in idx:
                status[i] = f"semisimple (multiplicity {c.algebraic}): eigenvalues of the projected problem"
        else:
            for i in idx:
                status[i] = (f"defective: not differentiable (Puiseux: lam - lam0 ~ c (p - p0)^(1/{c.index}), "
                             f"Jordan chains {tuple(c.partial)})")
            series.append(_puiseux(modes, c, dL) if puiseux else
                          {"indices": tuple(idx), "center": complex(c.center), "order": int(c.index),
                           "coefficient": None})
    gaps = _gaps(lam)
    for k in np.flatnonzero(~in_cluster):
        der[k], err[k] = simple_derivative(modes, int(k), dL, gaps[k])
        ok[k] = True
    return EigenDerivatives(
        derivatives=der, error=err, differentiable=ok, status=tuple(status), puiseux=tuple(series),
    )


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class EigenvalueSensitivity(Result):
    """d lam / dp of every eigenvalue of ``func(p)`` (theory: boundaries).

    Attributes
    ----------
    parameter : float
        p.
    eigenvalues : (2n,) complex
        lam_k [1/s], ordered as :func:`pinlin.modal_analysis` orders them.
    derivatives : (2n,) complex
        d lam_k / dp [1/s per unit of p].  NaN where ``differentiable`` is False
        (a defective or undecided eigenvalue: see ``status``), never a number there.
    derivative_error : (2n,) float
        Estimated absolute error of each derivative: the matrix derivatives' errors
        through the formula, its rounding, and the eigenvectors' first-order error
        (eigenvalue error bound over the distance to the nearest other eigenvalue).
    differentiable : (2n,) bool
    status : tuple of str
        Per eigenvalue: "simple", "semisimple (multiplicity m) ...", "defective: not
        differentiable (Puiseux ...)" or "undetermined ...".
    puiseux : tuple of dict
        One entry per defective cluster: ``indices``, ``center``, ``order`` k and,
        for a single chain of length 2, ``coefficient`` c with
        lam - lam0 ~ +-c sqrt(p - p0) (else None).
    matrix_derivatives : (3, n, n) ndarray
        dM/dp, dC/dp, dK/dp used.
    matrix_error : (3,) ndarray
        Their estimated absolute errors (Frobenius).
    evaluations : int
        Calls of ``func``.
    analyses : int
        Modal analyses (one).
    modes : Modes
        The modal analysis at p (not in ``to_dict``).
    method : str
        How the matrix derivatives were obtained, and the formula used.
    error : float
        Largest ``derivative_error`` over the differentiable eigenvalues, relative
        to the largest |d lam / dp| (inf when none is differentiable).
    elapsed : float
        Seconds [s].
    notes : tuple of str

    Examples
    --------
    >>> def family(p):
    ...     return pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.1]], [[1.0 - p]])
    >>> sens = pinlin.eigenvalue_sensitivity(family, 0.5)
    >>> sens.parameter, sens.differentiable.tolist()
    (0.5, [True, True])
    >>> bool(np.allclose(sens.derivatives, 1 / (2 * sens.eigenvalues + 0.1), rtol=1e-9))
    True
    """

    parameter: float
    eigenvalues: np.ndarray
    derivatives: np.ndarray
    derivative_error: np.ndarray
    differentiable: np.ndarray
    status: tuple[str, ...]
    puiseux: tuple[dict, ...]
    matrix_derivatives: np.ndarray
    matrix_error: np.ndarray
    evaluations: int
    analyses: int
    modes: Modes
    method: str
    elapsed: float
    notes: tuple[str, ...] = field(default=())

    _dict_exclude: ClassVar[tuple[str, ...]] = ("modes",)

    @property
    def error(self) -> float:
        ok = self.differentiable
        if not np.any(ok):
            return float("inf")
        scale = np.max(np.abs(self.derivatives[ok]))
        worst = float(np.max(self.derivative_error[ok]))
        return worst / scale if scale > 0 else worst

    def __repr__(self) -> str:
        ok = self.differentiable
        biggest = np.max(np.abs(self.derivatives[ok])) if np.any(ok) else float("nan")
        return (f"EigenvalueSensitivity(p={self.parameter:.6g}, eigenvalues={len(self.eigenvalues)}, "
                f"differentiable={int(np.sum(ok))}/{len(ok)}, max|dlam/dp|={biggest:.3g}, error={self.error:.1e}, "
                f"evaluations={self.evaluations}, elapsed={self.elapsed:.3g}s)")


def eigenvalue_sensitivity(
    func: Callable[[float], Any],
    p,
    *,
    derivative: Callable[[float], Any] | None = None,
    step: float | None = None,
    levels: int = RICHARDSON_LEVELS,
    modal_options: Mapping[str, Any] | None = None,
) -> EigenvalueSensitivity:
    """d lambda / dp of every eigenvalue of the system ``func(p)`` (theory: boundaries).

    Parameters
    ----------
    func : callable
        ``func(p) -> LinearizedSystem``; when p moves the equilibrium, ``func``
        should find it again (``find_equilibrium`` then ``linearize``): its
        differences then include the shift dq/dp (K dq/dp = -dr/dp) exactly as the
        total derivative requires (see :mod:`pinlin.boundaries.derivatives`).
    p : float
        The parameter value [its own unit].
    derivative : callable, optional
        ``derivative(p) -> (dM, dC, dK)``, the exact total derivatives of the
        matrices (including the equilibrium's shift).  Without it, central
        differences with Richardson extrapolation are used and their error is
        estimated and reported.
    step : float, optional
        First difference step [unit of p]; default ``STEP_FRACTION`` |p| (or
        ``STEP_FRACTION`` when p = 0).
    levels : int
        Number of difference steps (h, h/2, ...), at least 2; 2 ``levels`` calls of ``func``.
    modal_options : mapping, optional
        Passed to :func:`pinlin.modal_analysis`.

    Returns
    -------
    EigenvalueSensitivity

    Raises
    ------
    ParameterError
        p not finite, bad ``step`` or ``levels``, ``func`` not callable.
    SystemFunctionError
        ``func`` or ``derivative`` raised, or returned a wrong value, or systems of
        different sizes.

    Examples
    --------
    lam^2 + 0.1 lam + 1 - p = 0, so d lam / dp = 1 / (2 lam + 0.1):

    >>> def family(p):
    ...     return pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.1]], [[1.0 - p]])
    >>> sens = pinlin.eigenvalue_sensitivity(family, 0.5)
    >>> np.round(sens.derivatives, 6)
    array([...-0.708881j, ...+0.708881j])
    """
    t0 = time.perf_counter()
    p = check_parameter(p, "p")
    ev = Evaluator(func, modal_options)
    modes = ev.modes(p)
    n = modes.n
    if derivative is not None:
        dL = exact_derivatives(derivative, p, n)
    else:
        h = STEP_FRACTION * (abs(p) if p != 0 else 1.0) if step is None else check_parameter(step, "step")
        dL = richardson_derivatives(ev, p, h, levels)
    result = eigen_derivatives(modes, dL)
    notes = []
    if step is None and derivative is None and p == 0:
        notes.append(f"p = 0: the difference step defaults to {STEP_FRACTION:g} in the unit of p; pass step= to choose it")
    if not np.all(result.differentiable):
        notes.append(f"{int(np.sum(~result.differentiable))} eigenvalue(s) not differentiable (see status)")
    return EigenvalueSensitivity(
        parameter=p,
        eigenvalues=readonly(modes.eigenvalues),
        derivatives=readonly(result.derivatives),
        derivative_error=readonly(result.error),
        differentiable=readonly(result.differentiable),
        status=result.status,
        puiseux=result.puiseux,
        matrix_derivatives=readonly(dL.stack),
        matrix_error=readonly(dL.error),
        evaluations=ev.calls,
        analyses=ev.analyses,
        modes=modes,
        method=f"{dL.method}; d lam/dp = -y^T L_p x / (y^T L' x)",
        elapsed=time.perf_counter() - t0,
        notes=tuple(notes),
    )
