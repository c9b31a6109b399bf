"""The orbit's own error in the coefficients of its variational equation (theory: Floquet).

A shooting result misses exact periodicity by its residual r = x(T) - x(0).  To first order the exact orbit
starts at s + ds with (Phi - I) ds = -r (the next Newton step; an autonomous orbit leaves out the smallest
singular value of Phi - I, its time shift being free) and runs at dx(t) = Phi(t, 0) ds from the computed one.
The coefficients move with it: dA(t) = (dA/dx) Phi(t, 0) ds, the derivatives by central differences of A
(Pinocchio evaluations, the acceleration recomputed), periodic along the orbit: sampled once per period and
interpolated to every node (:mod:`.sampling`), so that the multipliers' first-order change
g_k . ds, g_k = d mu_k / d s from w^H dPhi z / (w^H z), keeps the integral's cancellations
(:func:`.bounds.multiplier_bounds`).  The error of r itself (``PeriodicOrbit.integration_error``, direction
unknown) enters as ||g_k|| ||ds'||, ||ds'|| <= integration_error * excursion / sigma.  The change of period of
an autonomous orbit's exact neighbour is not covered.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..linearization.state_form import first_order_form
from ..nonlinear.dynamics import FreeDynamics
from .bounds import multiplier_bounds
from .coefficients import evaluate_point
from .sampling import sample_periodic

__all__ = ["OrbitError", "orbit_bound", "orbit_start_error", "orbit_responses", "ORBIT_SAMPLES", "JACOBIAN_RTOL",
           "JACOBIAN_SAMPLES"]

#: Times per period at which the orbit's excursion is measured (its residual is relative to it).
ORBIT_SAMPLES = 64

#: Relative accuracy of the interpolated derivatives dA/dx along the orbit (the orbit's part of a bound is a
#: first-order figure with a safety factor 2: a few digits are all it needs) and the most samples they take.
JACOBIAN_RTOL = 1e-4
JACOBIAN_SAMPLES = 256

_FD_STEP = float(np.finfo(float).eps) ** (1 / 3)


@dataclass(frozen=True)
class OrbitError:
    """The reference orbit's error as the bounds take it: ``ds`` (m,) the start's first-order correction,
    ``unknown`` the norm of the correction's part of unknown direction (:func:`orbit_start_error`) and
    ``responses`` (steps, nodes, m, m, m), dA at every node per unit change of the orbit's start
    (:func:`orbit_responses`).

    Examples
    --------
    >>> from pinlin.periodic.orbit_error import OrbitError
    >>> e = OrbitError(np.array([1e-9]), 1e-12, np.ones((1, 2, 1, 1, 1)))
    >>> e.step_norms()[0]
    array([[1.001e-09]])
    """

    ds: np.ndarray
    unknown: float
    responses: np.ndarray

    def step_norms(self) -> list:
        """Per step, a (1, 1) bound on ||dA|| over its nodes (2-norms): ||dA . ds|| + ||dA|| unknown."""
        signed = np.linalg.norm(self.responses @ self.ds, ord=2, axis=(2, 3))               # (S, nodes)
        whole = np.sqrt(np.sum(self.responses ** 2, axis=(2, 3, 4)))                       # Frobenius
        return [np.array([[value]]) for value in (signed + whole * self.unknown).max(axis=1)]


def orbit_bound(scene, orbit, tr, eig, monodromy: np.ndarray) -> tuple[np.ndarray, list | None]:
    """(the orbit's part of each multiplier's bound, per-step norm bounds on its dA for the Jordan bound, or
    None): the first-order change of the multipliers from the orbit's correction, through the responses at
    every node (:class:`OrbitError`, :func:`~.bounds.multiplier_bounds`).

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> from pinlin.periodic.orbit_error import orbit_bound
    >>> orbit_bound(spec.scene, orbit, None, None, np.eye(2))         # a constant orbit
    (array([0., 0.]), None)
    """
    m = monodromy.shape[0]
    if orbit.constant or orbit.solution is None or not tr.steps:
        return np.zeros(m), None
    ds, unknown = orbit_start_error(scene, orbit, monodromy, 1 if orbit.autonomous else 0)
    if not np.any(ds) and unknown == 0.0:
        return np.zeros(m), None
    error = OrbitError(ds, unknown, orbit_responses(scene, orbit, tr.steps))
    return multiplier_bounds(tr, eig, error)[3], error.step_norms()


def _tangent_state(scene, orbit, t: float) -> np.ndarray:
    y = orbit.solution(float(t) % orbit.period)
    nv, n = scene.model.nv, scene.n
    return np.concatenate([y[:nv][scene.free_dofs], y[nv:nv + n]])


def orbit_start_error(scene, orbit, monodromy: np.ndarray, trivial: int) -> tuple[np.ndarray, float]:
    """(ds, unknown): the first-order correction ds = -(Phi - I)^+ r from the orbit's start to the exact
    orbit's (r = x(T) - x(0) of the orbit's own integration, the pseudo-inverse leaving out ``trivial``
    smallest singular values: 1 for an autonomous orbit, whose time shift is free), and the norm bound
    integration_error * excursion / sigma of the part whose direction is unknown (the error of r itself).
    Zero for a constant orbit (its residual is an equilibrium residual, not a state error).

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> from pinlin.periodic.orbit_error import orbit_start_error
    >>> orbit_start_error(spec.scene, orbit, np.eye(2), 0)       # a constant orbit
    (array([0., 0.]), 0.0)
    """
    m = monodromy.shape[0]
    if orbit.constant or orbit.solution is None:
        return np.zeros(m), 0.0
    nv, n = scene.model.nv, scene.n
    y0, yT = orbit.solution(0.0), orbit.solution(orbit.period)
    r = np.concatenate([(yT - y0)[:nv][scene.free_dofs], (yT - y0)[nv:nv + n]])
    times = np.linspace(0.0, orbit.period, ORBIT_SAMPLES + 1)
    X = np.stack([_tangent_state(scene, orbit, t) for t in times])
    excursion = float(np.max(np.linalg.norm(X - X[0], axis=1)))
    U, sigma, Vh = np.linalg.svd(monodromy - np.eye(m))
    keep = m - trivial
    if keep <= 0 or not sigma[keep - 1] > 0:
        return np.zeros(m), float("inf")
    ds = -(Vh[:keep].T @ ((U[:, :keep].T @ r) / sigma[:keep]))
    return ds, float(orbit.integration_error * excursion / sigma[keep - 1])


def _perturbed_A(scene, dyn: FreeDynamics, q, v, t: float, dx: np.ndarray) -> np.ndarray:
    """A at the orbit's point (q, v) moved by dx = (dq_f, dv_f) in the free coordinates' tangent space."""
    n, free = scene.n, scene.free_dofs
    dq, vv = np.zeros(scene.model.nv), v.copy()
    dq[free] = dx[:n]
    vv[free] += dx[n:]
    p = evaluate_point(scene, dyn, pin.integrate(scene.model, q, dq), vv, t)
    return first_order_form(p.M, p.C, p.K, residual=False)[0]


def _jacobian(scene, dyn: FreeDynamics, orbit, t: float) -> np.ndarray:
    """dA/dx_c at the orbit's point at t, (m, m, m) with c last, by central differences in each free
    coordinate's tangent direction and velocity."""
    n, m = scene.n, 2 * scene.n
    q, v = orbit.state(t)
    speeds = np.concatenate([np.zeros(n), v[scene.free_dofs]])
    J = np.zeros((m, m, m))
    for c in range(m):
        e = np.zeros(m)
        e[c] = _FD_STEP * max(1.0, abs(speeds[c]))
        J[..., c] = (_perturbed_A(scene, dyn, q, v, t, e) - _perturbed_A(scene, dyn, q, v, t, -e)) / (2 * e[c])
    return J


