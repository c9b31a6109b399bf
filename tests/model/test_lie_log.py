"""The joint springs' Lie-group log (pinlin.model.elements.lie_log) against mpmath, the stacked SE(3)
expansion of the bushings, Pinocchio away from small angles, and differences of Pinocchio's log.

Pinocchio 4.1's dDifference on SE(3), SO(3) and SE(2) loses accuracy between about 1e-4 and
2e-3 rad (up to 3e-5 relative on SE(3)): the tests in that band use mpmath references only.
"""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from helpers import BOX_URDF, mp_exp6_log_jacobian, mp_log6_jacobian
from pinlin.model.elements.lie_log import beta_gamma, exp_chart_rate, joint_log, se3_log
from pinlin.model.elements.se3 import log_expansion
from pinlin.nonlinear.charts import Chart, chart_groups

#: Angles [rad] of the band where Pinocchio 4.1's Lie-group Jacobians lose accuracy, and beyond.
BAND = [1e-4, 1.6e-4, 3e-4, 1e-3, 2e-3]
ANGLES = [0.0, 1e-9, *BAND, 0.3, 1.0, 1.99, 2.0, 2.01, 3.0, 3.1]


def _placement(rng, angle):
    w = rng.normal(size=3)
    return pin.exp3(angle * w / np.linalg.norm(w)), rng.normal(size=3)


def test_beta_gamma_against_their_closed_forms_in_mpmath():
    import mpmath as mp

    with mp.workdps(40):
        for t in [1e-6, 1e-3, 0.1, 0.9, 1.5, 1.999, 2.001, 2.5, 3.1]:
            tm = mp.mpf(t)
            beta = 1 / tm**2 - (1 + mp.cos(tm)) / (2 * tm * mp.sin(tm))
            gamma = mp.diff(lambda s: 1 / s**2 - (1 + mp.cos(s)) / (2 * s * mp.sin(s)), tm) / tm
            b, g = beta_gamma(t * t)
            assert abs(b - float(beta)) <= 2e-16 * abs(float(beta))
            assert abs(g - float(gamma)) <= 1e-15 * abs(float(gamma))


@pytest.mark.parametrize("angle", ANGLES)
def test_se3_log_against_the_stacked_expansion(angle):
    """e and J_log for one placement (Python floats) against the bushings' stacked expansion, checked
    against mpmath in test_frame_elements: the same closed form, evaluated another way."""
    R, p = _placement(np.random.default_rng(int(angle * 1e6) + 1), angle)
    theta = pin.log3(R)
    J_ref, _ = log_expansion(R, p, theta, second_order=False)
    e, J = se3_log(theta.tolist(), p.tolist())
    assert_allclose(J, J_ref, rtol=0, atol=2e-15 * np.abs(J_ref).max())
    assert_allclose(e, np.concatenate([J_ref[:3, :3].T @ p, theta]), rtol=0, atol=2e-15 * np.linalg.norm(p))


@pytest.mark.parametrize("angle", BAND)
def test_se3_log_jacobian_against_mpmath_in_pinocchios_band(angle):
    R, p = _placement(np.random.default_rng(7), angle)
    _, J = se3_log(pin.log3(R).tolist(), p.tolist())
    assert_allclose(J, mp_log6_jacobian(R, p), rtol=0, atol=1e-14)


@pytest.mark.parametrize("kind", [pin.JointModelFreeFlyer, pin.JointModelSpherical, pin.JointModelPlanar])
def test_joint_log_is_pinocchios_difference_away_from_the_band_and_exact_at_rest(kind):
    """The conventions: the same e and de/dq as Pinocchio's difference and dDifference(ARG1) where
    Pinocchio is accurate (below 1e-6 rad and above 0.05 rad); e = 0 and de/dq = I exactly at rest."""
    model = pin.Model()
    model.addJoint(0, kind(), pin.SE3.Identity(), "j")
    group, rng = model.joints[1].lieGroup(), np.random.default_rng(3)
    pin.seed(3)  # numpy's rng does not seed Pinocchio's randomConfiguration
    for angle in [0.0, 1e-7, 0.05, 0.5, 2.0, 3.0]:
        rest = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
        xi = rng.normal(size=model.nv)
        rotation = slice(3, 6) if model.nv == 6 else (slice(0, 3) if model.nq == 4 else slice(2, 3))
        xi[rotation] *= angle / np.linalg.norm(xi[rotation])
        q = pin.integrate(model, rest, xi)
        log = joint_log(model.joints[1], rest)
        assert log.name == group.name
        assert_allclose(log.difference(q), group.difference(rest, q), rtol=0, atol=1e-13)
        assert_allclose(log.jacobian(q), group.dDifference(rest, q, pin.ARG1), rtol=0, atol=1e-12)
        assert not log.difference(rest).any()
        assert np.array_equal(log.jacobian(rest), np.eye(model.nv))


