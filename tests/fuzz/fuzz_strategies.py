"""Shared pieces of the fuzzing harness, which keeps every bad input refused with a PinlinError.

- :func:`hard_deadline`: a per-example wall-clock limit that interrupts a hang (SIGALRM), which
  hypothesis's own ``deadline`` cannot (it only judges an example after it returns);
- :func:`outcome`: run a call and accept exactly two outcomes, a :class:`pinlin.PinlinError` or a
  result whose error figures are honest (:func:`check_result`); anything else fails the example;
- :func:`toml_dumps`: a small TOML writer for the mutated scene documents (tomllib only reads);
- strategies: :data:`NASTY_FLOATS`, :func:`arrays`, :func:`toml_values`, :func:`urdf_values`.
"""

from __future__ import annotations

import contextlib
import json
import math
import re
import signal
import warnings
from collections.abc import Callable, Mapping

import numpy as np
from hypothesis import strategies as st

import pinlin
from pinlin.results import Result, ResultArray

#: Wall time [s] one example may take before it counts as a hang: the slowest honest examples (an
#: equilibrium search and a modal analysis of a small scene on a loaded CI machine) take well under 5 s.
EXAMPLE_DEADLINE = 30.0

#: Floats that break naive code: zeros of both signs, the extremes of the double range, non-finite.
NASTY_FLOATS = st.sampled_from(
    [0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 5e-324, 1e300, -1e300, 1.7976931348623157e308, np.inf, -np.inf,
     np.nan, 1e-16, 1e16, 0.5]
)


class ExampleTimeout(Exception):
    """Raised inside an example that ran past :data:`EXAMPLE_DEADLINE` (never caught by pinlin code,
    which catches only its own and named exceptions)."""


@contextlib.contextmanager
def hard_deadline(seconds: float = EXAMPLE_DEADLINE):
    """Interrupt the block after ``seconds`` of wall time with :class:`ExampleTimeout` (main thread, POSIX)."""

    def expire(signum, frame):
        raise ExampleTimeout(f"the example ran longer than {seconds:g} s: a hang")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


#: Array attributes of results that carry the computed values (not detailed figures, which may be
#: documented NaN or inf, such as damping_ratio at lam = 0 or condition at a defective eigenvalue).
VALUE_ATTRIBUTES = ("eigenvalues", "q", "response", "M", "D", "G", "S", "N", "coef", "x", "xdot", "values")


def _numeric(a) -> bool:
    return isinstance(a, np.ndarray) and a.dtype.kind in "fc"


def check_result(result, what: str) -> None:
    """The result convention's promise on bad input: a finite headline ``error`` (or None where the
    convention documents it), and no NaN in the computed values while that error is finite."""
    if isinstance(result, (Result, ResultArray)):
        error = result.error
        assert error is None or isinstance(error, (int, float, np.floating)), f"{what}: error {error!r} is not a float"
        assert error is None or math.isfinite(error), f"{what}: headline error {error!r} is not finite"
        values = [np.asarray(result).view(np.ndarray)] if isinstance(result, ResultArray) else [
            getattr(result, name) for name in VALUE_ATTRIBUTES if _numeric(getattr(result, name, None))]
        for v in values:
            assert not np.isnan(v).any(), f"{what}: NaN in the values of a result with finite error {error!r}"
        json.dumps(result.to_dict(), allow_nan=False)  # to_dict is always plain JSON


def outcome(call: Callable[[], object], what: str):
    """``call()``'s result after :func:`check_result`, or None when it raised a PinlinError.

    Warnings are allowed (pinlin warns about what it computed but doubts; they
    are recorded, not shown); any other exception propagates and fails the
    example, as does a hang.
    """
    with hard_deadline(), warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        try:
            result = call()
        except pinlin.PinlinError:
            return None
    check_result(result, what)
    return result


# ---------------------------------------------------------------- arrays


#: Odd argument objects: not arrays, scalars where arrays belong, a ragged nested list.
ODD_OBJECTS = [None, "1.0", [], {"a": 1}, 3, 2.5, 1j, True, object()]
RAGGED = [[1.0], [2.0, 3.0]]


