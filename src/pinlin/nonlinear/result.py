"""``Simulation``: a nonlinear trajectory, an array of configurations with its figures (docs/conventions.md)."""

from __future__ import annotations

import numpy as np

from ..results import ResultArray
from .coordinates import linear_coordinates

__all__ = ["Simulation"]


class Simulation(ResultArray):
    """A nonlinear trajectory of a scene: the (len(t), nq) array of configurations, with its figures.

    The array itself holds the configurations (theory: conventions: ``simulate``
    returns (len(t), nq)); time is the first index.  The rest are attributes;
    like every :class:`~pinlin.results.ResultArray` they live on the whole
    array only, and the array is read-only.

    Attributes
    ----------
    q : (len(t), nq) ndarray
        The configurations as a plain array (full Pinocchio configurations,
        prescribed joints included, normalized).
    v : (len(t), nv) ndarray
        Velocities in Pinocchio's tangent space (prescribed joints at their velocity).
    t : (len(t),) ndarray
        Times [s].
    scene : Scene
        The scene simulated (not part of :meth:`to_dict`).
    method : str
        What was integrated and how: the integrator, its options, the path of
        the dynamics and how ``error`` was estimated.
    error : float
        Estimated relative error of the trajectory, ``max(error_q, error_v)``:
        the difference from a comparison run whose tolerances are
        :data:`~pinlin.nonlinear.simulate.ERROR_TOL_FACTOR` times tighter (whose
        own error is then about that factor smaller), relative to the size of
        the motion.  NaN when ``simulate`` was called with ``estimate_error=False``.
    error_q : float
        max_t ||difference(q_ref(t), q(t))_f|| / max(max_t ||difference(q(t0), q(t))_f||, atol):
        the configuration error on the free coordinates f [tangent units], relative to
        how far the configuration moved (or to atol when it moved less).
    error_v : float
        max_t ||v_f(t) - v_ref,f(t)|| / max(max_t ||v_f(t)||, atol): the same for the
        free velocities.
    integrator : str
        The ``solve_ivp`` method (``"DOP853"``, ``"Radau"``, ...).
    rtol, atol : float
        Its tolerances (atol in the units of the tangent coordinates and velocities).
    max_step : float
        Largest step [s].
    chart_radius : float
        Largest rotation [rad] of a chart before re-centring.
    nfev, njev, nlu : int
        Right-hand side evaluations, Jacobian evaluations, LU decompositions of
        the returned run (summed over all charts).
    steps : int
        Solver steps of the returned run (summed over all charts).
    max_steps : int or None
        The step budget of each run (None: none).
    max_time : float or None
        The wall-time budget [s] of each run (None: none).
    reference_nfev : int
        Right-hand side evaluations of the comparison run (0 without one).
    charts : int
        Number of local charts used (1 + re-centrings, see :func:`pinlin.simulate`).
    elapsed : float
        Wall time [s] of the whole call, comparison run included.
    message : str
        The solver's last status message.

    Examples
    --------
    A small swing of the double pendulum against its linearization at rest:

    >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    >>> t = np.linspace(0.0, 1.0, 5)
    >>> sim = pinlin.simulate(scene, [1e-3, 0.0], t=t)
    >>> x, xdot = sim.linear_coordinates(np.zeros(2))
    >>> linear = pinlin.free_response(pinlin.linearize(scene, np.zeros(2)), t, [1e-3, 0.0])
    >>> sim.v.shape, bool(np.max(np.abs(x - linear)) < 1e-8)
    ((5, 2), True)
    """

    _fields = (
        "v", "t", "scene", "method", "error", "error_q", "error_v", "integrator", "rtol", "atol", "max_step",
        "chart_radius", "nfev", "njev", "nlu", "steps", "max_steps", "max_time", "reference_nfev", "charts",
        "elapsed", "message",
    )  # fmt: skip
    _dict_exclude = ("scene",)

    @property
    def q(self) -> np.ndarray:
        return np.asarray(self).view(np.ndarray)

    def linear_coordinates(self, q_op) -> tuple[np.ndarray, np.ndarray]:
        """This trajectory in the coordinates of the linearized system at ``q_op``.

        See :func:`pinlin.linear_coordinates`; returns (x, xdot), each (len(t), n).

        Raises
        ------
        ConfigurationError
            ``q_op`` has the wrong size or is not finite.

        Examples
        --------
        >>> scene = pinlin.Scene(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
        >>> sim = pinlin.simulate(scene, [1e-3, 0.0], t=np.linspace(0.0, 1.0, 3))
        >>> x, xdot = sim.linear_coordinates(np.zeros(2))
        >>> x.shape, xdot.shape, np.round(x[0] + 0.0, 6).tolist()
        ((3, 2), (3, 2), [0.001, 0.0])
        """
        return linear_coordinates(self.scene, q_op, self.q, self.v)

    def _summary(self) -> list[str]:
        return [
            f"t=[{self.t[0]:g}, {self.t[-1]:g}] s",
            f"integrator={self.integrator!r}",
            f"rtol={self.rtol:g}",
            f"error={self.error:.1e}",
            f"steps={self.steps}",
            f"nfev={self.nfev}",
            f"charts={self.charts}",
            f"elapsed={self.elapsed * 1e3:.1f} ms",
        ]

    def __str__(self) -> str:
        """The summary (as the repr): ``print(sim)`` shows what was integrated and how well, not
        len(t) x nq numbers (those are ``sim.q``)."""
        if self.__dict__.get("_meta") is None:  # pragma: no cover (a part is a plain ndarray)
            return super().__str__()
        return repr(self)
