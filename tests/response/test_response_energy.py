"""The linearized power theorem (theory: responses).

The trajectories come from the exact discretization (``forced_response``); the
budget integrates the powers with its own Hermite rule.  The balance
E(t) - E(0) - W(t) must close to 1e-8 relative on damped, gyroscopic and
circulatory systems, and must not close on a trajectory of another system.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from response_cases import double_pendulum, turntable


@pytest.fixture(scope="module")
def damped():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(4, length=1.0, mass=1.0))
    scene = pinlin.Scene(
        robot,
        [pinlin.JointSpring(f"joint{i}", 2.0) for i in range(1, 5)]
        + [pinlin.JointDamper("joint2", 0.05), pinlin.RayleighDamping(alpha=0.02, beta=0.005)],
    )
    return pinlin.linearize(scene, scene.neutral())


def _initial(n, seed):
    rng = np.random.default_rng(seed)
    return rng.standard_normal(n) * 0.1, rng.standard_normal(n) * 0.1


def test_damped_budget_balances(damped):
    sys = damped
    assert np.any(sys.D) and not np.any(sys.G) and not np.any(sys.N)
    x0, v0 = _initial(sys.n, 1)
    t = np.linspace(0.0, 10.0, 4001)  # h |lam|_max = 0.17
    resp = pinlin.forced_response(sys, t, None, x0, v0)
    budget = pinlin.energy_budget(sys, t, resp.x, resp.xdot)
    assert budget.balance_residual < 1e-8
    assert budget.quadrature_error < 1e-6
    # damping only removes energy
    assert np.all(np.diff(budget.work_damping) <= 1e-15 * budget.scale)
    assert budget.energy[-1] < 0.9 * budget.energy[0]
    assert_allclose(budget.work_circulatory, 0.0, rtol=0, atol=0)
    assert_allclose(budget.energy, budget.kinetic + budget.potential, rtol=1e-15, atol=0)


def test_gyroscopic_forces_do_no_work():
    scene, q = turntable()
    sys = pinlin.linearize(scene, q)
    assert np.any(sys.G) and not np.any(sys.D)
    x0, v0 = _initial(sys.n, 2)
    t = np.linspace(0.0, 10.0, 2001)
    resp = pinlin.forced_response(sys, t, None, x0, v0)
    budget = pinlin.energy_budget(sys, t, resp.x, resp.xdot)
    assert budget.balance_residual < 1e-8
    assert_allclose(budget.energy, budget.energy[0], rtol=1e-10, atol=0)
    assert np.max(np.abs(budget.power_gyroscopic)) < 1e-14 * budget.scale


def test_circulatory_budget_balances_with_nonzero_circulatory_work():
    scene = double_pendulum(P=4.0, damping=0.02)
    sys = pinlin.linearize(scene, scene.neutral())
    assert np.any(sys.N)
    x0, v0 = _initial(sys.n, 3)
    t = np.linspace(0.0, 8.0, 3201)
    resp = pinlin.forced_response(sys, t, None, x0, v0)
    budget = pinlin.energy_budget(sys, t, resp.x, resp.xdot)
    assert budget.balance_residual < 1e-8
    assert np.max(np.abs(budget.work_circulatory)) > 1e-2 * budget.energy[0]


def test_forced_budget_balances_with_work_of_the_force():
    scene, q = turntable()
    sys = pinlin.linearize(scene, q)
    b = np.array([0.3, 1.0])
    t = np.linspace(0.0, 6.0, 601)
    resp = pinlin.forced_response(sys, t, lambda tt: np.sin(2.0 * tt) * b, interpolation="cubic", substeps=2)
    budget = resp.energy()
    assert budget.balance_residual < 1e-8
    assert np.max(np.abs(budget.work_force)) > 0.5 * np.max(budget.energy)
    # the same budget from the samples returned at the output times, read as a cubic spline
    coarse = pinlin.energy_budget(sys, resp.t, resp.x, resp.xdot, resp.f, interpolation="cubic")
    assert coarse.balance_residual < 1e-9


def test_single_oscillator_energy_values():
    # m x'' + k x = 0, x = cos(w t): kinetic m w^2 sin^2 / 2, potential k cos^2 / 2.
    m, k = 2.0, 8.0
    w = np.sqrt(k / m)
    sys = pinlin.LinearizedSystem.from_matrices([[m]], None, [[k]])
    t = np.linspace(0.0, 3.0, 301)
    x, v = np.cos(w * t)[:, None], -w * np.sin(w * t)[:, None]
    budget = pinlin.energy_budget(sys, t, x, v)
    assert_allclose(budget.kinetic, m * w**2 * np.sin(w * t) ** 2 / 2, rtol=1e-14, atol=1e-14)
    assert_allclose(budget.potential, k * np.cos(w * t) ** 2 / 2, rtol=1e-14, atol=1e-14)
    assert budget.balance_residual < 1e-13


def test_trajectory_of_another_system_does_not_balance(damped):
    x0, v0 = _initial(damped.n, 4)
    t = np.linspace(0.0, 5.0, 1001)
    resp = pinlin.forced_response(damped, t, None, x0, v0)
    other = pinlin.LinearizedSystem.from_matrices(damped.M, damped.C, damped.K * 1.01)
    budget = pinlin.energy_budget(other, t, resp.x, resp.xdot)
    assert budget.balance_residual > 1e-4


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda s, t, x: pinlin.energy_budget(s, t, x[:, :1], x), r"x: expected shape \(5, 2\)"),
        (lambda s, t, x: pinlin.energy_budget(s, t, x, x[:4]), r"xdot: expected shape \(5, 2\)"),
        (lambda s, t, x: pinlin.energy_budget(s, t, x * np.nan, x), "must be finite"),
        (lambda s, t, x: pinlin.energy_budget(s, t[::-1], x, x), "strictly increasing"),
        (lambda s, t, x: pinlin.energy_budget(s, t, x, x, np.zeros(2)), r"f: expected shape \(5, 2\)"),
        (lambda s, t, x: pinlin.energy_budget(s, t, x, x, lambda tt: np.zeros(1)), r"shape \(2,\)"),
        (lambda s, t, x: pinlin.energy_budget(s, t, x, x, interpolation="quadratic"), "interpolation"),
        (lambda s, t, x: pinlin.energy_budget("sys", t, x, x), "LinearizedSystem"),
    ],
)
def test_bad_inputs_raise(call, match):
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    t = np.linspace(0.0, 1.0, 5)
    with pytest.raises(pinlin.ParameterError, match=match):
        call(sys, t, np.zeros((5, 2)))
