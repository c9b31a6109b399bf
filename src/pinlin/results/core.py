"""The result base class and the reversible JSON encoding of results (see :mod:`pinlin.results`)."""

from __future__ import annotations

import dataclasses
import functools
import inspect
import math
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

__all__ = ["Result", "to_jsonable", "persistent", "encode", "decode"]


def _number(x) -> Any:
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (complex, np.complexfloating)):
        return {"re": _number(float(x.real)), "im": _number(float(x.imag))}
    x = float(x)
    if math.isfinite(x):
        return x + 0.0  # an exact zero is exported as 0, never -0 (a sign that carries no information)
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


#: Result classes by name (filled by :meth:`Result.__init_subclass__`) and value types by name (:func:`persistent`).
_RESULTS: dict[str, type] = {}
_VALUES: dict[str, type] = {}


def persistent(cls: type) -> type:
    """Class decorator: a value type held by results (a frozen dataclass, or a class whose ``__reduce__``
    returns ``(cls, args)`` with plain arguments) that :func:`decode` rebuilds by its name."""
    _VALUES[cls.__name__] = cls
    return cls


def _array_spec(arr: np.ndarray) -> dict:
    spec: dict[str, Any] = {"ndarray": arr.dtype.str if arr.dtype.kind != "O" else "object", "shape": list(arr.shape)}
    if arr.dtype.kind == "O":
        spec["items"] = [encode(x)[1] for x in arr.ravel()]
    return spec


def _spec(value: Any) -> Any:
    """How :func:`decode` reads back ``to_jsonable(value)``: None where the JSON value is the value itself."""
    if value is None or type(value) in (str, bool):
        return None
    if isinstance(value, Result):
        return {"result": type(value).__name__}
    if type(value).__name__ in _VALUES and _VALUES[type(value).__name__] is type(value):
        if dataclasses.is_dataclass(value):
            fields = {f.name: _spec(getattr(value, f.name)) for f in dataclasses.fields(value)}
            return {"value": type(value).__name__, "fields": {k: v for k, v in fields.items() if v is not None}}
        _, args = value.__reduce__()[:2]
        return {"value": type(value).__name__, "args": to_jsonable(args), "args_encoding": _spec(tuple(args))}
    if isinstance(value, np.ndarray):
        return _array_spec(np.asarray(value).view(np.ndarray))
    if isinstance(value, np.generic):
        return {"scalar": value.dtype.str}
    if isinstance(value, (bool, int)):
        return None
    if isinstance(value, float):
        return None if math.isfinite(value) else "float"
    if isinstance(value, complex):
        return "complex"
    if isinstance(value, Mapping):
        items = {str(k): _spec(v) for k, v in value.items()}
        return {"dict": {k: v for k, v in items.items() if v is not None}}
    if isinstance(value, (list, tuple)):
        items = [_spec(v) for v in value]
        return {type(value).__name__ if type(value) in (list, tuple) else "list": (
            None if all(x is None for x in items) else items)}
    if isinstance(value, str):
        return None
    if isinstance(value, BaseException):
        return {"exception": type(value).__name__}
    return {"unkept": type(value).__name__}


def encode(value: Any) -> tuple[Any, Any]:
    """``(to_jsonable(value), spec)``: the JSON data and how :func:`decode` reads it back."""
    return to_jsonable(value), _spec(value)


def _float(x):
    return float(x) if isinstance(x, str) else x


def _decode_array(data, spec) -> np.ndarray:
    dtype, shape = spec["ndarray"], tuple(spec["shape"])
    if dtype == "object":
        flat = [decode(x, s) for x, s in zip(_flatten(data, len(shape)), spec["items"])]
        out = np.empty(len(flat), dtype=object)
        out[:] = flat
        out = out.reshape(shape)
    elif np.dtype(dtype).kind == "c":
        out = np.empty(shape, dtype=dtype)
        out.real = _decode_array(data["re"], {"ndarray": out.real.dtype.str, "shape": list(shape)})
        out.imag = _decode_array(data["im"], {"ndarray": out.real.dtype.str, "shape": list(shape)})
    else:
        raw = np.asarray(data, dtype=object).reshape(shape) if np.size(data) else np.empty(shape, dtype=object)
        out = np.vectorize(_float, otypes=[object])(raw) if raw.size else raw
        out = np.asarray(out.tolist() if raw.size else np.empty(shape), dtype=dtype).reshape(shape)
    out.flags.writeable = False  # arrays in results are read-only
    return out


def _flatten(data, depth):
    if depth <= 0:
        return [data]
    return [x for item in data for x in _flatten(item, depth - 1)] if depth > 1 else list(data)


