"""The periodic reference motion of a scene: :class:`PeriodicOrbit` (theory: Floquet)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from ..model.scene import Scene
from ..nonlinear.dynamics import FreeDynamics
from ..numerics.arrays import readonly
from ..results import Result

__all__ = ["PeriodicOrbit"]


@dataclass(frozen=True, repr=False, eq=False, kw_only=True)
class PeriodicOrbit(Result):
    """A T-periodic motion q*(t) of a scene's free coordinates (forced, or an autonomous orbit).

    ``q(t)``, ``v(t)`` and ``a(t)`` are the full configuration (nq), velocity and acceleration (nv) at any
    time t [s] (periodic extension of the free coordinates; prescribed joints exactly at their motion, a
    constant-speed joint at its angle Omega t).  Between the integrator's steps q and v come from the
    DOP853 dense output (7th-order interpolant, error of the order of the integration's ``rtol`` relative
    to the motion); ``a(t)`` is the dynamics evaluated at (q(t), v(t), t), not an interpolant.

    Attributes
    ----------
    period : float
        T [s].
    q0 : (nq,) ndarray
        q*(0).
    v0 : (nv,) ndarray
        v*(0).
    residual : float
        ||x(T) - x(0)|| / max_t ||x(t) - x(0)|| with x = (dq_f, v_f) the free coordinates [rad or m] and
        velocities stacked: the shooting's last relative defect.  For a constant orbit: the largest relative
        equilibrium residual ||r_f|| / (||tau|| + ||Q_e|| + ||K||) found along the period.
    integration_error : float
        ||x_T - x_T'|| / max_t ||x(t) - x(0)||: the final flow against one at ``rtol * 10`` (an over-estimate
        of the returned flow's error for an 8th-order method); 0 for a constant orbit.
    error : float
        ``residual + integration_error``: the headline figure, a relative bound on how far x(T) misses x(0)
        in exact arithmetic.
    iterations : int
        Newton steps taken (0 for a constant orbit).
    history : tuple of float
        The residual before each Newton step and after the last.
    constant : bool
        The free coordinates stay at an equilibrium: the prescribed motion does not reach them (no shooting).
    autonomous : bool
        A free oscillation (the period was unknown); its variational equation has the trivial multiplier 1.
    monodromy : (2n, 2n) ndarray or None
        The shooting's last Phi(T) of the free coordinates (from the variational equation integrated with
        the orbit); None for a constant orbit.
    elapsed : float
        Wall time [s].
    method : str
    family : str or None
        The orbit belongs to a one-parameter family of a conservative scene, labelled by ``"energy"`` or by
        the kept joint's name (``periodic_orbit(keep=...)``); None for an isolated orbit.
    family_value : float or None
        The label's value: the energy [J] (Pinocchio's kinetic and gravity energies, the elements' potential
        zero at the free joints' neutral configuration), or the kept joint's start position [rad or m].
    period_derivative : float or None
        dT/dE [s/J] (or dT/dq_j [s/rad or s/m]) along the family, from the shooting's bordered matrix
        (the Jordan block at multiplier 1).
    period_derivative_error : float or None
        Its error estimate: the change with the flow at ``rtol * 10`` plus its size times ``error``.

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> q, v = orbit.state(0.01)
    >>> print(orbit.constant, q.shape, np.round(v + 0.0, 6), orbit.error < 1e-12)
    True ... True
    """

    period: float
    q0: np.ndarray
    v0: np.ndarray
    residual: float
    integration_error: float
    error: float
    iterations: int
    history: tuple
    constant: bool
    autonomous: bool
    monodromy: np.ndarray | None
    elapsed: float
    method: str
    scene: Scene = field(repr=False)
    base: np.ndarray = field(repr=False)
    solution: object = field(repr=False)
    family: str | None = None
    family_value: float | None = None
    period_derivative: float | None = None
    period_derivative_error: float | None = None

    _dict_exclude = ("scene", "base", "solution")

    def __post_init__(self):
        # a result may be shared by threads: its arrays are read-only copies
        for name in ("q0", "v0", "monodromy", "base"):
            object.__setattr__(self, name, readonly(getattr(self, name)))

    def state(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """(q*(t), v*(t)) at once (full, nq and nv).

        Examples
        --------
        The Kapitza pendulum hangs still while its pivot moves as 0.02 sin(200 t):

        >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
        >>> q, v = pinlin.periodic_orbit(spec.scene, spec.q0).state(0.01)
        >>> print(np.round(q + 0.0, 6), np.round(v + 0.0, 6))
        [ 0.018186 -1.        0.      ] [-1.664587  0.      ]
        """
        return self._state(t)

    def _state(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        scene = self.scene
        model = scene.model
        tau = float(t) % self.period
        dq = np.zeros(model.nv)
        v = np.array(scene.v0, dtype=float)
        if self.solution is not None:
            y = self.solution(tau)
            dq[:] = y[: model.nv]
            v[scene.free_dofs] = y[model.nv : model.nv + scene.n]
        for name, omega in scene.prescribed.items():  # the advancing angle, exactly
            dq[scene.robot.joint(name).idx_v] = omega * float(t)
        q = pin.integrate(model, self.base, dq)
        if scene.motions:
            FreeDynamics(scene).apply_motions(float(t), q, v)
        return q, v

    def q(self, t: float) -> np.ndarray:
        """Configuration q*(t) (nq,).

        Examples
        --------
        >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
        >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
        >>> print(np.round(orbit.q(0.01) + 0.0, 6), bool(np.allclose(orbit.q(0.01 + orbit.period), orbit.q(0.01))))
        [ 0.018186 -1.        0.      ] True
        """
        return self._state(t)[0]

    def v(self, t: float) -> np.ndarray:
        """Velocity v*(t) (nv,).

        Examples
        --------
        >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
        >>> print(np.round(pinlin.periodic_orbit(spec.scene, spec.q0).v(0.0) + 0.0, 6))  # the pivot at 0.02 * 200 m/s
        [4. 0.]
        """
        return self._state(t)[1]

    def a(self, t: float) -> np.ndarray:
        """Acceleration a*(t) (nv,): the free accelerations from the dynamics at (q*(t), v*(t)), the
        prescribed ones a_p(t) (constant-speed joints 0).

        Examples
        --------
        >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
        >>> print(np.round(pinlin.periodic_orbit(spec.scene, spec.q0).a(0.01) + 0.0, 4))  # -800 sin(2) at the pivot
        [-727.4379    0.    ]
        """
        q, v = self._state(t)
        dyn = FreeDynamics(self.scene)
        a_p = dyn.apply_motions(float(t), q, v)
        a_f = dyn.acceleration(q, v, a_p)
        if a_f.shape[0] == self.scene.model.nv:
            return a_f
        a = np.zeros(self.scene.model.nv) if a_p is None else a_p
        a[self.scene.free_dofs] = a_f
        return a

    def __repr__(self) -> str:
        kind = "constant" if self.constant else ("autonomous" if self.autonomous else "forced")
        return (f"PeriodicOrbit({kind}, period={self.period:.10g} s, n={self.scene.n}, "
                f"iterations={self.iterations}, residual={self.residual:.2e}, error={self.error:.2e}"
                f"{f', family={self.family!r}' if self.family else ''})")