def orbit_responses(scene, orbit, steps: list) -> np.ndarray | None:
    """dA at every node of every step per unit change of the orbit's start: (S, nodes, m, m, m), the last
    axis the start direction e_j, dA(t_i) = sum_c dA/dx_c (Phi(t_i, 0) e_j)_c.  The derivatives dA/dx (central
    differences, Pinocchio evaluations with the acceleration recomputed) are periodic along the orbit: they
    are sampled and interpolated (:mod:`.sampling`, to :data:`JACOBIAN_RTOL`), or evaluated at every node
    where the interpolant does not converge.  None for a constant orbit or no steps.

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> from pinlin.periodic.orbit_error import orbit_responses
    >>> print(orbit_responses(spec.scene, orbit, []))
    None
    """
    if not steps or orbit.constant or orbit.solution is None:
        return None
    dyn = FreeDynamics(scene)
    m = 2 * scene.n
    times = np.concatenate([step.nodes for step in steps])
    samples = sample_periodic(lambda t: _jacobian(scene, dyn, orbit, t).transpose(2, 0, 1), orbit.period,
                              tol=JACOBIAN_RTOL, max_samples=JACOBIAN_SAMPLES, scales=_common_scale)
    if samples.converged:
        J = samples(times).transpose(0, 2, 3, 1)                 # (nodes of all steps, m, m, c)
    else:
        J = np.stack([_jacobian(scene, dyn, orbit, float(t)) for t in times])
    J = J.reshape(len(steps), -1, m, m, m)
    out = np.zeros_like(J)
    start = np.eye(m)                                       # Phi(t0, 0)
    for k, step in enumerate(steps):
        out[k] = J[k] @ (step.stage @ start)[:, None]
        start = step.P @ start
    return out


def _common_scale(samples: np.ndarray) -> np.ndarray:
    """One scale for every group: the largest Frobenius norm of the whole Jacobian over the samples."""
    return np.full(samples.shape[1], float(np.sqrt(np.sum(samples ** 2, axis=(1, 2, 3))).max()))
