"""The linearized power theorem: an energy budget along a trajectory (theory: responses).

.. math::
    E = \\tfrac12 \\dot x^T M \\dot x + \\tfrac12 x^T S x, \\qquad
    \\frac{dE}{dt} = -\\dot x^T D \\dot x - \\dot x^T N x + \\dot x^T f

The gyroscopic forces do no work (x'^T G x' = 0 for skew G); the circulatory
forces do, which is how they can feed flutter.  Along a trajectory of
M x'' + C x' + K x = f, E(t) - E(0) equals the work W(t) of damping,
circulatory and applied forces; their difference is the balance residual.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..errors import ComputationError
from ..linearization.system import LinearizedSystem, check_system
from ..numerics.arrays import check_samples, check_times
from ..results import Result
from .sampled_force import SampledForce, check_interpolation, sample_callable

__all__ = ["EnergyBudget", "energy_budget", "METHOD"]


#: What :func:`energy_budget` computes and how (``EnergyBudget.method``).
METHOD = "linearized power theorem; work by the two-point Hermite rule of order 6 (derivatives from the equation)"


@dataclass(frozen=True, repr=False, eq=False)
class EnergyBudget(Result):
    """Energy, powers and work along a trajectory (theory: responses).

    Attributes
    ----------
    t : (K,) ndarray
        Times [s].
    kinetic, potential, energy : (K,) ndarray
        1/2 x'^T M x', 1/2 x^T S x and their sum E [J].
    power_damping, power_circulatory, power_force : (K,) ndarray
        -x'^T D x', -x'^T N x, x'^T f [W].
    power_gyroscopic : (K,) ndarray
        -x'^T G x': zero in exact arithmetic, shown as a rounding check [W].
    work_damping, work_circulatory, work_force : (K,) ndarray
        Their integrals from t_0 [J].
    work : (K,) ndarray
        Total work W(t).
    residual : (K,) ndarray
        E(t) - E(t_0) - W(t) [J].
    scale : float
        max |E| + the integral of |P_D| + |P_N| + |P_f| [J]: what ``residual`` is relative to.
    balance_residual : float
        max |residual| / scale (0 when scale is 0).
    quadrature_error : float
        Estimate of the relative error of the work integrals (difference between
        the fifth- and third-order Hermite rules, an upper bound for the former);
        if it is not well below ``balance_residual`` the sampling is too coarse
        for the residual to mean anything.
    elapsed : float
        Seconds.
    method : str
        How the work was integrated.
    error : float
        The headline figure: ``balance_residual`` (relative to ``scale``).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])
    >>> budget = pinlin.forced_response(sys, np.linspace(0.0, 1.0, 41), None, [0.1]).energy()
    >>> print(f"E0 = {budget.energy[0]:.6f} J, E1 = {budget.energy[-1]:.6f} J, "
    ...       f"damping work {budget.work_damping[-1]:.6f} J")
    E0 = 0.020000 J, E1 = 0.015825 J, damping work -0.004175 J
    """

    t: np.ndarray
    kinetic: np.ndarray
    potential: np.ndarray
    energy: np.ndarray
    power_damping: np.ndarray
    power_circulatory: np.ndarray
    power_force: np.ndarray
    power_gyroscopic: np.ndarray
    work_damping: np.ndarray
    work_circulatory: np.ndarray
    work_force: np.ndarray
    work: np.ndarray
    residual: np.ndarray
    scale: float
    balance_residual: float
    quadrature_error: float
    elapsed: float
    method: str = METHOD

    @property
    def error(self) -> float:
        return self.balance_residual

    def __repr__(self) -> str:
        return (
            f"EnergyBudget(points={len(self.t)}, E0={self.energy[0]:.4g} J, E_end={self.energy[-1]:.4g} J, "
            f"W={self.work[-1]:.4g} J, balance_residual={self.balance_residual:.2e}, "
            f"quadrature_error={self.quadrature_error:.1e})"
        )


def _bilinear(a: np.ndarray, A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise a_k^T A b_k."""
    return np.einsum("ki,ij,kj->k", a, A, b)


def _power_derivatives(sys: LinearizedSystem, factor, x, xd, fe):
    """P and its first two time derivatives for each power term, at one end of each interval.

    ``fe`` is (k, 3, n): f, f', f'' at that end.  x'' and x''' come from the
    equation of motion: x^(j+2) = M^{-1} (f^(j) - C x^(j+1) - K x^(j)).
    """
    C, K, D, N = sys.C, sys.K, sys.D, sys.N
    f, f1, f2 = fe[:, 0], fe[:, 1], fe[:, 2]
    a, b = x, xd
    c = scipy.linalg.cho_solve(factor, (f - b @ C.T - a @ K.T).T).T
    d = scipy.linalg.cho_solve(factor, (f1 - c @ C.T - b @ K.T).T).T
    PD = (-_bilinear(b, D, b), -(_bilinear(c, D, b) + _bilinear(b, D, c)),
          -(_bilinear(d, D, b) + 2 * _bilinear(c, D, c) + _bilinear(b, D, d)))
    PN = (-_bilinear(b, N, a), -(_bilinear(c, N, a) + _bilinear(b, N, b)),
          -(_bilinear(d, N, a) + 2 * _bilinear(c, N, b) + _bilinear(b, N, c)))
    dot = lambda u, w: np.einsum("ki,ki->k", u, w)  # noqa: E731
    Pf = (dot(b, f), dot(c, f) + dot(b, f1), dot(d, f) + 2 * dot(c, f1) + dot(b, f2))
    return PD, PN, Pf


