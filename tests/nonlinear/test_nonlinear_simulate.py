"""The nonlinear reference simulation against hand-derived equations and first integrals.

Each test checks :func:`pinlin.simulate` against something it does not compute
itself: a hand-written equation of motion integrated by scipy, the Jacobi
integral of a particle on a turntable, the conserved energy and momentum of a
torque-free rigid body (free-flyer, nq != nv, several charts), and the same
chain modelled with continuous (SO(2)) and with revolute joints.
"""

from __future__ import annotations

import json

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

import pinlin
from helpers import BOX_URDF, mp_log6, mp_log6_jacobian
from pinlin.model.elements import Element
from response_cases import TURNTABLE, expm_free_response, rotating_ring, turntable


def test_single_pendulum_matches_hand_equation():
    # Uniform slender bar (m, l) about +y, hanging along -z; tip at (-l sin th, 0, -l cos th):
    # (m l^2 / 3) th'' = -k (th - th_r) - (c + alpha m l^2/3 + beta k) th' - m g l/2 sin th
    #                    + Fx (-l cos th) + Fz (l sin th) + tau
    m, l, g = 1.2, 0.8, 9.81
    k, th_r, c, alpha, beta = 2.0, 0.2, 0.05, 0.1, 0.01
    Fx, Fz, tau = 0.5, -1.0, 0.3
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1, length=l, mass=m))
    scene = pinlin.Scene(
        robot,
        [
            pinlin.JointSpring("joint1", k, rest=th_r),
            pinlin.JointDamper("joint1", c),
            pinlin.RayleighDamping(alpha=alpha, beta=beta),
            pinlin.DeadWrench("tip", force=(Fx, 0, Fz)),
            pinlin.FollowerWrench("tip", torque=(0, tau, 0)),
        ],
        gravity=(0, 0, -g),
    )
    inertia = m * l**2 / 3

    def rhs(t, y):
        th, om = y
        damping = c + alpha * inertia + beta * k
        torque = -k * (th - th_r) - damping * om - m * g * l / 2 * np.sin(th) + Fx * (-l * np.cos(th)) + Fz * l * np.sin(th) + tau
        return [om, torque / inertia]

    t = np.linspace(0.0, 3.0, 31)
    sim = pinlin.simulate(scene, [1.0], [-0.5], t)
    ref = solve_ivp(rhs, (0.0, 3.0), [1.0, -0.5], t_eval=t, rtol=1e-12, atol=1e-13, method="DOP853")
    assert_allclose(sim.q[:, 0], ref.y[0], rtol=0, atol=1e-8)
    assert_allclose(sim.v[:, 0], ref.y[1], rtol=0, atol=1e-8)
    assert sim.shape == (31, 1) and sim.v.shape == (31, 1)  # the result is the (len(t), nq) array
    assert type(sim.q) is np.ndarray and np.array_equal(sim.q, np.asarray(sim))
    assert sim.nfev > 0 and sim.elapsed > 0 and sim.charts == 1
    assert repr(sim).startswith("Simulation(shape=(31, 1)") and "\n" not in repr(sim) and len(repr(sim)) < 200


def test_turntable_conserves_jacobi_integral():
    # In the frame of a table turning at constant W, the particle's Jacobi integral
    # J = m/2 (r'^2 + r^2 th'^2) - m W^2/2 |rho|^2 + k/2 (r - l0)^2, rho = (a + r cos th, r sin th),
    # is conserved; it checks the prescribed-velocity path (rnea with the table spinning).
    scene, q_eq = turntable()
    p = TURNTABLE
    m, k, W, a, l0 = p["m"], p["k"], p["Omega"], p["a"], p["l0"]
    q0 = q_eq.copy()
    q0[scene.robot.joint("arm").idx_q] = 0.7
    q0[scene.robot.joint("slider").idx_q] += 0.2
    t = np.linspace(0.0, 4.0, 41)
    sim = pinlin.simulate(scene, q0, [0.3, -0.4], t)
    th = sim.q[:, scene.robot.joint("arm").idx_q]
    r = sim.q[:, scene.robot.joint("slider").idx_q]
    thd, rd = sim.v[:, scene.free_dofs].T
    J = m / 2 * (rd**2 + r**2 * thd**2) - m * W**2 / 2 * ((a + r * np.cos(th)) ** 2 + (r * np.sin(th)) ** 2) + k / 2 * (r - l0) ** 2
    assert np.ptp(th) > 0.5  # a large motion, not a linear one
    assert_allclose(J, J[0], rtol=0, atol=1e-8 * abs(J[0]))
    # the table turned at exactly W
    table = scene.robot.joint("table")
    angle = np.arctan2(sim.q[:, table.idx_q + 1], sim.q[:, table.idx_q])
    assert_allclose(np.unwrap(angle), W * t, rtol=0, atol=1e-10)
    assert_allclose(sim.v[:, table.idx_v], W, rtol=0, atol=0)


