"""The nonlinear reference: Pinocchio forward dynamics of a scene, integrated on its configuration manifold.

Modules, in the order of the computation:

- :mod:`.dynamics` -- the right-hand side: free accelerations of a scene at (q, v), in the
  calling thread's Pinocchio workspace; the initial velocity check;
- :mod:`.charts` -- local charts q = integrate(q_b, dq) of the configuration manifold;
- :mod:`.budget` -- the steps and wall time one integration may take, checked at every step;
- :mod:`.integration` -- one ``solve_ivp`` integration across charts (re-centring on events);
- :mod:`.simulate` -- :func:`simulate`: checks, the run, its error estimate (a comparison run);
- :mod:`.result` -- :class:`Simulation`, the (len(t), nq) array of configurations with its figures;
- :mod:`.coordinates` -- :func:`linear_coordinates`, the deviation from an operating point in
  the coordinates of a :class:`~pinlin.LinearizedSystem`.
"""

from .budget import PROJECTION_FACTOR, PROJECTION_MIN_STEPS
from .coordinates import linear_coordinates
from .result import Simulation
from .simulate import DEFAULT_MAX_STEPS, ERROR_TOL_FACTOR, EXPLICIT_METHODS, IMPLICIT_METHODS, simulate

__all__ = [
    "Simulation",
    "simulate",
    "linear_coordinates",
    "EXPLICIT_METHODS",
    "IMPLICIT_METHODS",
    "ERROR_TOL_FACTOR",
    "DEFAULT_MAX_STEPS",
    "PROJECTION_FACTOR",
    "PROJECTION_MIN_STEPS",
]
