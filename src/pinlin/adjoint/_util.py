"""Shared helpers of the adjoint package: input checks, scales, result arrays.

Nothing here is public API; see :mod:`pinlin.adjoint`.
"""

from __future__ import annotations

import numbers
from collections.abc import Sequence

import numpy as np
import scipy.linalg as sla

from ..errors import ComputationError, ParameterError
from ..linearization.system import LinearizedSystem

EPS = float(np.finfo(float).eps)
#: Natural log of the largest and smallest positive normal doubles.
LOG_MAX = float(np.log(np.finfo(float).max))
LOG_TINY = float(np.log(np.finfo(float).tiny))


def check_system(sys) -> LinearizedSystem:
    """``sys`` itself if it is a :class:`~pinlin.LinearizedSystem`, else ParameterError."""
    if not isinstance(sys, LinearizedSystem):
        raise ParameterError(
            "sys",
            f"expected a pinlin.LinearizedSystem (see LinearizedSystem.from_matrices), got {type(sys).__name__}",
        )
    return sys


def complex_scalar(value, name: str) -> complex:
    """A finite complex scalar, or ParameterError naming ``name``."""
    if isinstance(value, np.ndarray):
        if value.ndim != 0:
            raise ParameterError(name, f"expected a scalar, got an array of shape {value.shape}")
        value = value.item()
    if not isinstance(value, numbers.Number) or isinstance(value, bool):
        raise ParameterError(name, f"expected a complex number, got {type(value).__name__}")
    z = complex(value)
    if not (np.isfinite(z.real) and np.isfinite(z.imag)):
        raise ParameterError(name, f"must be finite, got {value!r}")
    return z


def complex_points(values, name: str) -> tuple[np.ndarray, bool]:
    """Finite complex points as a 1-D array, and whether the input was a scalar."""
    try:
        arr = np.asarray(values)
    except (TypeError, ValueError):
        raise ParameterError(name, "expected a complex number or an array of them") from None
    if arr.dtype == object or not (np.issubdtype(arr.dtype, np.number)) or arr.dtype == bool:
        raise ParameterError(name, f"expected complex numbers, got dtype {arr.dtype}")
    if arr.ndim > 1:
        raise ParameterError(name, f"expected a scalar or a 1-D array, got shape {arr.shape}")
    scalar = arr.ndim == 0
    arr = np.atleast_1d(arr).astype(complex)
    if arr.size == 0:
        raise ParameterError(name, "expected at least one point, got an empty array")
    bad = ~np.isfinite(arr)
    if np.any(bad):
        raise ParameterError(name, f"must be finite; entry {int(np.flatnonzero(bad)[0])} is {arr[bad][0]}")
    return arr, scalar