FREE_BODY = """<?xml version="1.0"?>
<robot name="body">
  <link name="body">
    <inertial>
      <origin xyz="0.1 0.02 0" rpy="0 0 0"/>
      <mass value="2.0"/>
      <inertia ixx="0.1" ixy="0.01" ixz="0.0" iyy="0.2" iyz="0.0" izz="0.3"/>
    </inertial>
  </link>
</robot>
"""


def test_free_flyer_conserves_energy_and_momentum_across_charts():
    robot = pinlin.load_urdf_string(FREE_BODY, free_flyer=True)
    scene = pinlin.Scene(robot, [], gravity=(0, 0, 0))
    assert robot.nq == 7 and robot.nv == 6
    q0 = scene.neutral()
    v0 = np.array([0.1, 0.0, -0.2, 1.0, 0.6, 2.0])
    t = np.linspace(0.0, 6.0, 61)
    sim = pinlin.simulate(scene, q0, v0, t, chart_radius=1.0)
    assert sim.charts > 5  # rotated by about 13 rad: re-centred many times
    model = scene.model
    data = model.createData()
    energy = np.array([pin.computeKineticEnergy(model, data, q, v) for q, v in zip(sim.q, sim.v)])
    momentum = []
    for q, v in zip(sim.q, sim.v):
        h = pin.computeCentroidalMomentum(model, data, q, v)
        momentum.append(np.concatenate([h.linear, h.angular]))
    momentum = np.array(momentum)
    assert_allclose(energy, energy[0], rtol=1e-9, atol=0)
    assert_allclose(momentum, np.broadcast_to(momentum[0], momentum.shape), rtol=0, atol=1e-9 * np.abs(momentum[0]).max())
    assert_allclose(np.linalg.norm(sim.q[:, 3:], axis=1), 1.0, rtol=0, atol=1e-12)  # unit quaternions


def test_continuous_joints_match_revolute_joints():
    # The same chain with continuous joints (nq = 2 nv, SO(2)) and revolute joints (nq = nv).
    def scene(kind):
        robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, joint_type=kind))
        return pinlin.Scene(robot, [pinlin.JointSpring("joint1", 4.0), pinlin.JointDamper("joint2", 0.1)])

    rev, cont = scene("revolute"), scene("continuous")
    angles = np.array([2.5, -1.0])  # beyond pi/2: the angle wraps in (cos, sin) form
    t = np.linspace(0.0, 2.0, 21)
    s_rev = pinlin.simulate(rev, angles, [3.0, 0.0], t)
    s_cont = pinlin.simulate(cont, np.ravel(np.column_stack([np.cos(angles), np.sin(angles)])), [3.0, 0.0], t)
    assert cont.robot.nq == 4 and cont.robot.nv == 2
    theta = np.arctan2(s_cont.q[:, 1::2], s_cont.q[:, 0::2])
    wrapped = np.angle(np.exp(1j * s_rev.q))
    assert_allclose(np.angle(np.exp(1j * (theta - wrapped))), 0.0, rtol=0, atol=1e-8)
    assert_allclose(s_cont.v, s_rev.v, rtol=0, atol=1e-8)
    assert np.ptp(s_rev.q[:, 0]) > 1.0


def test_implicit_method_agrees_with_explicit():
    scene, q_eq = turntable()
    q0 = q_eq.copy()
    q0[scene.robot.joint("arm").idx_q] = 0.3
    t = np.linspace(0.0, 1.0, 11)
    explicit = pinlin.simulate(scene, q0, None, t)
    implicit = pinlin.simulate(scene, q0, None, t, method="Radau", rtol=1e-10, atol=1e-12)
    assert implicit.integrator == "Radau" and "solve_ivp Radau" in implicit.method and implicit.njev > 0
    assert_allclose(implicit.q, explicit.q, rtol=0, atol=1e-8)