def arrays(shapes: list[tuple[int, ...]], *, ragged: bool = True, text: bool = True):
    """Array-like arguments: mostly the expected shapes with nasty or ordinary values, sometimes
    wrong shapes, dtypes (int, complex, bool, str, object), nested lists or scalars.

    ``ragged=False`` leaves out the ragged nested list and ``text=False`` the arrays of strings:
    for the functions where those are known bugs (see the tests that pass them).
    """
    values = st.one_of(st.floats(-10, 10, allow_nan=False), NASTY_FLOATS)

    def of_shape(shape):
        size = int(np.prod(shape)) if shape else 1
        return st.lists(values, min_size=size, max_size=size).map(lambda v: np.array(v, dtype=float).reshape(shape))

    right = st.sampled_from(shapes).flatmap(of_shape)
    odd = ODD_OBJECTS + ([RAGGED] if ragged else [])
    wrong = [
        st.tuples(st.integers(0, 4), st.integers(0, 4)).flatmap(of_shape),
        st.integers(0, 5).flatmap(lambda n: of_shape((n,))),
        right.map(lambda a: a.astype(complex) * (1 + 1j)),
        right.map(lambda a: np.clip(np.nan_to_num(a), -1e9, 1e9).astype(int)),
        right.map(lambda a: a.astype(bool)),
        right.map(lambda a: a.tolist()),
        st.sampled_from(odd),
    ]
    if text:
        wrong.append(right.map(lambda a: a.astype(str)))
    return st.one_of(right, right, st.one_of(wrong))


# ---------------------------------------------------------------- TOML


def _string(text: str) -> str:
    """A TOML basic string: quotes, backslashes and control characters escaped, the rest as is."""
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else _string(k)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v == math.inf else "-inf" if v == -math.inf else repr(v))
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return str(v)  # dates and times print as TOML literals


def toml_dumps(doc: Mapping) -> str:
    """TOML text of a document: top-level tables as ``[name]``, lists of tables as ``[[name]]``."""
    head, tables = [], []
    for k, v in doc.items():
        if isinstance(v, Mapping):
            tables.append(f"[{_key(k)}]")
            tables += [f"{_key(a)} = {_value(b)}" for a, b in v.items()]
        elif isinstance(v, list) and v and all(isinstance(x, Mapping) for x in v):
            for item in v:
                tables.append(f"[[{_key(k)}]]")
                tables += [f"{_key(a)} = {_value(b)}" for a, b in item.items()]
        else:
            head.append(f"{_key(k)} = {_value(v)}")
    return "\n".join(head + tables) + "\n"


NAMES = ["joint1", "joint2", "tip", "base", "link1", "knee", "", " ", "../../etc/passwd", "joint1\u0000",
         "double_pendulum.urdf", "ur5", "\u00e9t\u00e9", "x" * 300]


def toml_values(depth: int = 3):
    """Values a TOML document can hold: numbers (nasty ones too), strings, booleans, dates, arrays, tables."""
    scalars = st.one_of(
        st.integers(-(2**63), 2**63 - 1),
        st.sampled_from([0, -1, 2, 10**400]),
        st.floats(allow_nan=True, allow_infinity=True),
        NASTY_FLOATS,
        st.sampled_from(NAMES),
        st.text(max_size=8),
        st.booleans(),
        st.dates(),
    )
    return st.recursive(
        scalars,
        lambda inner: st.one_of(st.lists(inner, max_size=4),
                                st.dictionaries(st.sampled_from(["a", "joint1", "xyz", "rpy", "start"]), inner,
                                                max_size=3)),
        max_leaves=8,
    )


# ---------------------------------------------------------------- URDF

#: Attribute values that urdfdom or pinlin may read wrongly.
URDF_VALUES = ["nan", "inf", "-inf", "1e999", "-1e999", "abc", "", " ", "-1", "0", "1e-300", "1e300", "-0",
               "1 2", "0 0 0", "1 1 1 1", "0x10", "1,5", "NaN", "+inf", "&lt;", "1e-320", "5"]


def urdf_values():
    """Nasty attribute values, any float, short text, and plausible numbers (so that mutated models
    also reach the analyses, not only the loader's checks)."""
    plausible = st.one_of(st.floats(-2, 2), st.floats(0, 1e3)).map(repr)
    return st.one_of(st.sampled_from(URDF_VALUES), st.floats(allow_nan=True).map(repr), st.text(max_size=6),
                     plausible, plausible)
