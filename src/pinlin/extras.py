"""Optional dependencies, imported when first asked for (each names the extra that installs it).

Nothing here imports an optional package at import time; a missing one raises
:class:`~pinlin.errors.MissingDependencyError` with the ``pip install`` line.
"""

from __future__ import annotations

from .errors import MissingDependencyError

__all__ = ["import_control", "import_pandas"]


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


def import_pandas():
    """The ``pandas`` module (for the ``to_pandas()`` tables of results).

    Raises
    ------
    MissingDependencyError
        pandas is not installed.
    """
    try:
        import pandas
    except ImportError as exc:
        raise MissingDependencyError("this needs pandas (>= 2.0): pip install 'pinlin[pandas]'") from exc
    return pandas
