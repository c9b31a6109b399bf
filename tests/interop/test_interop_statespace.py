"""state_space: the default model against python-control and scipy, and its blocks in closed form.

python-control's ``frequency_response`` and ``damp`` and scipy's ``freqresp`` on the
exported model must agree with pinlin's ``frequency_response`` and
``modal_analysis`` (to 1e-10).
"""

import json

import numpy as np
import pytest
from interop_cases import C1, CASES, K1, K2, L1, L2, M1, M2, G, P, double_pendulum
from numpy.testing import assert_allclose
from scipy import signal

import pinlin

control = pytest.importorskip("control")

#: Agreement demanded between pinlin and python-control / scipy (both compute the same matrices).
AGREEMENT = 1e-10
#: The first-order blocks are Cholesky solves with M, backward stable: a relative residual of a
#: few tens of eps at most.
SOLVE_RESIDUAL = 1e-14


def frequencies(sys):
    """A grid over the system's band, through (near) its resonances [rad/s]."""
    top = 2 * np.max(np.abs(pinlin.modal_analysis(sys).eigenvalues))
    return np.linspace(0.01, top, 41)


def scaled_close(actual, desired, rtol=AGREEMENT):
    """Equal to ``rtol`` relative to the largest entry (a response's zeros are only zero to rounding)."""
    assert_allclose(actual, desired, rtol=rtol, atol=rtol * np.abs(desired).max())


@pytest.mark.parametrize("case", sorted(CASES))
def test_frequency_response_of_control_model_equals_pinlin(case):
    _, sys = CASES[case]()
    omega = frequencies(sys)
    model = pinlin.state_space(sys)
    ctl = control.frequency_response(model.to_control(), omega)
    ref = pinlin.frequency_response(sys, omega)
    assert model.input_names == tuple(f"force:{n}" for n in sys.dof_names)
    assert model.output_names == sys.dof_names
    assert_allclose(ctl.omega, omega, rtol=0, atol=0)
    scaled_close(ctl.complex, ref.response)


@pytest.mark.parametrize("case", sorted(CASES))
def test_damp_of_control_model_equals_modal_analysis(case):
    _, sys = CASES[case]()
    modes = pinlin.modal_analysis(sys)
    wn, zeta, poles = control.damp(pinlin.state_space(sys).to_control(), doprint=False)
    lam = modes.eigenvalues
    order = [int(np.argmin(np.abs(poles - l))) for l in lam]
    assert sorted(order) == list(range(2 * sys.n))  # one pole per eigenvalue
    assert_allclose(poles[order], lam, rtol=AGREEMENT)
    assert_allclose(wn[order], modes.natural_frequency, rtol=AGREEMENT)
    assert_allclose(zeta[order], modes.damping_ratio, rtol=AGREEMENT, atol=AGREEMENT)


#: scipy's freqresp evaluates a state-space model through zeros, poles and gain (ss2tf, then roots):
#: fine for a few states, but on the 8-state chain, whose poles spread over 4-76 rad/s, the polynomial
#: coefficients lose about 1e-6 relative (measured 9.4e-7).  Cases and the agreement scipy can reach:
SCIPY_AGREEMENT = {
    "double_pendulum": AGREEMENT,
    "rotating_ring": AGREEMENT,
    "turntable": AGREEMENT,
    "random": AGREEMENT,
    "damped_chain": 1e-5,
}


@pytest.mark.filterwarnings("ignore::scipy.signal.BadCoefficients")  # scipy's own polynomial conversion
@pytest.mark.parametrize("case", sorted(SCIPY_AGREEMENT))
def test_scipy_freqresp_equals_pinlin(case):
    _, sys = CASES[case]()
    omega = frequencies(sys)
    ss = pinlin.state_space(sys).to_scipy()
    assert isinstance(ss, signal.StateSpace)
    ref = pinlin.frequency_response(sys, omega).response
    for i in range(sys.n):
        for j in range(sys.n):
            # scipy's freqresp is single-input single-output: one pair of the MIMO model at a time
            w, h = signal.freqresp((ss.A, ss.B[:, [j]], ss.C[[i]], ss.D[[i]][:, [j]]), omega)
            assert_allclose(w, omega, rtol=0, atol=0)
            scaled_close(h, ref[i, j], rtol=SCIPY_AGREEMENT[case])


@pytest.mark.parametrize("case", sorted(CASES))
def test_scipy_model_resolvent_equals_pinlin(case):
    """C (i omega I - A)^-1 B + D of the scipy model, evaluated directly, to 1e-10 in every case."""
    _, sys = CASES[case]()
    omega = frequencies(sys)
    ss = pinlin.state_space(sys).to_scipy()
    I = np.eye(ss.A.shape[0])
    h = np.stack([ss.C @ np.linalg.solve(1j * w * I - ss.A, ss.B) + ss.D for w in omega], axis=-1)
    scaled_close(h, pinlin.frequency_response(sys, omega).response)