def test_linear_coordinates_are_tangent_differences():
    scene, q_eq = turntable()
    q = q_eq.copy()
    q[scene.robot.joint("arm").idx_q] += 0.01
    q[scene.robot.joint("slider").idx_q] -= 0.02
    x, xdot = pinlin.linear_coordinates(scene, q_eq, q, np.array([2.0, 0.5, -0.1]))
    assert_allclose(x, [0.01, -0.02], rtol=0, atol=1e-15)
    assert_allclose(xdot, [0.5, -0.1], rtol=0, atol=1e-15)
    # a turned table does not change the deviation of the free coordinates
    q_turned = pin.integrate(scene.model, q, np.array([1.3, 0.0, 0.0]))
    x2, none = pinlin.linear_coordinates(scene, q_eq, q_turned)
    assert none is None
    assert_allclose(x2, x, rtol=0, atol=1e-15)


def test_linear_coordinates_of_a_floating_body_at_small_rotations():
    """A free body 1.6e-4 rad from its operating point (where Pinocchio 4.1's dDifference is 7e-6 off):
    x = log6(q_op^-1 q) and xdot = J_log(q_op^-1 q) v, both against mpmath."""
    robot = pinlin.load_urdf_string(BOX_URDF, free_flyer=True)
    scene = pinlin.Scene(robot, gravity=(0, 0, 0))
    rng = np.random.default_rng(11)
    q_op = pin.integrate(robot.model, pin.neutral(robot.model), rng.normal(size=6))
    w = rng.normal(size=3)
    xi = np.concatenate([rng.normal(size=3), 1.6e-4 * w / np.linalg.norm(w)])
    q = pin.integrate(robot.model, q_op, xi)
    v = rng.normal(size=6)
    x, xdot = pinlin.linear_coordinates(scene, q_op, q, v)
    X = pin.XYZQUATToSE3(q_op).actInv(pin.XYZQUATToSE3(q))
    assert_allclose(x, mp_log6(X.rotation, X.translation), rtol=0, atol=1e-15)
    assert_allclose(x, xi, rtol=0, atol=1e-12)  # (Pinocchio's integrate that made q: 2e-13 off in this band)
    assert_allclose(xdot, mp_log6_jacobian(X.rotation, X.translation) @ v, rtol=0, atol=1e-14)


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
@pytest.mark.parametrize("rtol", [1e-5, 1e-8])
def test_error_estimate_matches_the_true_error(method, rtol):
    # The rotating ring (theory: rotating ring) has exactly linear equations of motion: expm of its
    # linearization is the exact trajectory, against which the estimate is checked.
    scene = rotating_ring()
    q_eq = scene.neutral()
    x0, v0 = np.array([0.3, -0.2]), np.array([0.5, 1.0])
    t = np.linspace(0.0, 5.0, 51)
    x_exact, v_exact = expm_free_response(pinlin.linearize(scene, q_eq), x0, v0, t)
    step = np.zeros(scene.model.nv)
    step[scene.free_dofs] = x0
    sim = pinlin.simulate(scene, pin.integrate(scene.model, q_eq, step), v0, t, method=method, rtol=rtol, atol=1e-2 * rtol)
    x, _ = sim.linear_coordinates(q_eq)
    v = sim.v[:, scene.free_dofs]
    true_q = np.max(np.linalg.norm(x - x_exact, axis=1)) / np.max(np.linalg.norm(x - x[0], axis=1))
    true_v = np.max(np.linalg.norm(v - v_exact, axis=1)) / np.max(np.linalg.norm(v, axis=1))
    # tolerance proportionality: within a factor 2 of the truth (measured: 0.9 to 1.05)
    assert 0.5 < sim.error_q / true_q < 2.0
    assert 0.5 < sim.error_v / true_v < 2.0
    assert sim.error == max(sim.error_q, sim.error_v)
    assert sim.error < 1e3 * rtol and sim.reference_nfev > sim.nfev


def test_result_convention_and_skipped_estimate():
    scene, q_eq = turntable()
    t = np.linspace(0.0, 0.5, 6)
    sim = pinlin.simulate(scene, q_eq, [0.1, 0.0], t, rtol=1e-9)
    assert "solve_ivp DOP853" in sim.method and "rtol=1e-09" in sim.method and "/ 10" in sim.method
    assert np.isfinite(sim.error) and sim.elapsed > 0
    data = sim.to_dict()
    assert list(data)[:4] == ["type", "method", "error", "elapsed"] and data["type"] == "Simulation"
    assert "scene" not in data and np.array_equal(np.array(data["values"]), sim.q)
    assert json.loads(json.dumps(data, allow_nan=False))["integrator"] == "DOP853"
    fast = pinlin.simulate(scene, q_eq, [0.1, 0.0], t, rtol=1e-9, estimate_error=False)
    assert np.isnan(fast.error) and fast.reference_nfev == 0 and "not estimated" in fast.method
    assert np.array_equal(fast.q, sim.q) and np.array_equal(fast.v, sim.v)  # the returned run is the same


