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
  strings ``"inf"``, ``"-inf"``, ``"nan"``).

:class:`Result` is the mixin that gives ``to_dict`` from the fields a result
declares; :class:`ResultArray` is the ndarray subclass for results that are
arrays (a free response, an adjugate), whose figures live only on the whole
array returned by pinlin.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

__all__ = ["Result", "ResultArray", "to_jsonable", "result_types"]



def _number(x) -> Any:
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (complex, np.complexfloating)):
        return {"re": _number(float(x.real)), "im": _number(float(x.imag))}
    x = float(x)
    if math.isfinite(x):
        return x + 0.0  # an exact zero is exported as 0, never -0 (issue 25)
    return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")


def to_jsonable(value: Any) -> Any:
    """``value`` as JSON-serializable data (see the module docstring for the encoding)."""
    if value is None or isinstance(value, str):
        return str(value) if isinstance(value, str) else None
    if isinstance(value, Result):
        return value.to_dict()
    if isinstance(value, (bool, int, float, complex, np.generic)):
        return _number(value)
    if isinstance(value, np.ndarray):
        arr = np.asarray(value).view(np.ndarray)
        if arr.dtype.kind == "c":
            return {"re": to_jsonable(arr.real), "im": to_jsonable(arr.imag)}
        if arr.dtype.kind in "fiub":
            return [to_jsonable(x) for x in arr] if arr.ndim > 1 else [_number(x) for x in arr.ravel()]
        return [to_jsonable(x) for x in arr.tolist()]
    if isinstance(value, Mapping):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, set, frozenset)):
        return [to_jsonable(v) for v in value]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: to_jsonable(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if hasattr(value, "to_dict"):
        return value.to_dict()
    return repr(value)


class Result:
    """Mixin for result objects: ``to_dict()`` from the declared fields.

    Subclasses are usually frozen dataclasses (their fields are dumped) or set
    :attr:`_dict_fields` to the attribute names to dump.  Fields named in
    :attr:`_dict_exclude` (back-references to large inputs, such as the analysed
    system) are left out.  Every subclass provides ``elapsed``, ``method`` and
    ``error``.
    """

    _dict_fields: ClassVar[tuple[str, ...] | None] = None
    _dict_exclude: ClassVar[tuple[str, ...]] = ()

    def _field_names(self) -> tuple[str, ...]:
        if self._dict_fields is not None:
            names = self._dict_fields
        elif dataclasses.is_dataclass(self):
            names = tuple(f.name for f in dataclasses.fields(self))
        else:  # pragma: no cover (programming error)
            raise TypeError(f"{type(self).__name__} declares no fields for to_dict")
        return tuple(n for n in names if n not in self._dict_exclude)

    def to_dict(self) -> dict[str, Any]:
        """The result as JSON-serializable data, with ``type``, ``method``, ``error`` and ``elapsed`` first."""
        out: dict[str, Any] = {
            "type": type(self).__name__,
            "method": to_jsonable(str(self.method) if self.method is not None else None),
            "error": to_jsonable(self.error),
            "elapsed": to_jsonable(self.elapsed),
        }
        for name in self._field_names():
            if name not in out:
                out[name] = to_jsonable(getattr(self, name))
        return out


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
        out = Result.to_dict(self)
        out["values"] = to_jsonable(np.asarray(self).view(np.ndarray))
        return out


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
