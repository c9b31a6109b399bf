"""The orbit's own error in the coefficients of its variational equation (theory: Floquet).

A shooting result misses exact periodicity by its residual r = x(T) - x(0) (``PeriodicOrbit.error``, relative
to the orbit's excursion max_t ||x(t) - x(0)||).  To first order the exact orbit starts at s + ds with
(Phi - I) ds = -r, so ||ds|| <= ||r|| / sigma, sigma the smallest singular value of Phi - I (an autonomous
orbit: the next one, the time shift being free), and it runs at distance ||dx(t)|| <= ||Phi(t, 0)|| ||ds||.
The coefficients move with it: ||dA(t)|| <= S(t) ||dx(t)||, S(t) = (sum_i ||dA/dx_i||_F^2)^(1/2) by central
differences of A at the perturbed states (Pinocchio evaluations, the acceleration recomputed).  These block
bounds per step enter the multipliers through the same first-order terms as an interpolant's error
(:func:`.bounds.coefficient_terms`).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..linearization.state_form import first_order_form
from ..nonlinear.dynamics import FreeDynamics
from .coefficients import evaluate_point

__all__ = ["orbit_state_error", "orbit_coefficient_errors", "ORBIT_SAMPLES", "ORBIT_SLACK"]

#: Times per period at which the orbit's excursion is measured (its residual is relative to it).
ORBIT_SAMPLES = 64

#: Factor on the sensitivity S(t) and on ||dx(t)|| taken at the ends of a step, for their values inside it.
ORBIT_SLACK = 2.0

_FD_STEP = float(np.finfo(float).eps) ** (1 / 3)


def _tangent_state(scene, orbit, t: float) -> np.ndarray:
    y = orbit.solution(float(t) % orbit.period)
    nv, n = scene.model.nv, scene.n
    return np.concatenate([y[:nv][scene.free_dofs], y[nv:nv + n]])


def orbit_state_error(scene, orbit, monodromy: np.ndarray, trivial: int) -> float:
    """||ds|| <= orbit.error * excursion / sigma: the distance [state units] from the orbit's start to the
    exact orbit's, to first order; 0 for a constant orbit (its residual is an equilibrium residual, not a state
    error) or an orbit without its integrator's solution.  ``trivial``: singular values of Phi - I left out
    (1 for an autonomous orbit: its time shift).

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> from pinlin.periodic.orbit_error import orbit_state_error
    >>> orbit_state_error(spec.scene, orbit, np.eye(2), 0)       # a constant orbit
    0.0
    """
    if orbit.constant or orbit.solution is None or not orbit.error > 0:
        return 0.0
    times = np.linspace(0.0, orbit.period, ORBIT_SAMPLES + 1)
    X = np.stack([_tangent_state(scene, orbit, t) for t in times])
    excursion = float(np.max(np.linalg.norm(X - X[0], axis=1)))
    sigma = np.linalg.svd(monodromy - np.eye(monodromy.shape[0]), compute_uv=False)
    kept = sigma[: sigma.size - trivial]
    if kept.size == 0 or not kept[-1] > 0:
        return float("inf")
    return float(orbit.error * excursion / kept[-1])


def _sensitivity(scene, dyn: FreeDynamics, orbit, t: float) -> float:
    """(sum_i ||dA/dx_i||_F^2)^(1/2) at the orbit's point at t, by central differences in the free
    coordinates' tangent directions and velocities."""
    n, nv, free = scene.n, scene.model.nv, scene.free_dofs
    q, v = orbit.state(t)
    x = np.concatenate([np.zeros(n), v[free]])
    total = 0.0
    for i in range(2 * n):
        pair = []
        for sign in (1.0, -1.0):
            h = _FD_STEP * max(1.0, abs(x[i]))
            dq, vv = np.zeros(nv), v.copy()
            if i < n:
                dq[free[i]] = sign * h
            else:
                vv[free[i - n]] += sign * h
            p = evaluate_point(scene, dyn, pin.integrate(scene.model, q, dq), vv, t)
            pair.append(first_order_form(p.M, p.C, p.K, residual=False)[0])
        total += float(np.sum(((pair[0] - pair[1]) / (2 * h)) ** 2))
    return float(np.sqrt(total))


def orbit_coefficient_errors(scene, orbit, steps: list, ds: float) -> list | None:
    """Per step, the (1, 1) block bound on ||dA|| along the step from the orbit's state error ``ds``: the
    sensitivity and ||Phi(t, 0)|| ds at the step's ends, the larger of each times :data:`ORBIT_SLACK`
    (None when ``ds`` is 0).

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> from pinlin.periodic.orbit_error import orbit_coefficient_errors
    >>> print(orbit_coefficient_errors(spec.scene, orbit, [], 0.0))
    None
    """
    if not steps or ds == 0.0:
        return None
    dyn = FreeDynamics(scene)
    ends = [s.t0 for s in steps] + [steps[-1].t0 + steps[-1].h]
    S = np.array([_sensitivity(scene, dyn, orbit, t) for t in ends])
    growth, Phi = [1.0], np.eye(steps[0].P.shape[0])
    for step in steps:
        Phi = step.P @ Phi
        growth.append(float(np.linalg.norm(Phi, 2)))
    dx = np.array(growth) * ds
    return [np.array([[ORBIT_SLACK ** 2 * max(S[i], S[i + 1]) * max(dx[i], dx[i + 1])]])
            for i in range(len(steps))]
