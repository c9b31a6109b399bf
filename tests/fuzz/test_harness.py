"""The fuzzing harness itself: it interrupts hangs, catches lies, and writes the TOML it means."""

from __future__ import annotations

import math
import sys
import time

import numpy as np
import pytest
from fuzz_strategies import ExampleTimeout, check_result, hard_deadline, outcome, toml_dumps
from hypothesis import given
from hypothesis import strategies as st

import pinlin

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def test_hard_deadline_interrupts_a_hang():
    t0 = time.perf_counter()
    with pytest.raises(ExampleTimeout, match="longer than 0.2 s"), hard_deadline(0.2):
        time.sleep(5)
    assert time.perf_counter() - t0 < 2
    with hard_deadline(5):  # and is cancelled when the block ends in time
        pass
    time.sleep(0.01)


def test_outcome_accepts_pinlin_errors_and_passes_others_on():
    assert outcome(lambda: pinlin.modal_analysis("not a system"), "modal_analysis") is None
    with pytest.raises(ZeroDivisionError):
        outcome(lambda: 1 / 0, "division")


def test_check_result_catches_a_lie():
    sys_ = pinlin.LinearizedSystem.from_matrices(np.eye(2), np.zeros((2, 2)), np.eye(2))
    resp = pinlin.free_response(sys_, [1.0, 0.0], [0.0, 0.0], [0.0, 1.0])
    check_result(resp, "free_response")  # an honest result passes
    lie = type(resp)(np.full((2, 2), np.nan), **{**resp._meta, "error": 0.0})
    with pytest.raises(AssertionError, match="NaN in the values of a result with finite error 0.0"):
        check_result(lie, "lie")
    unknown = type(resp)(np.asarray(resp), **{**resp._meta, "error": math.nan})
    with pytest.raises(AssertionError, match="headline error nan is not finite"):
        check_result(unknown, "unknown")


VALUES = st.recursive(
    st.one_of(st.integers(-(2**63), 2**63 - 1), st.floats(allow_nan=False), st.text(), st.booleans()),
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.dictionaries(st.text(min_size=1), inner, max_size=3)),
    max_leaves=6,
)


@given(doc=st.dictionaries(st.text(min_size=1), st.one_of(
    VALUES, st.dictionaries(st.text(min_size=1), VALUES, max_size=3),
    st.lists(st.dictionaries(st.text(min_size=1), VALUES, min_size=1, max_size=2), min_size=1, max_size=2)),
    max_size=4))
def test_toml_writer_round_trips(doc):
    assert tomllib.loads(toml_dumps(doc)) == doc