def positive(value, name: str) -> float:
    """A finite positive float, or ParameterError."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, f"expected a positive number, got {value!r}") from None
    if not (np.isfinite(v) and v > 0):
        raise ParameterError(name, f"must be a finite positive number, got {value!r}")
    return v


def check_radii(radii) -> np.ndarray:
    """Contour radii: a non-empty 1-D array of finite positive numbers.

    Raises
    ------
    ParameterError
        Anything else.
    """
    try:
        r = np.atleast_1d(np.asarray(radii, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError("radii", f"expected positive numbers, got {radii!r}") from None
    if r.ndim != 1 or r.size == 0 or not np.all(np.isfinite(r)) or np.any(r <= 0):
        raise ParameterError("radii", f"expected a non-empty list of finite positive radii, got {radii!r}")
    return r


def dof_indices(sys: LinearizedSystem, which, name: str) -> np.ndarray:
    """Indices of the coordinates named or numbered in ``which`` (None: all of them)."""
    if which is None:
        return np.arange(sys.n)
    items = [which] if isinstance(which, (str, numbers.Integral)) else which
    if not isinstance(items, (Sequence, np.ndarray)) or len(items) == 0:
        raise ParameterError(name, f"expected a coordinate index or name, or a non-empty list of them, got {which!r}")
    out = []
    for item in items:
        if isinstance(item, str):
            if item not in sys.dof_names:
                raise ParameterError(name, f"unknown coordinate {item!r}; valid names: {list(sys.dof_names)}")
            out.append(sys.dof_names.index(item))
        elif isinstance(item, numbers.Integral) and not isinstance(item, bool):
            if not 0 <= int(item) < sys.n:
                raise ParameterError(name, f"index {item} out of range for n = {sys.n} coordinates")
            out.append(int(item))
        else:
            raise ParameterError(name, f"expected coordinate indices or names, got {item!r}")
    return np.asarray(out, dtype=int)


def eigenvalue_bounds(sys: LinearizedSystem) -> tuple[float, float]:
    """Bounds ``lo <= |lam_k| <= hi`` on the moduli of all eigenvalues.

    From ``lam^2 x = -M^{-1}(lam C + K) x``: ``|lam|^2 <= a |lam| + b`` with
    ``a = ||M^{-1} C||_2``, ``b = ||M^{-1} K||_2``; likewise for ``1/lam`` with
    ``K^{-1}`` when K is safely invertible (otherwise ``lo = 0``).
    """
    cho = sla.cho_factor(sys.M)
    a = np.linalg.norm(sla.cho_solve(cho, sys.C), 2)
    b = np.linalg.norm(sla.cho_solve(cho, sys.K), 2)
    hi = 0.5 * (a + np.sqrt(a * a + 4 * b))
    lo = 0.0
    if np.any(sys.K):
        sv = np.linalg.svd(sys.K, compute_uv=False)
        if sv[-1] > 1e3 * sys.n * EPS * sv[0]:
            a2 = np.linalg.norm(np.linalg.solve(sys.K, sys.C), 2)
            b2 = np.linalg.norm(np.linalg.solve(sys.K, sys.M), 2)
            lo = 2.0 / (a2 + np.sqrt(a2 * a2 + 4 * b2))
    return float(lo), float(hi)


def natural_scale(sys: LinearizedSystem) -> float:
    """A modulus typical of the eigenvalues [1/s].

    The geometric mean ``|det K / det M|^(1/2n)`` of the eigenvalue moduli when K
    is nonsingular, otherwise the Fan-Lin-Van Dooren ``sqrt(||K|| / ||M||)``
    (SPEC section 4), otherwise ``||C|| / ||M||``, otherwise 1.
    """
    n = sys.n
    sk, lk = np.linalg.slogdet(sys.K)
    if sk != 0 and np.isfinite(lk):
        _, lm = np.linalg.slogdet(sys.M)
        return float(np.exp((lk - lm) / (2 * n)))
    nm = np.linalg.norm(sys.M)
    for num, power in ((np.linalg.norm(sys.K), 0.5), (np.linalg.norm(sys.C), 1.0)):
        if num > 0:
            return float((num / nm) ** power)
    return 1.0


def checked_exp(log_value: np.ndarray | float, what: str, *, each: bool = False) -> np.ndarray:
    """``exp(log_value)``, raising ComputationError when it overflows or underflows.

    Underflow is an error when the largest value underflows (everything would be
    zero), or, with ``each=True``, when any finite value does.  NaN entries are
    ignored (and returned as NaN: callers pass them only for values they discard).
    """
    lv = np.asarray(log_value, dtype=float)
    finite = lv[np.isfinite(lv)]
    if finite.size and finite.max() > LOG_MAX:
        raise ComputationError(
            f"{what} overflows double precision (about 10^{finite.max() / np.log(10):.0f}); "
            f"rescale the system (units, for example mm and g instead of m and kg)"
        )
    low = finite.min() if each and finite.size else (finite.max() if finite.size else 0.0)
    if finite.size and low < LOG_TINY:
        raise ComputationError(
            f"{what} underflows double precision (about 10^{low / np.log(10):.0f}); "
            f"rescale the system (units, for example mm and g instead of m and kg)"
        )
    return np.exp(lv)


class ResultArray(np.ndarray):
    """An ndarray that also carries the error figures of the computation that made it.

    The metadata (``_meta`` names) lives only on the array a pinlin function
    returned: views, slices and arithmetic results are plain data and carry
    ``None`` (an error figure of ``A`` says nothing about ``A + 1``).  Ufunc
    results are plain :class:`numpy.ndarray`.
    """

    _meta: tuple[str, ...] = ()

    def __new__(cls, data, **meta):
        obj = np.asarray(data).view(cls)
        unknown = set(meta) - set(cls._meta)
        if unknown:
            raise TypeError(f"unknown fields {sorted(unknown)} for {cls.__name__}")
        for key in cls._meta:
            setattr(obj, key, meta.get(key))
        return obj

    def __array_finalize__(self, obj):
        for key in self._meta:
            setattr(self, key, None)

    def __array_ufunc__(self, ufunc, method, *inputs, out=None, **kwargs):
        inputs = tuple(x.view(np.ndarray) if isinstance(x, ResultArray) else x for x in inputs)
        if out is not None:
            kwargs["out"] = tuple(o.view(np.ndarray) if isinstance(o, ResultArray) else o for o in out)
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __reduce__(self):
        # pickle as plain data: the metadata describes one computation, not the numbers
        return self.view(np.ndarray).__reduce__()
