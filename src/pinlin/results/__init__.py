"""The one result convention of pinlin (docs/conventions.md).

Every object an analysis returns carries

- ``elapsed`` [s]: wall time of the call that made it;
- ``method``: what was computed and how (a short string; some results attach a
  ``.reason``);
- ``error``: its headline error figure, one float whose meaning each result
  documents (relative unless its docstring says otherwise); detailed figures
  (per-eigenvalue backward errors, per-frequency residuals) keep their own names;
- a one-screen ``__repr__`` (never the full arrays);
- ``to_dict()``: plain JSON-serializable data (complex numbers as
  ``{"re": ..., "im": ...}``, arrays as nested lists, non-finite floats as the
  strings ``"inf"``, ``"-inf"``, ``"nan"``), with an ``"encoding"`` entry that
  says how to read each value back (dtype and shape of arrays, tuple or list,
  complex, non-finite floats, nested results and value types);
- ``from_dict(d)`` / :func:`load`: the result back from that data (or a JSON file).

:class:`Result` is the mixin that gives ``to_dict`` from the fields a result
declares; :class:`ResultArray` is the ndarray subclass for results that are
arrays (a free response, an adjugate), whose figures live only on the whole
array returned by pinlin.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

from .core import Result, decode, encode, persistent, to_jsonable

__all__ = ["Result", "ResultArray", "to_jsonable", "result_types", "load", "persistent", "encode", "decode"]


def load(source) -> Result:
    """A result from its ``to_dict()`` data or a JSON file holding it.

    Parameters
    ----------
    source : str, os.PathLike or mapping
        A path to a JSON file written from ``json.dump(result.to_dict(), f)``, or that dict.

    Returns
    -------
    Result
        Equal to the result that was saved, in every field ``to_dict()`` keeps (see docs/conventions.md).

    Raises
    ------
    ParameterError
        ``source`` is neither a mapping nor a readable JSON file, or it is not a result's data.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), np.zeros((2, 2)), np.diag([1.0, 4.0]))
    >>> modes = pinlin.modal_analysis(sys)
    >>> again = pinlin.load(modes.to_dict())  # or a JSON file written from it
    >>> type(again).__name__, bool(np.allclose(again.eigenvalues, modes.eigenvalues))
    ('Modes', True)
    """
    import json
    import os

    from ..errors import ParameterError

    if isinstance(source, Mapping):
        return Result.from_dict(source)
    if not isinstance(source, (str, os.PathLike)):
        raise ParameterError("source", f"expected a path to a JSON file or a dict, got {type(source).__name__}")
    try:
        with open(source, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as exc:
        raise ParameterError("source", f"cannot read a result from {os.fspath(source)!r}: {exc}") from exc
    return Result.from_dict(data)


class ResultArray(np.ndarray, Result):
    """An ndarray that carries the figures of the computation that made it.

    Shape, dtype, indexing and arithmetic are the array's.  The figures (named in
    ``_fields``) live only on the whole array a pinlin function returned: views
    of parts, slices and arithmetic results are plain :class:`numpy.ndarray`
    (an error figure of ``A`` says nothing about ``A[0]`` or ``A + 1``).  The
    array is read-only.
    """

    _fields: ClassVar[tuple[str, ...]] = ()

    def __new__(cls, values, **fields):
        obj = np.asarray(values).view(cls)
        unknown = set(fields) - set(cls._fields)
        if unknown:  # pragma: no cover (programming error)
            raise TypeError(f"unknown fields {sorted(unknown)} for {cls.__name__}")
        obj._meta = {name: fields.get(name) for name in cls._fields}
        obj.flags.writeable = False
        return obj

    def __array_finalize__(self, obj):
        meta = getattr(obj, "_meta", None)
        # Only a view of the whole array keeps the figures; slices and copies of parts do not.
        self._meta = meta if meta is not None and getattr(obj, "shape", None) == self.shape else None

    def __array_wrap__(self, array, context=None, return_scalar=False):
        out = np.asarray(array).view(np.ndarray)
        return out[()] if return_scalar else out

    def __array_ufunc__(self, ufunc, method, *inputs, out=None, **kwargs):
        inputs = tuple(x.view(np.ndarray) if isinstance(x, ResultArray) else x for x in inputs)
        if out is not None:
            kwargs["out"] = tuple(o.view(np.ndarray) if isinstance(o, ResultArray) else o for o in out)
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __getitem__(self, key):
        out = super().__getitem__(key)
        return out.view(np.ndarray) if isinstance(out, ResultArray) else out

    def __getattr__(self, name):
        meta = self.__dict__.get("_meta")
        if meta is not None and name in meta:
            return meta[name]
        if name in type(self)._fields:
            raise AttributeError(f"{name!r} is only available on the whole result, not on a part of it")
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def __reduce__(self):
        # pickle as plain data: the figures describe one computation, not the numbers
        return (np.array, (np.asarray(self).view(np.ndarray),))

    def __repr__(self) -> str:
        figures = ", ".join(self._summary()) if self.__dict__.get("_meta") is not None else ""
        return f"{type(self).__name__}(shape={self.shape}, dtype={self.dtype}{', ' if figures else ''}{figures})"

    def _summary(self) -> list[str]:
        """Short ``name=value`` strings for the repr; subclasses add theirs."""
        out = []
        for name in ("method", "error", "elapsed"):
            value = self._meta.get(name) if self._meta else None
            if isinstance(value, float):
                out.append(f"{name}={value:.2e}" if name == "error" else f"{name}={value * 1e3:.3g} ms")
            elif value is not None:
                out.append(f"{name}={value!r}")
        return out

    def __str__(self) -> str:
        return np.asarray(self).view(np.ndarray).__str__()

    def _field_names(self) -> tuple[str, ...]:
        return tuple(n for n in self._fields if n not in self._dict_exclude)

    def to_dict(self) -> dict[str, Any]:
        """The figures and the values (``"values"``) as JSON-serializable data."""
        return Result.to_dict(self, extra={"values": np.asarray(self).view(np.ndarray)})

    @classmethod
    def _from_values(cls, values: dict[str, Any]) -> ResultArray:
        return cls(values["values"], **{k: values.get(k) for k in cls._fields})


def result_types() -> list[type]:
    """Every result class defined in pinlin (subclasses of :class:`Result`), for tests and docs."""
    seen: list[type] = []
    stack = list(Result.__subclasses__())
    while stack:
        cls = stack.pop()
        if cls not in seen and cls is not ResultArray:
            seen.append(cls)
        stack.extend(cls.__subclasses__())
    return sorted(seen, key=lambda c: (c.__module__, c.__name__))