def test_single_time_point_returns_initial_state():
    scene, q_eq = turntable()
    sim = pinlin.simulate(scene, q_eq, None, [0.5])
    assert_allclose(sim.q, q_eq[None, :], rtol=0, atol=0)
    assert_allclose(sim.v, scene.v0[None, :], rtol=0, atol=0)


class _NaNAfter(Element):
    """A test element whose force becomes NaN once joint1 passes 0.1 rad."""

    kind = "nan-after"

    def check(self, robot):
        return None

    def generalized_force(self, ev):
        return np.full(ev.model.nv, np.nan) if ev.q[0] > 0.1 else np.zeros(ev.model.nv)


@pytest.fixture
def pendulum():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1))
    return pinlin.Scene(robot, [pinlin.JointSpring("joint1", 1.0)])


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"q0": [0.0, 0.0]}, pinlin.ConfigurationError, "nq = 1"),
        ({"q0": [np.nan]}, pinlin.ConfigurationError, "non-finite"),
        ({"v0": [0.0, 1.0]}, pinlin.ConfigurationError, "velocity of size nv = 1"),
        ({"v0": [np.inf]}, pinlin.ConfigurationError, "non-finite"),
        ({"t": [0.0, 1.0, 1.0]}, pinlin.ParameterError, "strictly increasing"),
        ({"t": [0.0, np.nan]}, pinlin.ParameterError, "finite"),
        ({"t": [[0.0, 1.0]]}, pinlin.ParameterError, "1-D"),
        ({"t": None}, pinlin.ParameterError, "required"),
        ({"method": "Euler"}, pinlin.ParameterError, "unknown method"),
        ({"rtol": -1.0}, pinlin.ParameterError, "rtol"),
        ({"rtol": 1e-15}, pinlin.ParameterError, "cannot honour rtol"),
        ({"rtol": 1e-13}, pinlin.ParameterError, "comparison run"),
        ({"max_step": "long"}, pinlin.ParameterError, "max_step"),
        ({"atol": np.nan}, pinlin.ParameterError, "atol"),
        ({"chart_radius": 4.0}, pinlin.ParameterError, "chart_radius"),
        ({"max_step": 0.0}, pinlin.ParameterError, "max_step"),
    ],
)
def test_bad_inputs_raise(pendulum, kwargs, error, match):
    args = {"q0": [0.1], "v0": None, "t": [0.0, 1.0]}
    args.update(kwargs)
    q0, v0, t = args.pop("q0"), args.pop("v0"), args.pop("t")
    with pytest.raises(error, match=match):
        pinlin.simulate(pendulum, q0, v0, t, **args)


def test_bad_scene_and_prescribed_velocity_raise():
    with pytest.raises(pinlin.ParameterError, match="pinlin.Scene"):
        pinlin.simulate("scene", [0.0], None, [0.0, 1.0])
    scene, q_eq = turntable()
    with pytest.raises(pinlin.ConfigurationError, match="prescribed joint 'table'"):
        pinlin.simulate(scene, q_eq, [1.0, 0.0, 0.0], [0.0, 1.0])
    with pytest.raises(pinlin.ConfigurationError, match="q_op"):
        pinlin.linear_coordinates(scene, q_eq[:2], q_eq)
    with pytest.raises(pinlin.ConfigurationError, match="v has shape"):
        pinlin.linear_coordinates(scene, q_eq, q_eq, [0.0])


def test_non_finite_dynamics_raise_integration_error():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1))
    scene = pinlin.Scene(robot, [_NaNAfter()])
    with pytest.raises(pinlin.IntegrationError, match="non-finite") as info:
        pinlin.simulate(scene, [0.0], [1.0], [0.0, 1.0])
    assert 0.0 < info.value.t_reached < 1.0


def test_default_accuracy_is_the_named_constants():
    import inspect

    from pinlin.nonlinear.simulate import DEFAULT_ATOL, DEFAULT_RTOL

    params = inspect.signature(pinlin.simulate).parameters
    assert (params["rtol"].default, params["atol"].default) == (DEFAULT_RTOL, DEFAULT_ATOL) == (1e-10, 1e-12)