def test_blocks_equal_closed_form_double_pendulum():
    """A = [[0, I], [-M^-1 K, -M^-1 C]] with theory: double pendulum's M, S, N (theta coordinates) and D = diag(C1, 0)."""
    _, sys = double_pendulum()
    T = np.array([[1.0, 0.0], [1.0, 1.0]])
    M = T.T @ np.array([[(M1 / 3 + M2) * L1**2, M2 * L1 * L2 / 2], [M2 * L1 * L2 / 2, M2 * L2**2 / 3]]) @ T
    S = (
        T.T
        @ np.array(
            [
                [K1 + K2 + (M1 / 2 + M2) * G * L1 - P * L1, -K2 + P * L1 / 2],
                [-K2 + P * L1 / 2, K2 + M2 * G * L2 / 2],
            ]
        )
        @ T
    )
    N = T.T @ (P * L1 / 2 * np.array([[0.0, 1.0], [-1.0, 0.0]])) @ T
    D = np.diag([C1, 0.0])
    model = pinlin.state_space(sys)
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Minv @ (S + N), -Minv @ D]])
    B = np.vstack([np.zeros((2, 2)), Minv])
    assert_allclose(model.A, A, rtol=1e-12, atol=1e-12 * np.abs(A).max())
    assert_allclose(model.B, B, rtol=1e-12, atol=1e-12 * np.abs(B).max())
    assert_allclose(model.C, np.hstack([np.eye(2), np.zeros((2, 2))]), rtol=0, atol=0)
    assert_allclose(model.D, np.zeros((2, 2)), rtol=0, atol=0)
    assert model.state_names == ("joint1", "joint2", "rate:joint1", "rate:joint2")


@pytest.mark.parametrize("case", sorted(CASES))
def test_error_is_backward_error_of_the_solves(case):
    _, sys = CASES[case]()
    model = pinlin.state_space(sys)
    n = sys.n
    X = -model.A[n:]  # [M^-1 K, M^-1 C]
    Y = np.hstack([sys.K, sys.C])
    residual = np.linalg.norm(sys.M @ X - Y) / (np.linalg.norm(sys.M) * np.linalg.norm(X) + np.linalg.norm(Y))
    assert residual <= SOLVE_RESIDUAL
    assert 0 <= model.error <= SOLVE_RESIDUAL
    assert_allclose(
        sys.M @ model.B[n:],
        np.eye(n),
        rtol=0,
        atol=SOLVE_RESIDUAL * np.linalg.norm(sys.M) * np.linalg.norm(model.B),
    )


def test_result_convention():
    _, sys = double_pendulum()
    model = pinlin.state_space(sys, outputs=["joint1", "rate:joint2"])
    assert isinstance(model, pinlin.StateSpaceModel)
    assert model.elapsed > 0 and isinstance(model.method, str) and "Cholesky" in model.method
    assert isinstance(model.error, float)
    text = repr(model)
    assert "StateSpaceModel(states=4" in text and "\n" not in text and len(text) < 300
    data = json.loads(json.dumps(model.to_dict()))
    assert data["type"] == "StateSpaceModel"
    assert data["output_names"] == ["joint1", "rate:joint2"]
    assert_allclose(np.array(data["A"]), model.A, rtol=0, atol=0)
    assert not model.A.flags.writeable and not model.B.flags.writeable
    assert pinlin.StateSpaceModel in pinlin.results.result_types()


def test_control_model_carries_names():
    _, sys = double_pendulum()
    ctl = pinlin.state_space(sys, outputs=["joint2", "rate:joint1"]).to_control(name="pendulum")
    assert ctl.name == "pendulum"
    assert ctl.input_labels == ["force:joint1", "force:joint2"]
    assert ctl.output_labels == ["joint2", "rate:joint1"]
    assert ctl.state_labels == ["joint1", "joint2", "rate:joint1", "rate:joint2"]
    assert ctl.find_input("force:joint2") == 1 and ctl.find_output("rate:joint1") == 1


def test_rates_are_i_omega_times_coordinates():
    """y = x' gives i omega H(i omega): the rate outputs against pinlin's coordinate response."""
    _, sys = double_pendulum()
    omega = np.linspace(0.5, 20.0, 17)
    model = pinlin.state_space(sys, inputs="joint2", outputs=["rate:joint1", "rate:joint2"])
    ctl = control.frequency_response(model.to_control(), omega).complex
    ref = pinlin.frequency_response(sys, omega, inputs="joint2").response
    scaled_close(ctl, 1j * omega * ref)


def test_selected_coordinates_keep_their_order():
    _, sys = CASES["damped_chain"]()
    omega = np.linspace(0.1, 50.0, 9)
    ins, outs = ["joint3", 0], [3, "joint2"]
    model = pinlin.state_space(sys, inputs=ins, outputs=outs)
    assert model.input_names == ("force:joint3", "force:joint1")
    assert model.output_names == ("joint4", "joint2")
    ctl = control.frequency_response(model.to_control(), omega).complex
    scaled_close(ctl, pinlin.frequency_response(sys, omega, inputs=ins, outputs=outs).response)


def test_bad_system_and_tolerance():
    _, sys = double_pendulum()
    with pytest.raises(pinlin.ParameterError, match="expected a pinlin.LinearizedSystem"):
        pinlin.state_space((sys.M, sys.C, sys.K))
    with pytest.raises(pinlin.ParameterError, match="periodic_tol"):
        pinlin.state_space(sys, periodic_tol=-1.0)
