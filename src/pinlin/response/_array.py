"""An ndarray that carries the error figures of the response it holds.

The SPEC's API returns plain arrays from ``free_response`` ((len(t), n) real)
and ``harmonic_response`` (complex amplitudes).  These subclasses keep that
contract -- shape, dtype, indexing and arithmetic are the array's -- and add the
error figures and run time as attributes.  The attributes describe the whole
response: a slice or any computed array (``x[:, 0]``, ``2 * x``, ``x.max()``)
is a plain ndarray without them.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

__all__ = ["ResponseArray"]


class ResponseArray(np.ndarray):
    """Base class: a response array with named, read-only attributes listed in ``_fields``."""

    _fields: ClassVar[tuple[str, ...]] = ()

    def __new__(cls, values: np.ndarray, **fields):
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

    def __getitem__(self, key):
        out = super().__getitem__(key)
        return out.view(np.ndarray) if isinstance(out, ResponseArray) else out

    def __getattr__(self, name):
        meta = self.__dict__.get("_meta")
        if meta is not None and name in meta:
            return meta[name]
        if name in type(self)._fields:
            raise AttributeError(f"{name!r} is only available on the whole response, not on a part of it")
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def __reduce__(self):
        return (np.array, (np.asarray(self).view(np.ndarray),))

    def __repr__(self) -> str:
        figures = ", ".join(self._summary()) if self._meta is not None else ""
        return f"{type(self).__name__}(shape={self.shape}, dtype={self.dtype}{', ' if figures else ''}{figures})"

    def _summary(self) -> list[str]:
        return []

    def __str__(self) -> str:
        return np.asarray(self).view(np.ndarray).__str__()