def test_free_flyer_spring_stiffness_near_rest_against_mpmath():
    """A 6-DOF spring mount deflected by 1.6e-4 rad: K = K_s J_log(rest^-1 q), with J_log from mpmath.
    Pinocchio's dDifference (the code before) is 8e-6 off here (relative); now exact to rounding."""
    robot = pinlin.load_urdf_string(BOX_URDF, free_flyer=True)
    rng = np.random.default_rng(11)
    A = rng.normal(size=(6, 6))
    Ks = A @ A.T + 6.0 * np.eye(6)
    rest = pin.neutral(robot.model)
    R, p = _placement(rng, 1.6e-4)
    q = pin.SE3ToXYZQUAT(pin.SE3(R, p))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("root_joint", Ks, rest=rest)], gravity=(0, 0, 0))
    sys = pinlin.linearize(scene, q, balancing=True)
    X = pin.XYZQUATToSE3(q)
    K_ref = Ks @ mp_log6_jacobian(X.rotation, X.translation)
    assert_allclose(sys.K, K_ref, rtol=0, atol=5e-14 * np.abs(K_ref).max())
    assert_allclose(pinlin.linearize_many(scene, [q, q], balancing=True)[1].K, sys.K, rtol=0, atol=0)


@pytest.mark.parametrize("angle", [1e-9, *BAND, 0.5, 2.5])
def test_exp_chart_rate_against_mpmath(angle):
    """The simulator's chart rate (d integrate / d dq)^-1 v = J_log(exp dq) v, exp and log in mpmath
    (solving Pinocchio 4.1's dIntegrate: up to 3e-5 off in the band); SO(3) and SE(2) as its blocks."""
    rng = np.random.default_rng(int(angle * 1e5) + 3)
    w = rng.normal(size=3)
    dq = np.concatenate([rng.normal(size=3), angle * w / np.linalg.norm(w)])
    v = rng.normal(size=6)
    J = mp_exp6_log_jacobian(dq)
    assert_allclose(exp_chart_rate("SE(3)", dq, v), J @ v, rtol=0, atol=1e-14 * np.abs(J).max() * np.abs(v).max())
    assert_allclose(exp_chart_rate("SO(3)", dq[3:], v[3:]), J[3:, 3:] @ v[3:], rtol=0, atol=1e-15)
    planar = np.array([dq[0], dq[1], 0.0, 0.0, 0.0, angle])
    Jp = mp_exp6_log_jacobian(planar)[np.ix_([0, 1, 5], [0, 1, 5])]
    assert_allclose(exp_chart_rate("SE(2)", planar[[0, 1, 5]], v[:3]), Jp @ v[:3], rtol=0, atol=1e-14 * np.abs(Jp).max())


def test_chart_rate_of_a_model_with_a_free_flyer_and_a_spherical_joint():
    """Chart.coordinate_rate block by block equals solving Pinocchio's dIntegrate where that is accurate."""
    model = pin.Model()
    root = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "root")
    ball = model.addJoint(root, pin.JointModelSpherical(), pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.5])), "ball")
    model.addJoint(ball, pin.JointModelRUBY(), pin.SE3.Identity(), "wheel")
    rng = np.random.default_rng(4)
    pin.seed(4)  # numpy's rng does not seed Pinocchio
    base = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
    chart = Chart(model, base, chart_groups(model))
    assert [name for _, name in chart.curved] == ["SE(3)", "SO(3)"]
    dq, v = 0.7 * rng.normal(size=model.nv), rng.normal(size=model.nv)
    expected = np.linalg.solve(pin.dIntegrate(model, base, dq, pin.ARG1), v)
    assert_allclose(chart.coordinate_rate(dq, v), expected, rtol=0, atol=1e-12)
    assert chart.recentred(dq).curved is chart.curved


@pytest.mark.parametrize("kind", [pin.JointModelFreeFlyer, pin.JointModelSpherical, pin.JointModelPlanar])
def test_joint_log_of_many_rows_against_pinocchio_on_every_branch(kind):
    """evaluate_many (linearize_many's springs) against Pinocchio's difference and dDifference(ARG1) row by row,
    over every branch of the log: at rest (v = 0 exactly), the series of beta and gamma and their closed form
    above t = 2, rotations near pi (w of either sign), translations with and without rotation.  Angles in
    Pinocchio's inaccurate band are left to the mpmath tests above."""
    model = pin.Model()
    model.addJoint(0, kind(), pin.SE3.Identity(), "j")
    group, rng = model.joints[1].lieGroup(), np.random.default_rng(17)
    pin.seed(17)
    rest = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
    rotation = slice(3, 6) if model.nv == 6 else (slice(0, 3) if model.nq == 4 else slice(2, 3))
    rows = [rest.copy()]
    for angle in [0.0, 1e-9, 3e-2, 0.3, 0.9, 1.5, 1.9, 2.1, 3.0, np.pi - 1e-6, np.pi + 1e-3, 5.0]:
        xi = rng.normal(size=model.nv)
        xi[rotation] *= angle / np.linalg.norm(xi[rotation])
        rows.append(pin.integrate(model, rest, xi))
    qs = np.array(rows)
    if model.nq == 7:  # the same rotation by -q (w < 0) as by q
        qs = np.vstack([qs, np.hstack([qs[:, :3], -qs[:, 3:]])])
    log = joint_log(model.joints[1], rest)
    E, J = log.evaluate_many(qs)
    assert E.shape == (len(qs), model.nv) and J.shape == (len(qs), model.nv, model.nv)
    for q, e, jacobian in zip(qs, E, J):
        assert_allclose(e, group.difference(rest, q), rtol=0, atol=1e-12)
        assert_allclose(jacobian, group.dDifference(rest, q, pin.ARG1), rtol=0, atol=1e-9)
    assert not E[0].any() and np.array_equal(J[0], np.eye(model.nv))