def energy_budget(
    sys: LinearizedSystem,
    t,
    x,
    xdot,
    f=None,
    *,
    interpolation: str = "linear",
) -> EnergyBudget:
    """Energy budget of a trajectory of the linearized system (theory: responses).

    E(t) = 1/2 x'^T M x' + 1/2 x^T S x is evaluated at the samples; the work of
    damping, circulatory and applied forces is integrated interval by interval
    with the two-point Hermite rule of order 6,

    .. math::
        \\int_0^h P = \\frac h2 (P_0 + P_1) + \\frac{h^2}{10} (P_0' - P_1')
        + \\frac{h^3}{120} (P_0'' + P_1'') + O(h^7),

    where P' and P'' use x'' and x''' from the equation of motion at the
    samples (so the rule needs no samples between them).  The balance residual
    E(t) - E(t_0) - W(t) then measures how well the samples (x, x') follow the
    equation between one another: it is at rounding level for an exact
    response sampled finely enough (h |lam|_max below about 0.3 for 1e-10), and
    it is large for a trajectory that does not solve the equation.

    Parameters
    ----------
    sys : LinearizedSystem
    t : (K,) array
        Strictly increasing times [s].
    x, xdot : (K, n) arrays
        Displacements and velocities at t.
    f : None, (K, n) array or callable
        Applied generalized force at t (a callable ``f(t) -> (n,)`` is sampled
        at t); between samples it is read as ``interpolation`` says, the same
        reading :func:`~pinlin.forced_response` uses.
    interpolation : {"linear", "cubic"}

    Returns
    -------
    EnergyBudget

    Raises
    ------
    ParameterError
        Wrong shapes, non-finite values, a bad time grid, an unknown interpolation.
    ComputationError
        The energies or powers overflow double precision.

    Examples
    --------
    The damped oscillator x'' + 0.2 x' + 4 x = 0 loses to damping what its energy drops by:

    >>> sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])
    >>> t = np.linspace(0.0, 1.0, 41)
    >>> resp = pinlin.forced_response(sys, t, None, [0.1])
    >>> budget = pinlin.energy_budget(sys, t, resp.x, resp.xdot)
    >>> print(f"{budget.energy[-1] - budget.energy[0]:.6f} J = {budget.work_damping[-1]:.6f} J")
    -0.004175 J = -0.004175 J
    >>> bool(budget.balance_residual < 1e-10)
    True
    """
    t0 = time.perf_counter()
    check_system(sys)
    n = sys.n
    times = check_times(t)
    check_interpolation(interpolation)
    k = len(times)
    X = check_samples(x, k, n, "x")
    V = check_samples(xdot, k, n, "xdot")
    if f is None:
        F = np.zeros((k, n))
    elif callable(f):
        F = sample_callable(f, times, n)
    else:
        F = check_samples(f, k, n, "f")

    kinetic = 0.5 * _bilinear(V, sys.M, V)
    potential = 0.5 * _bilinear(X, sys.S, X)
    energy = kinetic + potential
    P_D = -_bilinear(V, sys.D, V)
    P_N = -_bilinear(V, sys.N, X)
    P_f = np.einsum("ki,ki->k", V, F)
    P_G = -_bilinear(V, sys.G, V)

    works = [np.zeros(k) for _ in range(3)]
    quad_err = 0.0
    if k > 1:
        h = np.diff(times)
        left, right = SampledForce(times, F, interpolation).ends()
        factor = scipy.linalg.cho_factor(sys.M)
        ends0 = _power_derivatives(sys, factor, X[:-1], V[:-1], left)
        ends1 = _power_derivatives(sys, factor, X[1:], V[1:], right)
        err = np.zeros(k - 1)
        for i, (p0, p1) in enumerate(zip(ends0, ends1)):
            trap = h / 2 * (p0[0] + p1[0])
            fifth = trap + h**2 / 10 * (p0[1] - p1[1]) + h**3 / 120 * (p0[2] + p1[2])
            third = trap + h**2 / 12 * (p0[1] - p1[1])
            works[i][1:] = np.cumsum(fifth)
            err += np.abs(fifth - third)
        quad_err = float(np.sum(err))
    W_D, W_N, W_f = works
    work = W_D + W_N + W_f
    residual = energy - energy[0] - work
    absP = np.abs(P_D) + np.abs(P_N) + np.abs(P_f)
    scale = float(np.max(np.abs(energy)))
    if k > 1:
        scale += float(np.sum(np.diff(times) * (absP[:-1] + absP[1:]) / 2))
    rel = float(np.max(np.abs(residual)) / scale) if scale > 0 else 0.0
    if not (np.isfinite(rel) and np.isfinite(scale)):
        raise ComputationError(
            "energy_budget: the energies or powers overflow double precision (entries of x, xdot or f "
            "near the largest double); rescale the trajectory"
        )
    return EnergyBudget(
        t=times,
        kinetic=kinetic,
        potential=potential,
        energy=energy,
        power_damping=P_D,
        power_circulatory=P_N,
        power_force=P_f,
        power_gyroscopic=P_G,
        work_damping=W_D,
        work_circulatory=W_N,
        work_force=W_f,
        work=work,
        residual=residual,
        scale=scale,
        balance_residual=rel,
        quadrature_error=quad_err / scale if scale > 0 else 0.0,
        elapsed=time.perf_counter() - t0,
    )