def decode(data: Any, spec: Any = None) -> Any:
    """The value :func:`encode` gave ``data`` for, read by its ``spec``.

    Raises
    ------
    ParameterError
        The data names a result or value type pinlin does not know (or whose module is not imported).
    """
    if spec is None:
        return data
    if spec == "float":
        return _float(data)
    if spec == "complex":
        return complex(_float(data["re"]), _float(data["im"]))
    if "ndarray" in spec:
        return _decode_array(data, spec)
    if "scalar" in spec:
        dtype = np.dtype(spec["scalar"])
        return dtype.type(complex(_float(data["re"]), _float(data["im"])) if dtype.kind == "c" else _float(data))
    if "result" in spec:
        return Result.from_dict(data)
    if "value" in spec:
        cls = _known(_VALUES, spec["value"], "value type")
        if "fields" in spec:
            return cls(**{k: decode(v, spec["fields"].get(k)) for k, v in data.items()})
        return cls(*decode(spec["args"], spec["args_encoding"]))
    if "dict" in spec:
        return {k: decode(v, spec["dict"].get(k)) for k, v in data.items()}
    for kind in ("tuple", "list"):
        if kind in spec:
            items = data if spec[kind] is None else [decode(x, s) for x, s in zip(data, spec[kind])]
            return tuple(items) if kind == "tuple" else list(items)
    if "exception" in spec:
        return _exception(spec["exception"], data)
    return data  # {"unkept": type}: the repr string to_jsonable gave


def _exception(name: str, data):
    from .. import errors  # the layer below: errors -> results

    cls = getattr(errors, name, None)
    if not (isinstance(cls, type) and issubclass(cls, BaseException)):
        cls = errors.PinlinError
    exc = cls.__new__(cls)
    exc.args = (data.get("message", "") if isinstance(data, Mapping) else str(data),)
    return exc


def _known(registry: dict, name: str, what: str) -> type:
    if name not in registry:
        from ..errors import ParameterError

        raise ParameterError("data", f"unknown {what} {name!r}; known: {', '.join(sorted(registry))} "
                             "(import the module that defines it first)")
    return registry[name]


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

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        # for from_dict / load: a result class registers itself by name (a user's class of the same name as
        # one of pinlin's does not shadow it)
        if cls.__name__ not in _RESULTS or cls.__module__.startswith("pinlin."):
            _RESULTS[cls.__name__] = cls

    def to_dict(self, extra: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """The result as JSON-serializable data, with ``type``, ``method``, ``error`` and ``elapsed`` first.

        ``extra`` (for subclasses) adds more named values.  The fifth key, ``"encoding"``, maps each key
        whose JSON value is not the value itself to how :func:`decode` reads it back.
        """
        out: dict[str, Any] = {
            "type": type(self).__name__,
            "method": to_jsonable(str(self.method) if self.method is not None else None),
            "error": to_jsonable(self.error),
            "elapsed": to_jsonable(self.elapsed),
            "encoding": {},  # filled below; fifth, so that a result's own last keys stay last
        }
        encoding = {"method": _spec(self.method), "error": _spec(self.error), "elapsed": _spec(self.elapsed)}
        items = [(name, getattr(self, name)) for name in self._field_names()] + list((extra or {}).items())
        for name, value in items:
            if name not in out or name in (extra or {}):
                out[name], encoding[name] = encode(value)
        out["encoding"] = {k: v for k, v in encoding.items() if v is not None}
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Result:
        """The result whose :meth:`to_dict` gave ``data`` (its ``type`` picks the class).

        Every value ``to_dict`` keeps comes back equal (arrays with their dtype and shape,
        bitwise); what it leaves out (``_dict_exclude``) is None.

        Raises
        ------
        ParameterError
            ``data`` is not a result's data, or names a class other than ``cls`` (or a subclass).
        """
        from ..errors import ParameterError

        if not isinstance(data, Mapping) or not isinstance(data.get("type"), str):
            raise ParameterError("data", "expected the dict of a result's to_dict() (with a 'type' key)")
        target = _known(_RESULTS, data["type"], "result type")
        if not issubclass(target, cls):
            raise ParameterError("data", f"holds a {data['type']}, not a {cls.__name__}")
        encoding = data.get("encoding", {})
        values = {k: decode(v, encoding.get(k)) for k, v in data.items() if k not in ("type", "encoding")}
        return target._from_values(values)

    @classmethod
    def _from_values(cls, values: dict[str, Any]) -> Result:
        """Rebuild from decoded values: fields set directly (no validation again), values of properties
        formed on first access put where they would be kept, values derived from the others dropped."""
        if not dataclasses.is_dataclass(cls) and "__init__" in vars(cls):  # a constructor of its own
            params = inspect.signature(cls).parameters
            return cls(**{k: v for k, v in values.items() if k in params})
        obj = object.__new__(cls)
        names = [f.name for f in dataclasses.fields(cls)] if dataclasses.is_dataclass(cls) else list(cls._dict_fields)
        for name in names:
            object.__setattr__(obj, name, values.get(name))
        for name, value in values.items():
            if name not in names and isinstance(getattr(cls, name, None), functools.cached_property):
                obj.__dict__[name] = value
        # The derived values as saved, for properties that need a left-out input (``modes.dof_names``).
        obj.__dict__["_loaded"] = {k: v for k, v in values.items() if k not in names}
        return obj

