"""The variational equation along a motion, from Pinocchio (theory: Floquet): :func:`variational_coefficients`.

Along a motion q*(t), v*(t) of the free coordinates (prescribed joints at q_p(t), v_p(t), a_p(t)), small
deviations x in the tangent space of the free coordinates obey

.. math::
    M(t)\\, \\ddot x + C(t)\\, \\dot x + K(t)\\, x = 0, \\qquad
    M = \\partial r / \\partial a, \\quad C = \\partial r / \\partial v, \\quad K = \\partial r / \\partial q

with r(q, v, a) = tau(q, v, a, f_ext) - Q_e(q, v) evaluated at the *actual* acceleration a*(t)
(``computeRNEADerivatives(q*, v*, a*)``, elements' stiffness and damping included: the same assembly as
:func:`pinlin.linearize`, :func:`pinlin.linearization.assembly.assemble` with ``a``), restricted to the
free coordinates.  Each point costs one forward-dynamics pass (``rnea`` and ``crba``, or ``aba``, for a*; none along a
constant orbit, whose free acceleration is 0) and one RNEA-derivative pass.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from ..linearization.assembly import assemble
from ..linearization.state_form import first_order_form
from ..model.scene import Scene
from ..nonlinear.dynamics import FreeDynamics

__all__ = ["Point", "VariationalCoefficients", "evaluate_point", "variational_coefficients"]


@dataclass(frozen=True)
class Point:
    """The variational coefficients at one point of a motion.

    Attributes
    ----------
    a_free : (n,) ndarray
        The free accelerations a*_f [rad/s^2 or m/s^2].
    a : (nv,) ndarray
        The full acceleration (prescribed joints: a_p(t); constant-speed ones 0).
    M, C, K : (n, n) ndarray
        dr/da, dr/dv, dr/dq on the free coordinates.

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> p = pinlin.variational_coefficients(spec.scene, orbit).point(0.0)
    >>> print(p.M.shape, p.first_order().shape, np.round(p.a_free + 0.0, 6))
    (1, 1) (2, 2) [0.]
    """

    a_free: np.ndarray
    a: np.ndarray
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray

    def first_order(self) -> np.ndarray:
        """A = [[0, I], [-M^-1 K, -M^-1 C]] (2n, 2n), by
        :func:`~pinlin.linearization.state_form.first_order_form`."""
        return first_order_form(self.M, self.C, self.K, residual=False)[0]


def evaluate_point(scene: Scene, dyn: FreeDynamics, q: np.ndarray, v: np.ndarray, t: float,
                   at_rest: bool = False) -> Point:
    """The coefficients at (q, v) and time t; q and v (full, nq and nv) get the prescribed motions at t
    (in place).  ``dyn``: the thread's :class:`~pinlin.nonlinear.dynamics.FreeDynamics` of ``scene``.
    ``at_rest``: the free coordinates stay at an equilibrium (a constant orbit), so their acceleration is
    exactly 0 and the forward-dynamics pass is skipped.

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> from pinlin.nonlinear.dynamics import FreeDynamics
    >>> from pinlin.periodic.coefficients import evaluate_point
    >>> q, v = orbit.state(0.0)
    >>> p = evaluate_point(spec.scene, FreeDynamics(spec.scene), q.copy(), v.copy(), 0.0, at_rest=True)
    >>> print(np.round(p.M, 6), np.round(p.a_free + 0.0, 6))
    [[0.004]] [0.]
    """
    a_p = dyn.apply_motions(t, q, v)
    a_f = np.zeros(scene.n) if at_rest else dyn.acceleration(q, v, a_p)
    free = scene.free_dofs
    a = np.zeros(scene.model.nv) if a_p is None else a_p.copy()
    if a_f.shape[0] == scene.model.nv:  # the aba path: no prescribed joint
        a = a_f
        a_f = a_f[free]
    else:
        a[free] = a_f
    asm = assemble(scene, q, v, stiffness=True, damping=True, mass=True, a=a)
    ix = np.ix_(free, free)
    M = asm.M[ix]  # symmetric: Pinocchio's upper triangle mirrored
    return Point(a_f, a, M.copy(), asm.C[ix].copy(), asm.K[ix].copy())


class VariationalCoefficients:
    """M(t), C(t), K(t) and A(t) along a periodic orbit (callables of t [s], periodic extension).

    Each distinct t is one Pinocchio evaluation (:func:`evaluate_point`); the last ``cache`` points are
    kept, so that M(t), C(t) and K(t) at one node cost one evaluation.  An instance belongs to the thread
    that created it (it holds that thread's Pinocchio workspace).

    Attributes
    ----------
    evaluations : int
        Pinocchio evaluations made so far.

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> co = pinlin.variational_coefficients(spec.scene, orbit)
    >>> p = co.point(0.0)
    >>> print(np.round(p.M, 6), co.M(0.0) is p.M, co.evaluations)       # one evaluation per time, cached
    [[0.004]] True 1
    """

    def __init__(self, scene: Scene, orbit, cache: int = 16):
        self.scene, self.orbit = scene, orbit
        self.dyn = FreeDynamics(scene)
        self._cache: OrderedDict[float, Point] = OrderedDict()
        self._size = int(cache)
        self.evaluations = 0

    def point(self, t: float) -> Point:
        t = float(t)
        hit = self._cache.get(t)
        if hit is not None:
            return hit
        q, v = self.orbit.state(t) if hasattr(self.orbit, "state") else (self.orbit.q(t), self.orbit.v(t))
        p = evaluate_point(self.scene, self.dyn, q, v, t,
                           at_rest=bool(getattr(self.orbit, "constant", False)))
        self.evaluations += 1
        self._cache[t] = p
        if len(self._cache) > self._size:
            self._cache.popitem(last=False)
        return p

    def M(self, t: float) -> np.ndarray:
        return self.point(t).M

    def C(self, t: float) -> np.ndarray:
        return self.point(t).C

    def K(self, t: float) -> np.ndarray:
        return self.point(t).K

    def A(self, t: float) -> np.ndarray:
        return self.point(t).first_order()


def variational_coefficients(scene: Scene, orbit) -> VariationalCoefficients:
    """The coefficients M(t), C(t), K(t) (and A(t)) of the variational equation along ``orbit``.

    Parameters
    ----------
    scene : Scene
        The scene the orbit belongs to.
    orbit : PeriodicOrbit
        From :func:`pinlin.periodic_orbit` (anything with ``q(t)``, ``v(t)`` full arrays works).

    Returns
    -------
    VariationalCoefficients
        ``.M(t)``, ``.C(t)``, ``.K(t)`` (n, n), ``.A(t)`` (2n, 2n), ``.point(t)`` (all at once).

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> co = pinlin.variational_coefficients(spec.scene, orbit)
    >>> print(co.M(0.0).shape, co.A(0.0).shape, np.round(co.M(0.0), 6))
    (1, 1) (2, 2) [[0.004]]
    """
    return VariationalCoefficients(scene, orbit)
