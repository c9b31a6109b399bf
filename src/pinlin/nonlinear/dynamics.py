"""The right-hand side of the nonlinear equations of motion of a scene (theory: equations, elements).

The free coordinates obey

.. math::
    M_{ff}(q)\\, a_f = Q_{e,f}(q, v) - h_f(q, v), \\qquad
    h = \\mathrm{rnea}(q, v, 0, f_{ext})

with every scene element: joint springs, dampers and Rayleigh damping through
their generalized forces Q_e, follower and dead wrenches through Pinocchio's
``fext`` (:func:`pinlin.linearization.assembly.external_forces`), gravity in the
scene's model.  Prescribed joints keep their constant velocity (zero
acceleration) or follow their periodic motion q_p(t), v_p(t), a_p(t)
(:meth:`FreeDynamics.apply_motions`, theory: Floquet); the torque that takes is not computed.  Without prescribed
joints the accelerations come from ``aba`` directly.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import scipy.linalg

from ..errors import ConfigurationError
from ..linearization.assembly import external_forces
from ..model.evaluation import Evaluation, workspace
from ..model.scene import Scene

__all__ = ["FreeDynamics", "initial_velocity"]


class FreeDynamics:
    """Free accelerations a_f(q, v) of a scene: M_ff a_f = Q_f - h_f, prescribed accelerations zero.

    Everything is computed in the calling thread's Pinocchio workspace
    (:func:`pinlin.model.evaluation.workspace`), fetched once: an
    instance belongs to the thread that created it.

    Examples
    --------
    >>> from pinlin.nonlinear.dynamics import FreeDynamics
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> np.round(FreeDynamics(scene).acceleration(np.array([0.1, 0.0]), np.zeros(2)), 6)
    array([-1.859555,  2.826524])
    """

    def __init__(self, scene: Scene):
        self.scene = scene
        self.model = scene.model
        self.ws = workspace(scene)
        self.data = self.ws.data
        self.free = scene.free_dofs
        self.prescribed = bool(scene.prescribed or scene.motions)
        self.zero = np.zeros(self.model.nv)
        self.motions = tuple(
            (scene.robot.joint(name).idx_q, scene.robot.joint(name).nq, scene.robot.joint(name).idx_v, m)
            for name, m in scene.motions.items()
        )

    def apply_motions(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray | None:
        """Set the periodically moving joints of q and v (in place) to q_p(t), v_p(t); return the full
        acceleration vector holding a_p(t) on them and zero elsewhere (None without periodic motions).

        A continuous joint (nq = 2) gets (cos q_p, sin q_p)."""
        if not self.motions:
            return None
        a = np.zeros(self.model.nv)
        for iq, nq, iv, m in self.motions:
            angle = m.q(t)
            if nq == 1:
                q[iq] = angle
            else:
                q[iq], q[iq + 1] = np.cos(angle), np.sin(angle)
            v[iv], a[iv] = m.v(t), m.a(t)
        return a

    def acceleration(self, q: np.ndarray, v: np.ndarray, a_p: np.ndarray | None = None) -> np.ndarray:
        """The full acceleration (nv,) on the aba path, or the free accelerations (n,) with prescribed joints.

        ``a_p``: the full acceleration vector of the prescribed joints (zero on the free ones), from
        :meth:`apply_motions`; None for constant prescribed velocities."""
        model, data = self.model, self.data
        ev = Evaluation(self.scene, q, v, self.ws)
        fext = external_forces(self.scene, ev)
        Q = np.zeros(model.nv)
        for group in self.scene.groups:  # joint-space elements, vectorized by class
            group.add_force(ev, Q)
        extra = () if fext is None else (fext,)
        if not self.prescribed:
            return np.array(pin.aba(model, data, q, v, Q, *extra))
        # Prescribed joints move at constant velocity (zero acceleration) or follow q_p(t): the actuator
        # holding them supplies whatever torque that takes, so only the free rows count.
        h = np.array(pin.rnea(model, data, q, v, self.zero if a_p is None else a_p, *extra))
        f = self.free
        M = ev.mass_matrix()[np.ix_(f, f)]
        return scipy.linalg.cho_solve(scipy.linalg.cho_factor(M), Q[f] - h[f])


def initial_velocity(scene: Scene, v0) -> np.ndarray:
    """The full initial velocity (nv,): ``v0`` given in full or on the free joints only.

    Parameters
    ----------
    scene : Scene
    v0 : (nv,) or (n,) array, or None
        The full velocity (its prescribed entries must equal the scene's), the n
        free velocities, or None for the steady velocity (zero on the free joints).

    Raises
    ------
    ConfigurationError
        Not numbers, not finite, of neither size, or contradicting a prescribed velocity.

    Examples
    --------
    >>> from pinlin.nonlinear.dynamics import initial_velocity
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> initial_velocity(scene, None), initial_velocity(scene, [1.0, 0.0])
    (array([0., 0.]), array([1., 0.]))
    """
    nv, n = scene.model.nv, scene.n
    v = np.array(scene.v0, dtype=float)
    if v0 is None:
        return v
    try:
        arr = np.array(v0, dtype=float)
    except (TypeError, ValueError):
        raise ConfigurationError(f"v0 must be an array of numbers, got {v0!r:.80}") from None
    if arr.shape not in ((nv,), (n,)):
        sizes = f"nv = {nv}" if n == nv else f"nv = {nv} (all joints) or n = {n} (free joints)"
        raise ConfigurationError(f"v0 has shape {arr.shape}; scene needs a velocity of size {sizes}")
    if not np.all(np.isfinite(arr)):
        raise ConfigurationError(f"v0 has non-finite entries: {arr}")
    if arr.shape == (n,):
        v[scene.free_dofs] = arr
        return v
    for name, omega in {**scene.prescribed, **{k: m.v(0.0) for k, m in scene.motions.items()}}.items():
        i = scene.robot.joint(name).idx_v
        if arr[i] != omega:
            raise ConfigurationError(
                f"v0[{i}] = {arr[i]!r} for prescribed joint {name!r}, but the scene prescribes "
                f"{omega!r}; give the full velocity with the prescribed values, or only the {n} free velocities"
            )
    return arr
