"""Optional dependencies, imported when first asked for (each names the extra that installs it).

Nothing here imports an optional package at import time; a missing one raises
:class:`~pinlin.errors.MissingDependencyError` with the ``pip install`` line.
"""

from __future__ import annotations

import importlib

from .errors import MissingDependencyError

__all__ = ["import_control", "import_pandas", "import_ray", "optional_module"]


def optional_module(name: str, message: str):
    """The module ``name``, or :class:`~pinlin.errors.MissingDependencyError` with ``message`` (the install line).

    A module that was blocked (``sys.modules[name] = None``) counts as missing.

    Examples
    --------
    >>> from pinlin.extras import optional_module
    >>> optional_module("json", "pip install json").__name__
    'json'
    >>> optional_module("no_such_module", "this needs no_such_module: pip install it")
    Traceback (most recent call last):
    ...
    pinlin.errors.base.MissingDependencyError: this needs no_such_module: pip install it
    """
    try:
        return importlib.import_module(name)
    except ImportError as exc:
        raise MissingDependencyError(message) from exc


def import_control():
    """The ``control`` module.

    Raises
    ------
    MissingDependencyError
        python-control is not installed.

    Examples
    --------
    >>> from pinlin.extras import import_control
    >>> def available():
    ...     try:
    ...         return import_control().__name__
    ...     except pinlin.MissingDependencyError as exc:  # the message names the pip install line
    ...         return "pip install" in str(exc)
    >>> available() in ("control", True)
    True
    """
    return optional_module("control", "this needs python-control (>= 0.10): pip install 'pinlin[control]'")


def import_pandas():
    """The ``pandas`` module (for the ``to_pandas()`` tables of results).

    Raises
    ------
    MissingDependencyError
        pandas is not installed.

    Examples
    --------
    >>> from pinlin.extras import import_pandas
    >>> def available():
    ...     try:
    ...         return import_pandas().__name__
    ...     except pinlin.MissingDependencyError as exc:  # the message names the pip install line
    ...         return "pip install" in str(exc)
    >>> available() in ("pandas", True)
    True
    """
    return optional_module("pandas", "this needs pandas (>= 2.0): pip install 'pinlin[pandas]'")


def import_ray():
    """The ``ray`` module (for :class:`pinlin.studies.RayExecutor`).

    Raises
    ------
    MissingDependencyError
        Ray is not installed.

    Examples
    --------
    >>> from pinlin.extras import import_ray
    >>> def available():
    ...     try:
    ...         return import_ray().__name__
    ...     except pinlin.MissingDependencyError as exc:  # the message names the pip install line
    ...         return str(exc)
    >>> available() in ("ray", "RayExecutor needs Ray: pip install ray")
    True
    """
    return optional_module("ray", "RayExecutor needs Ray: pip install ray")
