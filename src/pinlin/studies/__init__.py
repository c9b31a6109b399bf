"""Studies over many systems: parameter sweeps and mode tracking.

- :mod:`.sweep` -- :func:`sweep`: evaluate a function over parameter values on any
  executor, with each point's error figure and run time taken where it ran;
- :mod:`.grid` -- the points of a grid, counted and capped (``max_points``) before any is built;
- :mod:`.sweep_result` -- :class:`SweepResult` (values in grid order),
  :class:`SweepFailure` (a point that raised) and :class:`SweepTimeoutError`;
- :mod:`.scheduling` -- running the points here or on an executor, collected in
  completion order and returned in grid order;
- :mod:`.progress` -- progress in completion order: a text bar, tqdm when installed;
- :mod:`.ray_executor` -- :class:`RayExecutor`: Ray tasks behind the Executor interface
  (Dask has its own: ``Client.get_executor()``);
- :mod:`.tracking` -- follow modes across a sweep by their shapes (MAC and assignment),
  and pick one mode of each conjugate pair for Campbell diagrams;
- :mod:`.floquet_campbell` -- :func:`floquet_campbell`: Floquet exponents of a periodic family against a speed,
  identified by their harmonic content and tracked.
"""

from .floquet_campbell import FloquetCampbell, floquet_campbell
from .grid import MAX_POINTS
from .ray_executor import RayExecutor
from .sweep import SweepFailure, SweepResult, SweepTimeoutError, sweep
from .tracking import TrackedModes, mac, one_per_conjugate_pair, track_modes

__all__ = [
    "sweep",
    "SweepResult",
    "SweepFailure",
    "SweepTimeoutError",
    "MAX_POINTS",
    "RayExecutor",
    "TrackedModes",
    "track_modes",
    "mac",
    "one_per_conjugate_pair",
    "floquet_campbell",
    "FloquetCampbell",
]
