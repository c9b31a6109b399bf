"""Studies over many systems: parameter sweeps and mode tracking.

- :mod:`.sweep` -- :func:`sweep`: evaluate a function over parameter values on any executor;
- :mod:`.tracking` -- follow modes across a sweep by their shapes (MAC and assignment).
"""

from .sweep import SweepFailure, SweepResult, sweep
from .tracking import TrackedModes, mac, track_modes

__all__ = ["sweep", "SweepResult", "SweepFailure", "TrackedModes", "track_modes", "mac"]
