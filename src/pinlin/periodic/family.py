"""The family of a conservative scene's free orbits, and the member the user started on (theory: Floquet).

A conservative autonomous scene (no damping, symmetric element stiffness, no periodic motion, held
prescribed joints) has its free orbits in one-parameter families: the energy E(s) = T + V is a first
integral, so the shooting equations F(s, T) = x(T; s) - s = 0 with the phase condition leave one direction
free.  :class:`Family` supplies the condition that picks one member, c(s) = c(s_0): the energy of the user's
start, or the start value of a named coordinate (``keep=``), and the bordered Newton system

.. math::
    \\begin{bmatrix} \\Phi - I & f(x_T) & \\nabla E \\\\ f_0^T & 0 & 0 \\\\ \\nabla c^T & 0 & 0 \\end{bmatrix}
    \\begin{bmatrix} \\delta s \\\\ \\delta T \\\\ \\delta\\lambda \\end{bmatrix}
    = -\\begin{bmatrix} F \\\\ f_0 \\cdot (s - s_0) \\\\ c(s) - c(s_0) \\end{bmatrix}

in which the unfolding column lambda grad E makes the square matrix regular (grad E(x_T) is the left null
vector of [Phi - I, f]): on an orbit lambda = 0, since E(x_T) = E(s) forces it.  Differentiating the solution
in c(s_0) gives the period's derivative along the family, dT/dc, the Jordan block at multiplier 1.

Before Newton, one integration from the start (without the variational equation) finds its first return to
the phase section: for a conservative family the start already lies on the orbit with its energy, so that
return time is the period, whatever the guess (a Newton iteration on T from a guess 30 % off leaves the basin
where the flow over the guessed period ends near the start).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
from scipy.integrate import solve_ivp

from ..errors import ParameterError
from ..linearization.assembly import external_forces
from ..linearization.plan import plan_of
from ..model.evaluation import Evaluation, workspace
from ..model.scene import Scene

__all__ = ["Family", "conservative_family", "return_time", "ENERGY", "QUADRATURE_NODES", "RETURN_TOL",
           "PERIOD_RANGE"]

#: The name of the energy family (``orbit.family``).
ENERGY = "energy"
#: Gauss-Legendre nodes of the potential's line integral V(q) - V(q_0) along the tangent path from the start.
QUADRATURE_NODES = 24
#: Largest relative miss ||x(t) - s_0|| / max_t ||x(t) - s_0|| of a section crossing that counts as the
#: start's return (the period estimate).
RETURN_TOL = 0.1
#: The return time replaces the guess only within a factor PERIOD_RANGE of it (a first return far from the
#: guess is another orbit's, or the guess names a multiple of the period on purpose).
PERIOD_RANGE = 2.0


def _why_not_conservative(scene: Scene) -> str | None:
    """Why ``scene`` is not conservative, or None when it is."""
    if scene.motions:
        return f"joints {sorted(scene.motions)} follow prescribed motions"
    moving = [name for name, omega in scene.prescribed.items() if omega != 0]
    if moving:
        return f"prescribed joints {moving} move at constant speed"
    plan = plan_of(scene)
    if not plan.undamped:
        return "its elements add damping"
    if not plan.symmetric_elements:
        return "an element's stiffness is not symmetric (a circulatory force)"
    if any(w.body_fixed for w in scene.wrenches):
        return "a follower wrench does work that no potential accounts for"
    return None


class Family:
    """The energy of a conservative scene and the condition c(s) = c(s_0) that keeps one orbit of its family.

    States s = (dq_f, v_f) are tangent displacements from ``q0`` and free velocities, as in the shooting.

    Parameters
    ----------
    scene : Scene
        Conservative (:func:`conservative_family` checks it).
    q0 : (nq,) ndarray
        The start configuration (the origin of the tangent coordinates).
    v0 : (nv,) ndarray
        The start velocity (prescribed entries zero).
    keep : str or None
        None: keep the energy; a free 1-DOF joint's name: keep its start position.

    Attributes
    ----------
    name : str
        ``"energy"`` or the kept joint's name.
    start_value : float
        c(s_0): the start's energy [J] (:meth:`energy`), or 0 for a kept joint (its displacement).
    label : float
        What labels the orbit in its family: the start's energy [J], or the kept joint's start position
        [rad or m].

    Examples
    --------
    The bundled double pendulum at rest at (0.1, 0) rad, and its energy's gradient with a velocity 0.5 rad/s:

    >>> from pinlin.periodic.family import Family
    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> family = Family(scene, np.array([0.1, 0.0]), np.zeros(2), None)
    >>> print(family.name, f"{family.label:.6f}", np.round(family.energy_gradient(np.array([0, 0, 0.5, 0])), 6))
    energy -12.786898 [1.282969 0.220357 0.521667 0.11625 ]
    """

    def __init__(self, scene: Scene, q0: np.ndarray, v0: np.ndarray, keep: str | None):
        self.scene, self.q0, self.v0 = scene, q0, v0
        self.model, self.free, self.n = scene.model, scene.free_dofs, scene.n
        self.ws = workspace(scene)
        self.elements = bool(scene.groups) or scene.constant_fext is not None
        # the elements' potential is measured from the free joints at Pinocchio's neutral (held joints as in q0)
        self.reference = q0.copy()
        neutral = pin.neutral(self.model)
        for name in scene.robot.joint_names:
            j = scene.robot.joint(name)
            if j.nv and j.idx_v in set(self.free.tolist()):
                self.reference[j.idx_q : j.idx_q + j.nq] = neutral[j.idx_q : j.idx_q + j.nq]
        self.name = ENERGY if keep is None else keep
        self.index = None if keep is None else int(np.flatnonzero(self.free == scene.robot.joint(keep).idx_v)[0])
        self.nodes, self.weights = np.polynomial.legendre.leggauss(QUADRATURE_NODES)
        s0 = np.concatenate([np.zeros(self.n), v0[self.free]])
        self.start_value = self.value(s0)
        if keep is None:
            self.label = self.start_value
        else:  # the joint's position at the start (the angle of a continuous joint)
            j = scene.robot.joint(keep)
            qj = q0[j.idx_q : j.idx_q + j.nq]
            self.label = float(qj[0]) if j.nq == 1 else float(np.arctan2(qj[1], qj[0]))

    def _point(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        dq = np.zeros(self.model.nv)
        dq[self.free] = s[: self.n]
        v = self.v0.copy()
        v[self.free] = s[self.n :]
        return pin.integrate(self.model, self.q0, dq), v

    def _element_gradient(self, q: np.ndarray) -> np.ndarray:
        """dV_e/dq (nv,) = rnea(q, 0, 0, fext) - g(q) - Q_e(q, 0): the wrenches' and elements' potential."""
        zero = np.zeros(self.model.nv)
        if not self.elements:
            return zero
        ev = Evaluation(self.scene, q, zero, self.ws, at_rest=True)
        fext = external_forces(self.scene, ev)
        Q = np.zeros(self.model.nv)
        for group in self.scene.groups:
            group.add_force(ev, Q)
        extra = () if fext is None else (fext,)
        data = self.ws.data
        return (np.array(pin.rnea(self.model, data, q, zero, zero, *extra))
                - np.array(pin.computeGeneralizedGravity(self.model, data, q)) - Q)

    def energy(self, s: np.ndarray) -> float:
        """E(s) = T(q, v) + V_g(q) + V_e(q) [J]: Pinocchio's kinetic and gravity energies (V_g zero at the
        world origin), and the elements' and wrenches' V_e, zero with the free joints at Pinocchio's neutral
        configuration, by Gauss-Legendre along q_ref + tau d, d = difference(q_ref, q), tau in [0, 1]."""
        q, v = self._point(s)
        V = float(pin.computePotentialEnergy(self.model, self.ws.data, q))
        if self.elements:
            d = np.array(pin.difference(self.model, self.reference, q))
            for x, w in zip(self.nodes, self.weights):
                qt = pin.integrate(self.model, self.reference, 0.5 * (1.0 + x) * d)
                V += 0.5 * w * float(self._element_gradient(qt) @ d)
        return float(pin.computeKineticEnergy(self.model, self.ws.data, q, v)) + V

    def energy_gradient(self, s: np.ndarray) -> np.ndarray:
        """dE/ds (2n,): (v^T d(M v)/dq / 2 + dV/dq, M v) on the free coordinates (Pinocchio's RNEA derivatives)."""
        q, v = self._point(s)
        data, zero = self.ws.data, np.zeros(self.model.nv)
        with_v = np.array(pin.computeRNEADerivatives(self.model, data, q, zero, v)[0])
        gravity = np.array(pin.computeRNEADerivatives(self.model, data, q, zero, zero)[0])
        Mv = np.array(pin.rnea(self.model, data, q, zero, v)) - np.array(pin.rnea(self.model, data, q, zero, zero))
        dE_dq = 0.5 * (with_v - gravity).T @ v + np.array(pin.computeGeneralizedGravity(self.model, data, q))
        dE_dq += self._element_gradient(q)
        return np.concatenate([dE_dq[self.free], Mv[self.free]])

    def value(self, s: np.ndarray) -> float:
        """c(s): the energy [J] or the kept coordinate's displacement from the start [rad or m]."""
        return self.energy(s) if self.index is None else float(s[self.index])

    def gradient(self, s: np.ndarray) -> np.ndarray:
        """dc/ds (2n,)."""
        if self.index is None:
            return self.energy_gradient(s)
        g = np.zeros(2 * self.n)
        g[self.index] = 1.0
        return g

    def matrix(self, J: np.ndarray, s: np.ndarray, f0: np.ndarray) -> np.ndarray:
        """The bordered matrix (2n + 2 square) from J = [Phi - I, f(x_T)] (2n, 2n + 1) at state s."""
        n2 = 2 * self.n
        A = np.zeros((n2 + 2, n2 + 2))
        A[:n2, : n2 + 1] = J
        A[:n2, n2 + 1] = self.energy_gradient(s)
        A[n2, :n2] = f0
        A[n2 + 1, :n2] = self.gradient(s)
        return A

    def step(self, J: np.ndarray, F: np.ndarray, s: np.ndarray, f0: np.ndarray, phase: float):
        """The Newton step (ds, dT) of the bordered system (the unfolding's dlambda is dropped: lambda = 0
        on an orbit, and the step it takes is of the order of the residual squared)."""
        rhs = -np.concatenate([F, [phase, self.value(s) - self.start_value]])
        d = np.linalg.solve(self.matrix(J, s, f0), rhs)
        return d[: F.size], float(d[F.size])

    def period_derivative(self, J: np.ndarray, s: np.ndarray, f0: np.ndarray) -> float:
        """dT/dc along the family [s/J, s/rad or s/m]: the period's entry of the bordered matrix's inverse in
        the family condition's column."""
        A = self.matrix(J, s, f0)
        e = np.zeros(A.shape[0])
        e[-1] = 1.0
        return float(np.linalg.solve(A, e)[2 * self.n])

    def slope(self, field, s: np.ndarray, T: float, f0: np.ndarray, flows, error: float) -> tuple[float, float]:
        """(dT/dc, its error) at the orbit (s, T): ``flows`` the (Phi(T), x(T)) of the returned flow and of one
        at 10 times its tolerances; the error is their derivatives' difference plus |dT/dc| ``error`` (the
        orbit's relative error, to first order)."""
        tight, loose = (self.period_derivative(np.hstack([Phi - np.eye(2 * self.n), field(T, x)[:, None]]), s, f0)
                        for Phi, x in flows)
        return tight, abs(tight - loose) + abs(tight) * error


def conservative_family(scene: Scene, q0: np.ndarray, v0: np.ndarray, keep: str | None,
                        autonomous: bool) -> Family | None:
    """The family of the start (q0, v0) of an autonomous conservative scene; None for any other scene.

    Raises
    ------
    ParameterError
        ``keep`` is not a string, names no joint of the robot, a prescribed or multi-DOF joint, or is given
        for a forced or non-conservative scene (whose orbits are isolated: there is no family to move along).

    Examples
    --------
    >>> from pinlin.periodic.family import conservative_family
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> start = (np.array([0.1, 0.0]), np.zeros(2))
    >>> print(conservative_family(pinlin.Scene(robot), *start, "joint2", True).name)
    joint2
    >>> print(conservative_family(pinlin.Scene(robot, [pinlin.JointDamper("joint1", 0.1)]), *start, None, True))
    None
    """
    if keep is not None:
        if not isinstance(keep, str):
            raise ParameterError("keep", f"expected a joint name (str) or None, got {type(keep).__name__}")
        names = list(scene.robot.joint_names)
        if keep not in names:
            raise ParameterError("keep", f"the robot has no joint {keep!r}; its joints: {names}")
        joint = scene.robot.joint(keep)
        if joint.nv != 1 or joint.idx_v not in set(scene.free_dofs.tolist()):
            raise ParameterError("keep", f"joint {keep!r} is not a free 1-DOF joint of the scene (prescribed, or "
                                         f"of {joint.nv} DOF): its start value cannot label the orbit")
    why = "the scene is forced (its orbits are isolated)" if not autonomous else _why_not_conservative(scene)
    if why is None:
        return Family(scene, q0, v0, keep)
    if keep is not None:
        raise ParameterError("keep", f"the scene is not conservative ({why}): its free orbits form no family "
                                     f"along which {keep!r} could be kept")
    return None


def return_time(field, s0: np.ndarray, guess: float, rtol: float, atol: float) -> float:
    """The start's first return time to the phase section f(s_0) . (x - s_0) = 0 (crossed in the start's
    sense, missing s_0 by at most :data:`RETURN_TOL` of the excursion), when within :data:`PERIOD_RANGE` of
    ``guess``; otherwise (or when the integration fails) ``guess``.  ``field(t, x)``: the autonomous field,
    integrated by DOP853 at ``rtol``, ``atol`` (the shooting's: the return time is then the period to about
    ``rtol``, and Newton has little left to do).

    Examples
    --------
    x'' = -4 x from x = 1 at rest returns after pi s; a guess 3 times off is kept:

    >>> from pinlin.periodic.family import return_time
    >>> field = lambda t, x: np.array([x[1], -4.0 * x[0]])
    >>> print(f"{return_time(field, np.array([1.0, 0.0]), 3.0, 1e-12, 1e-14):.10f}")
    3.1415926536
    >>> print(return_time(field, np.array([1.0, 0.0]), 9.0, 1e-12, 1e-14))
    9.0
    """
    f0 = field(0.0, s0)

    def section(t, x):
        return f0 @ (x - s0)

    section.direction = 1.0
    try:
        sol = solve_ivp(field, (0.0, PERIOD_RANGE * guess), s0, method="DOP853", rtol=rtol, atol=atol,
                        events=section, dense_output=True)
    except (ArithmeticError, ValueError, np.linalg.LinAlgError):
        return guess
    if sol.status < 0:
        return guess
    X = sol.sol(np.linspace(0.0, sol.t[-1], 257))
    excursion = float(np.max(np.linalg.norm(X - s0[:, None], axis=0)))
    for t, x in zip(sol.t_events[0], sol.y_events[0]):
        if t > 1e-3 * guess and np.linalg.norm(x - s0) <= RETURN_TOL * excursion:
            return float(t) if t >= guess / PERIOD_RANGE else guess
    return guess
