"""``to_pandas()`` of modes, sweeps and frequency responses, against closed forms.

- Modes of M = I, C = 0, K = diag(4, 9): lam = +-2i, +-3i, so one row per eigenvalue with
  natural frequency 2, 2, 3, 3 rad/s, 1/pi, 1/pi, 1.5/pi Hz, damping ratio 0, kind "undamped" (D = 0: decided on the axis).
- The frequency response of one oscillator m = 2, c = 0.4, k = 8: H(i w) = 1 / (k - m w^2 + i c w)
  in long format (one row per frequency, output, input).
- A sweep: one row per point, its parameters, value, error, elapsed and failure.
- Without pandas: MissingDependencyError naming the extra.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.extras import import_pandas
from pinlin.spectral.tables import MODE_COLUMNS, mode_records

pd = pytest.importorskip("pandas")


def test_modes_to_pandas_one_row_per_eigenvalue():
    modes = pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices(np.eye(2), np.zeros((2, 2)), np.diag([4.0, 9.0]),
                                                                        dof_names=("a", "b")))
    frame = modes.to_pandas()
    assert list(frame.columns) == list(MODE_COLUMNS) and frame.index.name == "k" and len(frame) == 4
    assert_allclose(frame["eigenvalue_re"], 0.0, atol=0)
    assert_allclose(frame["eigenvalue_im"], [2.0, -2.0, 3.0, -3.0], rtol=1e-14)
    assert_allclose(frame["natural_frequency"], [2.0, 2.0, 3.0, 3.0], rtol=1e-14)
    assert_allclose(frame["frequency_hz"], np.array([2.0, 2.0, 3.0, 3.0]) / (2 * np.pi), rtol=1e-14)
    assert_allclose(frame["damping_ratio"], 0.0, atol=0)
    assert not np.signbit(frame["damping_ratio"]).any() and not np.signbit(frame["eigenvalue_re"]).any()  # no -0
    assert list(frame["kind"]) == ["undamped"] * 4
    assert list(frame["dominant"]) == ["a 100%", "a 100%", "b 100%", "b 100%"]
    assert_allclose(frame["backward_error"], modes.backward_error, rtol=0)
    assert_allclose(frame["condition"], modes.condition, rtol=0)
    assert_allclose(frame["error_bound"], modes.error_bound, rtol=0)
    assert list(frame["multiplicity"]) == [1, 1, 1, 1]
    assert mode_records(modes)[2]["natural_frequency"] == 3.0


def test_frequency_response_to_pandas_long_format():
    m, c, k = 2.0, 0.4, 8.0
    sys1 = pinlin.LinearizedSystem.from_matrices([[m]], [[c]], [[k]], dof_names=("x",))
    omega = np.array([0.5, 1.0, 3.0])
    frame = pinlin.frequency_response(sys1, omega).to_pandas()
    assert list(frame.columns) == ["omega", "frequency_hz", "output", "input", "magnitude", "phase", "re", "im"]
    H = 1.0 / (k - m * omega**2 + 1j * c * omega)
    assert_allclose(frame["omega"], omega, rtol=0)
    assert_allclose(frame["frequency_hz"], omega / (2 * np.pi), rtol=1e-15)
    assert_allclose(frame["re"] + 1j * frame["im"], H, rtol=1e-13)
    assert_allclose(frame["magnitude"], np.abs(H), rtol=1e-13)
    assert_allclose(frame["phase"], np.angle(H), rtol=1e-13)
    assert list(frame["output"]) == ["x"] * 3 and list(frame["input"]) == ["x"] * 3


def test_frequency_response_rows_run_frequency_then_output_then_input():
    sys2 = pinlin.LinearizedSystem.from_matrices(np.diag([2.0, 1.0]), 0.1 * np.eye(2), [[6.0, -2.0], [-2.0, 3.0]])
    resp = pinlin.frequency_response(sys2, np.array([0.5, 1.5]))
    frame = resp.to_pandas()
    assert len(frame) == 2 * 2 * 2
    for row in frame.itertuples():
        w, o, i = list(resp.omega).index(row.omega), resp.output_names.index(row.output), resp.input_names.index(row.input)
        assert row.re + 1j * row.im == resp.response[o, i, w]
    assert list(frame["output"][:4]) == ["x1", "x1", "x2", "x2"] and list(frame["input"][:4]) == ["x1", "x2"] * 2


def refuse_negative(P: float):
    if P < 0:
        raise pinlin.ParameterError("P", "must be >= 0")
    return pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.0]], [[P + 1.0]]))


def test_sweep_to_pandas_one_row_per_point():
    result = pinlin.sweep(refuse_negative, {"P": [0.0, 3.0, -1.0]}, on_error="record")
    frame = result.to_pandas(extract=lambda modes: modes.natural_frequency[0])
    assert list(frame.columns) == ["P", "value", "error", "elapsed", "failure"]
    assert list(frame["P"]) == [0.0, 3.0, -1.0]
    assert_allclose(frame["value"][:2].astype(float), [1.0, 2.0], rtol=1e-14)
    assert pd.isna(frame["value"][2])  # a failed point has no value (None, NaN in a float column)
    assert frame["failure"][:2].isna().all()
    assert frame["failure"][2] == f"ParameterError: {result.values[2].exception}" and "must be >= 0" in frame["failure"][2]
    assert np.isnan(frame["error"][2]) and frame["error"][0] == result.point_errors[0]
    assert_allclose(frame["elapsed"], result.point_elapsed, rtol=0)
    assert isinstance(result.to_pandas()["value"][0], pinlin.Modes)


def test_missing_pandas_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas now raises ImportError
    with pytest.raises(pinlin.MissingDependencyError, match=r"needs pandas .*pip install 'pinlin\[pandas\]'"):
        import_pandas()
    modes = pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.0]], [[1.0]]))
    with pytest.raises(pinlin.MissingDependencyError, match=r"pinlin\[pandas\]"):
        modes.to_pandas()


def test_floquet_to_pandas_one_row_per_multiplier():
    """A time-invariant oscillator x'' + 4 x = 0 over T = 1: mu = exp(+-2i), frequency +-2 rad/s (harmonic 0)."""
    flo = pinlin.floquet_analysis_matrices(np.eye(1), None, 4.0 * np.eye(1), 1.0)
    frame = flo.to_pandas()
    assert list(frame.columns) == ["mu_re", "mu_im", "abs_mu", "error_bound", "exponent_re", "frequency",
                                   "frequency_hz", "harmonic", "share", "trivial"]
    assert len(frame) == 2
    order = np.argsort(frame["frequency"].to_numpy())
    assert_allclose(frame["frequency"].to_numpy()[order], [-2.0, 2.0], rtol=1e-10)
    assert_allclose(frame["frequency_hz"].to_numpy()[order], [-1 / np.pi, 1 / np.pi], rtol=1e-10)
    assert_allclose(frame["mu_re"], np.cos(2.0), rtol=1e-10)
    assert_allclose(frame["abs_mu"], 1.0, rtol=1e-12)
    assert list(frame["harmonic"]) == [0, 0] and not frame["trivial"].any()
    assert (frame["share"] > 0.99).all()
