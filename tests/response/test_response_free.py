"""Free vibration from the modal solution (theory: responses).

References: ``scipy.linalg.expm`` of the first-order form built in the tests
(``response_cases.expm_free_response``), and closed forms for one degree of
freedom.  Acceptance: 1e-10 relative for simple roots, 1e-8 for defective roots
and rigid-body modes.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from response_cases import double_pendulum, expm_free_response, rotating_ring, turntable


def _simple_systems():
    dp = double_pendulum(P=4.0)
    dpd = double_pendulum(P=4.0, damping=0.1)
    tt, q = turntable()
    ring = rotating_ring()
    rng = np.random.default_rng(11)
    A = rng.standard_normal((4, 4))
    M = A @ A.T + 4 * np.eye(4)
    return {
        "double pendulum, follower (N)": pinlin.linearize(dp, dp.neutral()),
        "double pendulum, damped + N": pinlin.linearize(dpd, dpd.neutral()),
        "turntable (G)": pinlin.linearize(tt, q),
        "rotating ring (D + G)": pinlin.linearize(ring, ring.neutral()),
        "random nonsymmetric": pinlin.LinearizedSystem.from_matrices(
            M, rng.standard_normal((4, 4)), rng.standard_normal((4, 4)) + 5 * np.eye(4)
        ),
    }


def _defective_systems():
    chain = pinlin.Scene(
        pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3)),
        [pinlin.JointSpring("joint2", 1.0), pinlin.JointSpring("joint3", 2.0)],
        gravity=(0, 0, 0),
    )
    return {
        # K a Jordan block: double roots -0.1 +- 1.4107i, each with one chain of length 2
        "Jordan stiffness": pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.2 * np.eye(2), [[2.0, 1.0], [0.0, 2.0]]),
        # two masses joined by a spring, no ground: lam = 0 with a chain of length 2
        "two free masses": pinlin.LinearizedSystem.from_matrices(np.diag([1.0, 3.0]), None, [[2.0, -2.0], [-2.0, 2.0]]),
        # a chain with no spring at its root and no gravity: a rigid-body rotation
        "chain, free root joint": pinlin.linearize(chain, chain.neutral()),
        # critical damping: lam = -1 double
        "critically damped": pinlin.LinearizedSystem.from_matrices([[1.0]], [[2.0]], [[1.0]]),
        # no stiffness at all: lam = 0 double for every coordinate
        "no stiffness": pinlin.LinearizedSystem.from_matrices(np.diag([1.0, 2.0]), None, None),
    }


SIMPLE = _simple_systems()
DEFECTIVE = _defective_systems()


def _compare(sys, seed, t, rtol):
    rng = np.random.default_rng(seed)
    x0, v0 = rng.standard_normal((2, sys.n))
    x = pinlin.free_response(sys, t, x0, v0)
    x_ref, v_ref = expm_free_response(sys, x0, v0, t)
    assert isinstance(x, np.ndarray) and x.shape == (len(t), sys.n) and x.dtype == float
    assert_allclose(x, x_ref, rtol=0, atol=rtol * np.abs(x_ref).max())
    assert_allclose(x.xdot, v_ref, rtol=0, atol=rtol * np.abs(v_ref).max())
    return x


@pytest.mark.parametrize("name", sorted(SIMPLE))
def test_simple_roots_match_expm(name):
    sys = SIMPLE[name]
    x = _compare(sys, 1, np.linspace(0.0, 6.0, 121), 1e-10)
    assert x.method == "modal"
    assert x.modes.is_simple
    assert x.defect < 1e-12 and x.initial_defect < 1e-12 and x.symmetry_defect < 1e-12
    assert x.elapsed > 0


@pytest.mark.parametrize("name", sorted(DEFECTIVE))
def test_defective_roots_and_rigid_body_modes_match_expm(name):
    sys = DEFECTIVE[name]
    x = _compare(sys, 2, np.linspace(0.0, 6.0, 121), 1e-8)
    assert x.method == "modal + Jordan chains"
    assert not x.modes.is_simple
    assert x.defect < 1e-10 and x.initial_defect < 1e-10 and x.projection_residual < 1e-10


def test_rigid_body_drift_is_linear_in_time():
    # Two free masses: the centre of mass moves at constant speed (the t x_0 term of the chain).
    sys = DEFECTIVE["two free masses"]
    t = np.linspace(0.0, 10.0, 11)
    x = pinlin.free_response(sys, t, [0.0, 0.0], [1.0, 1.0])
    assert_allclose(x, np.column_stack([t, t]), rtol=0, atol=1e-12)


def test_single_oscillator_closed_form():
    # m x'' + c x' + k x = 0: x = e^{-z w t} (x0 cos wd t + (v0 + z w x0) / wd sin wd t).
    m, c, k = 2.0, 0.6, 8.0
    w = np.sqrt(k / m)
    z = c / (2 * np.sqrt(k * m))
    wd = w * np.sqrt(1 - z**2)
    x0, v0 = 0.3, -1.1
    t = np.linspace(0.0, 8.0, 201)
    x = pinlin.free_response(pinlin.LinearizedSystem.from_matrices([[m]], [[c]], [[k]]), t, [x0], [v0])
    exact = np.exp(-z * w * t) * (x0 * np.cos(wd * t) + (v0 + z * w * x0) / wd * np.sin(wd * t))
    assert_allclose(x[:, 0], exact, rtol=0, atol=1e-14)


def test_initial_time_shift_and_backward_times():
    sys = SIMPLE["turntable (G)"]
    x0, v0 = np.array([0.1, 0.0]), np.array([0.0, 0.3])
    t = np.linspace(-1.0, 2.0, 31)
    shifted = pinlin.free_response(sys, t, x0, v0, t0=-1.0)
    plain = pinlin.free_response(sys, t + 1.0, x0, v0)
    assert_allclose(shifted, plain, rtol=0, atol=1e-14)
    x_ref, _ = expm_free_response(sys, x0, v0, t)  # negative times: expm(A t) backward
    assert_allclose(pinlin.free_response(sys, t, x0, v0), x_ref, rtol=0, atol=1e-12)


def test_reusing_modes_and_array_behaviour():
    sys = SIMPLE["double pendulum, damped + N"]
    modes = pinlin.modal_analysis(sys)
    t = np.linspace(0.0, 1.0, 11)
    a = pinlin.free_response(sys, t, [0.1, 0.2])
    b = pinlin.free_response(sys, t, [0.1, 0.2], modes=modes)
    assert b.modes is modes
    assert_allclose(b, a, rtol=0, atol=0)
    assert repr(a).startswith("FreeResponse(shape=(11, 2)")
    part = a[:, 0]
    assert type(part) is np.ndarray and part.shape == (11,)
    assert type(2 * a) is np.ndarray and isinstance(a.max(), float)
    with pytest.raises(AttributeError, match="whole result"):
        _ = a.view(type(a)).reshape(22).defect
    with pytest.raises(ValueError, match="read-only"):
        a[0, 0] = 1.0
    other = pinlin.LinearizedSystem.from_matrices(sys.M, sys.C, 2 * sys.K)
    with pytest.raises(pinlin.ParameterError, match="another system"):
        pinlin.free_response(other, t, [0.1, 0.2], modes=modes)


@pytest.mark.parametrize(
    ("args", "kwargs", "match"),
    [
        (([0.0, 1.0], [1.0], None), {}, r"x0: expected shape \(2,\)"),
        (([0.0, 1.0], [1.0, np.nan], None), {}, "x0: must be finite"),
        (([0.0, 1.0], [1.0, 0.0], [0.0, 0.0, 0.0]), {}, r"v0: expected shape \(2,\)"),
        (([0.0, 1.0, 0.5], [1.0, 0.0], None), {}, "strictly increasing"),
        (([[0.0, 1.0]], [1.0, 0.0], None), {}, "1-D"),
        (([0.0, np.inf], [1.0, 0.0], None), {}, "finite"),
        ((None, [1.0, 0.0], None), {}, "required"),
        (([0.0, 1.0], [1.0, 0.0], None), {"t0": np.nan}, "t0"),
        (([0.0, 1.0], [1.0, 0.0], None), {"rtol": -1.0}, "rtol"),
        (([0.0, 1.0], ["a", 0.0], None), {}, "x0"),
    ],
)
def test_bad_inputs_raise(args, kwargs, match):
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.free_response(sys, *args, **kwargs)


def test_not_a_system_raises():
    with pytest.raises(pinlin.ParameterError, match="LinearizedSystem"):
        pinlin.free_response(np.eye(2), [0.0, 1.0], [1.0, 0.0])


def test_long_response_across_evaluation_blocks_matches_exact_discretization():
    # More time points than one evaluation block (TIME_CHUNK): compared with forced_response's
    # exact discretization (matrix exponential of the step), a different method.
    from pinlin.response.free import TIME_CHUNK

    sys = DEFECTIVE["Jordan stiffness"]
    t = np.linspace(0.0, 40.0, TIME_CHUNK + 905)
    x = pinlin.free_response(sys, t, [1.0, 0.0], [0.0, 1.0])
    ref = pinlin.forced_response(sys, t, None, [1.0, 0.0], [0.0, 1.0])
    assert_allclose(x, ref.x, rtol=0, atol=1e-12 * np.abs(ref.x).max())
    assert_allclose(x.xdot, ref.xdot, rtol=0, atol=1e-12 * np.abs(ref.xdot).max())


def test_figures_above_tol_warn():
    sys = SIMPLE["turntable (G)"]
    with pytest.warns(pinlin.AccuracyWarning, match="defect"):
        x = pinlin.free_response(sys, [0.0, 1.0], [0.1, 0.0], rtol=1e-300)
    assert x.defect > 1e-300
