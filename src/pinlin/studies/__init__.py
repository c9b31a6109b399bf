"""Studies over many systems: parameter sweeps and mode tracking.

- :mod:`.sweep` -- :func:`sweep`: evaluate a function over parameter values on any
  executor, with each point's error figure and run time taken where it ran;
- :mod:`.tracking` -- follow modes across a sweep by their shapes (MAC and assignment),
  and pick one mode of each conjugate pair for Campbell diagrams.
"""

from .sweep import SweepFailure, SweepResult, sweep
from .tracking import TrackedModes, mac, one_per_conjugate_pair, track_modes

__all__ = ["sweep", "SweepResult", "SweepFailure", "TrackedModes", "track_modes", "mac", "one_per_conjugate_pair"]
