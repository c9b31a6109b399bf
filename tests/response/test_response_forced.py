"""Forced response by exact discretization against solve_ivp and closed forms."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

import pinlin
from response_cases import double_pendulum, expm_free_response, state_matrix, turntable


def _reference(sys, force, t, x0, v0, rtol=1e-12, atol=1e-14):
    """A tightly toleranced solve_ivp of z' = A z + [0; M^-1 f(t)] (A built in the tests)."""
    A = state_matrix(sys)
    Minv = np.linalg.inv(sys.M)
    n = sys.n

    def rhs(tt, z):
        dz = A @ z
        dz[n:] += Minv @ force(tt)
        return dz

    sol = solve_ivp(rhs, (t[0], t[-1]), np.concatenate([x0, v0]), t_eval=t, rtol=rtol, atol=atol, method="DOP853")
    return sol.y[:n].T, sol.y[n:].T


@pytest.fixture(scope="module")
def circulatory():
    scene = double_pendulum(P=4.0, damping=0.05)
    return pinlin.linearize(scene, scene.neutral())


def test_ramp_matches_solve_ivp(circulatory):
    sys = circulatory
    rng = np.random.default_rng(3)
    b, x0, v0 = rng.standard_normal((3, sys.n))
    t = np.linspace(0.0, 4.0, 81)
    resp = pinlin.forced_response(sys, t, t[:, None] * b, x0, v0)
    x_ref, v_ref = _reference(sys, lambda tt: tt * b, t, x0, v0)
    scale = np.abs(x_ref).max()
    assert_allclose(resp.x, x_ref, rtol=0, atol=1e-10 * scale)
    assert_allclose(resp.xdot, v_ref, rtol=0, atol=1e-10 * np.abs(v_ref).max())
    assert resp.x.shape == (81, sys.n)
    assert resp.exponential_defect < 1e-13 and resp.input_error is None and resp.elapsed > 0


def test_ramp_on_a_random_grid_is_exact(circulatory):
    # Non-uniform steps: one block exponential per step, still no step error.
    sys = circulatory
    rng = np.random.default_rng(4)
    t = np.concatenate([[0.0], np.cumsum(rng.uniform(0.01, 0.3, 30))])
    b = rng.standard_normal(sys.n)
    resp = pinlin.forced_response(sys, t, (2.0 - t[:, None]) * b)
    x_ref, _ = _reference(sys, lambda tt: (2.0 - tt) * b, t, np.zeros(sys.n), np.zeros(sys.n))
    assert resp.distinct_steps == 30
    assert_allclose(resp.x, x_ref, rtol=0, atol=1e-10 * np.abs(x_ref).max())


def test_harmonic_input_matches_solve_ivp(circulatory):
    sys = circulatory
    b = np.array([0.0, 1.0])
    omega = 3.0
    t = np.linspace(0.0, 5.0, 201)

    def force(tt):
        return np.cos(omega * tt) * b

    x_ref, _ = _reference(sys, force, t, np.zeros(2), np.zeros(2))
    cubic = pinlin.forced_response(sys, t, force, interpolation="cubic", substeps=4)
    assert cubic.input_error < 1e-8
    assert_allclose(cubic.x, x_ref, rtol=0, atol=1e-9 * np.abs(x_ref).max())
    linear = pinlin.forced_response(sys, t, force, substeps=10)
    # a first-order hold is exact for its own input; the input itself is off by O((omega h)^2 / 8)
    assert 1e-7 < linear.input_error < 1e-5
    assert_allclose(linear.x, x_ref, rtol=0, atol=10 * linear.input_error * np.abs(x_ref).max())


def test_free_case_matches_expm_on_gyroscopic_system():
    scene, q = turntable()
    sys = pinlin.linearize(scene, q)
    t = np.linspace(0.0, 3.0, 31)
    resp = pinlin.forced_response(sys, t, None, [0.1, -0.05], [0.0, 0.2])
    x_ref, v_ref = expm_free_response(sys, np.array([0.1, -0.05]), np.array([0.0, 0.2]), t)
    assert_allclose(resp.x, x_ref, rtol=0, atol=1e-12)
    assert_allclose(resp.xdot, v_ref, rtol=0, atol=1e-12)


