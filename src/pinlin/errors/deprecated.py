"""Every deprecation of pinlin in one place: renamed keywords, reordered arguments and renamed names.

A deprecated spelling keeps working for one release, warns with a :class:`DeprecationWarning` that names
the new spelling, and is then removed (the CHANGELOG lists each with its release).  Two tools:

- :func:`renamed_keywords`, a decorator: ``@renamed_keywords(tol="rtol")`` maps a call's old keyword to the
  new one and warns; passing both is an error;
- :func:`reordered_arguments`, a decorator: a call in a function's previous positional order (recognized
  by a test of the arguments) is mapped to the new order and warns;
- :func:`deprecated_names`, a module ``__getattr__``: an old module-level name (an exception class merged into
  its parent, a moved function) resolves to the new object and warns.

Examples
--------
>>> import warnings
>>> @renamed_keywords(tol="rtol")
... def solve(x, *, rtol=1e-8):
...     return rtol
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     solve(1.0, tol=1e-6)
1e-06
>>> print(caught[0].category.__name__, caught[0].message)
DeprecationWarning solve(tol=...) is deprecated since pinlin 0.4 and will be removed in 0.5: use rtol=...
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable

from .base import ParameterError, warn_user

__all__ = ["REMOVED_IN", "renamed_keywords", "reordered_arguments", "deprecated_names", "warn_deprecated"]

#: The release that removes what this module keeps alive.
REMOVED_IN = "0.5"
#: The release that deprecated it.
DEPRECATED_IN = "0.4"


def warn_deprecated(old: str, new: str) -> None:
    """Warn, at the caller's line (the first frame outside pinlin), that ``old`` is deprecated for ``new``.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_deprecated("pinlin.AssemblyError", "pinlin.LoopClosureError")
    >>> "use pinlin.LoopClosureError" in str(caught[0].message)
    True
    """
    warn_user(f"{old} is deprecated since pinlin {DEPRECATED_IN} and will be removed in {REMOVED_IN}: use {new}",
              DeprecationWarning)


def renamed_keywords(**renames: str) -> Callable:
    """Decorator: accept each old keyword (``old="new"``) for one release, with a warning.

    Examples
    --------
    >>> @renamed_keywords(structure_tolerance="structure_tol")
    ... def decide(*, structure_tol=None):
    ...     return structure_tol
    >>> decide(structure_tol=1e-9)
    1e-09
    >>> decide(structure_tolerance=1e-9, structure_tol=1e-9)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: structure_tolerance: is the deprecated name of structure_tol; pass only structure_tol
    """

    def decorate(func: Callable) -> Callable:
        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            for old, new in renames.items():
                if old in kwargs:
                    if new in kwargs:
                        raise ParameterError(old, f"is the deprecated name of {new}; pass only {new}")
                    warn_deprecated(f"{func.__name__}({old}=...)", f"{new}=...")
                    kwargs[new] = kwargs.pop(old)
            return func(*args, **kwargs)

        wrapper.__deprecated_keywords__ = dict(renames)
        return wrapper

    return decorate


def reordered_arguments(old: tuple[str, ...], is_old: Callable[[tuple, dict], bool]) -> Callable:
    """Decorator: accept a call in the previous positional order ``old`` for one release, with a warning.

    ``old`` names the parameters in their previous order; ``is_old(args, kwargs)`` tells a call in that
    order from one in the new order (from the kinds and shapes of the arguments).  Such a call is passed
    on by keyword; any other call is passed on unchanged.

    Examples
    --------
    >>> import warnings
    >>> @reordered_arguments(("f", "t"), lambda args, kwargs: bool(args) and callable(args[0]))
    ... def grid(t, f=None):
    ...     return [f(x) for x in t]
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     grid(abs, [-1, 2])
    [1, 2]
    >>> print(caught[0].message)
    grid(f, t) is deprecated since pinlin 0.4 and will be removed in 0.5: use grid(t, f)
    >>> grid([-1, 2], abs)
    [1, 2]
    """

    def decorate(func: Callable) -> Callable:
        new = [name for name in inspect.signature(func).parameters if name in old]

        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            if is_old(args, kwargs):
                warn_deprecated(f"{func.__name__}({', '.join(old)})", f"{func.__name__}({', '.join(new)})")
                if len(args) > len(old):
                    raise TypeError(f"{func.__name__}() takes {len(old)} positional arguments in its old order")
                for name, value in zip(old, args):
                    if name in kwargs:
                        raise TypeError(f"{func.__name__}() got multiple values for argument {name!r}")
                    kwargs[name] = value
                args = ()
            return func(*args, **kwargs)

        return wrapper

    return decorate


def deprecated_names(module: str, names: dict[str, tuple[str, Callable[[], object]]]) -> Callable[[str], object]:
    """A module ``__getattr__`` that resolves each old name to its replacement, with a warning.

    ``names`` maps an old name to ``(the new name as users spell it, a function returning the object)``: the
    object is looked up when the old name is used, so the module that defines it is imported only then.

    Examples
    --------
    >>> __getattr__ = deprecated_names("pkg", {"OldError": ("pkg.NewError", lambda: ValueError)})
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     __getattr__("OldError")
    <class 'ValueError'>
    >>> __getattr__("Missing")
    Traceback (most recent call last):
    ...
    AttributeError: module 'pkg' has no attribute 'Missing'
    """

    def __getattr__(name: str) -> object:
        if name in names:
            new, resolve = names[name]
            warn_deprecated(f"{module}.{name}", new)
            return resolve()
        raise AttributeError(f"module {module!r} has no attribute {name!r}")

    return __getattr__
