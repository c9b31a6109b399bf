"""Optional dependencies, imported when first asked for (each names the extra that installs it).

Nothing here imports an optional package at import time; a missing one raises
:class:`~pinlin.errors.MissingDependencyError` with the ``pip install`` line.
"""

from __future__ import annotations

from .errors import MissingDependencyError

__all__ = ["import_control"]


def import_control():
    """The ``control`` module.

    Raises
    ------
    MissingDependencyError
        python-control is not installed.
    """
    try:
        import control
    except ImportError as exc:
        raise MissingDependencyError(
            "this needs python-control (>= 0.10): pip install 'pinlin[control]'"
        ) from exc
    return control
