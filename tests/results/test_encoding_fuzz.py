"""The encoding of ``to_dict`` is reversible for any array, scalar and container (hypothesis).

Arrays of every dtype results hold (bool, int8 ... int64, uint8, float32, float64, complex64,
complex128), any shape of up to three axes (empty ones and 0-d included), with NaN, +-inf and -0;
tuples, lists and dicts of them.  ``decode(json(encode(v)))`` equals v: dtype, shape and bytes
(NaNs as NaN: JSON's "nan" keeps no sign or payload).
"""

from __future__ import annotations

import json

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from test_results_roundtrip import assert_same

from pinlin.results import decode, encode

DTYPES = ["bool", "int8", "int32", "int64", "uint8", "float32", "float64", "complex64", "complex128"]

arrays = st.sampled_from(DTYPES).flatmap(
    lambda dtype: hnp.arrays(np.dtype(dtype), hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=3))
)
scalars = st.one_of(st.booleans(), st.integers(-(2**62), 2**62), st.floats(allow_nan=True, allow_infinity=True),
                    st.complex_numbers(allow_nan=True, allow_infinity=True), st.none(), st.text(max_size=5))
values = st.recursive(
    st.one_of(arrays, scalars),
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.lists(inner, max_size=3).map(tuple),
                            st.dictionaries(st.text(max_size=4), inner, max_size=3)),
    max_leaves=6,
)


@given(values)
def test_decode_inverts_encode_through_json(value):
    data, spec = encode(value)
    data, spec = json.loads(json.dumps([data, spec], allow_nan=False))
    assert_same(value, decode(data, spec))