def test_stiff_ramp_with_large_steps_matches_closed_form():
    # Uncoupled oscillators x'' + 2 z w x' + w^2 x = b t, w from 1 to 1e4 rad/s, step 0.1 s (w h up to 1e3).
    # Particular solution x_p = b t / w^2 - 2 z b / w^3; the homogeneous part starts at -x_p(0), -x_p'(0).
    w = np.array([1.0, 1e2, 1e4])
    z = np.array([0.05, 0.3, 0.02])
    b = np.array([1.0, 2.0, 3.0])
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(3), np.diag(2 * z * w), np.diag(w**2))
    t = np.linspace(0.0, 3.0, 31)
    resp = pinlin.forced_response(sys, t, t[:, None] * b)
    wd = w * np.sqrt(1 - z**2)
    xp0, vp0 = -2 * z * b / w**3, b / w**2
    A0, B0 = -xp0, (-vp0 + z * w * (-xp0)) / wd
    tt = t[:, None]
    x_exact = b * tt / w**2 - 2 * z * b / w**3 + np.exp(-z * w * tt) * (A0 * np.cos(wd * tt) + B0 * np.sin(wd * tt))
    assert_allclose(resp.x, x_exact, rtol=1e-10, atol=1e-16)


def test_defective_system_matches_solve_ivp():
    # K a Jordan block: the double roots of lam^2 + 0.2 lam + 2 = 0 carry chains of length 2.
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.2 * np.eye(2), [[2.0, 1.0], [0.0, 2.0]])
    t = np.linspace(0.0, 6.0, 61)
    b = np.array([0.0, 1.0])
    resp = pinlin.forced_response(sys, t, lambda tt: np.sin(1.4 * tt) * b, [1.0, 0.0], interpolation="cubic", substeps=10)
    x_ref, _ = _reference(sys, lambda tt: np.sin(1.4 * tt) * b, t, np.array([1.0, 0.0]), np.zeros(2))
    assert_allclose(resp.x, x_ref, rtol=0, atol=1e-9 * np.abs(x_ref).max())


def test_coarse_callable_warns():
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(1), [[0.1]], [[1.0]])
    with pytest.warns(pinlin.AccuracyWarning, match="increase substeps"):
        resp = pinlin.forced_response(sys, np.linspace(0, 2, 11), lambda tt: np.array([np.cos(5 * tt)]))
    assert resp.input_error > 1e-4


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda s, t: pinlin.forced_response(s, t, np.zeros((len(t), 3))), r"expected shape \(11, 2\)"),
        (lambda s, t: pinlin.forced_response(s, t, np.full((len(t), 2), np.nan)), "must be finite"),
        (lambda s, t: pinlin.forced_response(s, t, lambda tt: np.zeros(3)), r"must return shape \(2,\)"),
        (lambda s, t: pinlin.forced_response(s, t, lambda tt: np.array([np.nan, 0.0])), "not finite"),
        (lambda s, t: pinlin.forced_response(s, t[::-1]), "strictly increasing"),
        (lambda s, t: pinlin.forced_response(s, [0.0, np.inf]), "finite"),
        (lambda s, t: pinlin.forced_response(s, t, None, [1.0]), r"x0: expected shape \(2,\)"),
        (lambda s, t: pinlin.forced_response(s, t, None, None, [np.nan, 0.0]), "v0: must be finite"),
        (lambda s, t: pinlin.forced_response(s, t, np.zeros((len(t), 2)), substeps=2), "callable force only"),
        (lambda s, t: pinlin.forced_response(s, t, substeps=0), "substeps"),
        (lambda s, t: pinlin.forced_response(s, t, interpolation="spline"), "interpolation"),
        (lambda s, t: pinlin.forced_response(s, t[:3], interpolation="cubic"), "at least 4"),
        (lambda s, t: pinlin.forced_response(s, t, input_tol=0.0), "input_tol"),
        (lambda s, t: pinlin.forced_response(s.M, t), "LinearizedSystem"),
    ],
)
def test_bad_inputs_raise(call, match):
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    with pytest.raises(pinlin.ParameterError, match=match):
        call(sys, np.linspace(0.0, 1.0, 11))
