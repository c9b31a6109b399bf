"""python-control as an optional dependency, and FrequencyResponse as its FrequencyResponseData."""

import sys as python_sys

import numpy as np
import pytest
from interop_cases import double_pendulum, rotating_ring
from numpy.testing import assert_allclose

import pinlin
from pinlin.interop import frequency_response_data

control = pytest.importorskip("control")

#: Agreement demanded between pinlin and python-control (both compute the same matrices).
AGREEMENT = 1e-10


def test_frequency_response_data_carries_values_and_names():
    _, sys = double_pendulum()
    omega = np.linspace(0.0, 20.0, 25)
    resp = pinlin.frequency_response(sys, omega, inputs="joint2")
    frd = frequency_response_data(resp, name="pendulum")
    assert isinstance(frd, control.FrequencyResponseData)
    assert frd.name == "pendulum"
    assert frd.input_labels == ["force:joint2"] and frd.output_labels == ["joint1", "joint2"]
    assert_allclose(frd.omega, omega, rtol=0, atol=0)
    assert_allclose(frd.frdata, resp.response, rtol=0, atol=0)


def test_frequency_response_data_equals_state_space_model():
    """The data and the state-space model of one system agree, signal by signal (same names)."""
    _, sys = rotating_ring()
    omega = np.linspace(0.05, 8.0, 33)
    frd = frequency_response_data(pinlin.frequency_response(sys, omega))
    ctl = control.frequency_response(pinlin.state_space(sys).to_control(), omega)
    assert frd.input_labels == ctl.input_labels and frd.output_labels == ctl.output_labels
    assert_allclose(frd.frdata, ctl.complex, rtol=AGREEMENT, atol=AGREEMENT * np.abs(ctl.complex).max())


def test_bad_responses():
    _, sys = double_pendulum()
    with pytest.raises(
        pinlin.ParameterError, match="resp.omega: python-control needs frequencies >= 0 in increasing order"
    ):
        frequency_response_data(pinlin.frequency_response(sys, [-1.0, 1.0]))
    with pytest.raises(pinlin.ParameterError, match="increasing order"):
        frequency_response_data(pinlin.frequency_response(sys, [2.0, 1.0]))
    with pytest.raises(pinlin.ParameterError, match="expected a pinlin.FrequencyResponse, got ndarray"):
        frequency_response_data(np.zeros((2, 2, 3)))


def test_missing_python_control(monkeypatch):
    """Without python-control, asking for it names the extra; the rest of interop works."""
    _, sys = double_pendulum()
    monkeypatch.setitem(python_sys.modules, "control", None)  # makes `import control` fail
    model = pinlin.state_space(sys)
    assert model.to_scipy().A.shape == (4, 4)
    with pytest.raises(pinlin.errors.MissingDependencyError, match=r"pip install 'pinlin\[control\]'"):
        model.to_control()
    with pytest.raises(ImportError, match="python-control"):
        frequency_response_data(pinlin.frequency_response(sys, [1.0, 2.0]))


@pytest.mark.skipif(
    not hasattr(pinlin.FrequencyResponse, "to_control"),
    reason="FrequencyResponse.to_control not attached yet",
)
def test_frequency_response_to_control_is_the_export():
    _, sys = double_pendulum()
    resp = pinlin.frequency_response(sys, np.linspace(0.5, 9.0, 7))
    frd = resp.to_control()
    assert isinstance(frd, control.FrequencyResponseData)
    assert frd.input_labels == ["force:joint1", "force:joint2"]
    assert_allclose(frd.frdata, resp.response, rtol=0, atol=0)
