"""URDF generators of machines that roll and spin (pinlin.model.vehicles): geometry, inertia, bad input."""

import math

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.vehicles import (
    WhippleParameters,
    free_body_urdf,
    rolling_disk_urdf,
    top_urdf,
    whipple_bicycle_urdf,
)

P = WhippleParameters()
BODIES = ("rear_frame", "rear_wheel_body", "fork", "front_wheel_body")


def upright(model):
    q = pin.neutral(model)
    q[2] = P.rR
    return q


def body_coms(model, data):
    """World centre of mass and mass of each body, by link name."""
    out = {}
    for name in BODIES:
        frame = model.frames[model.getFrameId(name)]
        inertia = model.inertias[frame.parentJoint]
        out[name] = (data.oMi[frame.parentJoint].act(inertia.lever), inertia.mass)
    return out


def test_bicycle_loads_in_pinocchio_and_pinlin():
    text = whipple_bicycle_urdf()
    robot = pinlin.load_urdf_string(text, free_flyer=True)
    assert robot.joint_names[-3:] == ("rear_wheel", "steer", "front_wheel")
    model = pin.buildModelFromXML(text, pin.JointModelFreeFlyer())
    assert (model.nq, model.nv) == (robot.model.nq, robot.model.nv) == (12, 9)


def test_bicycle_masses_and_centres_of_mass():
    model = pin.buildModelFromXML(whipple_bicycle_urdf(), pin.JointModelFreeFlyer())
    data = model.createData()
    total_com = pin.centerOfMass(model, data, upright(model))
    assert_allclose(pin.computeTotalMass(model), 94.0, rtol=1e-15)
    # The benchmark's positions (x forward, z down from the rear contact) in z-up axes.
    expected = {"rear_frame": ([P.xB, 0, -P.zB], P.mB), "rear_wheel_body": ([0, 0, P.rR], P.mR),
                "fork": ([P.xH, 0, -P.zH], P.mH), "front_wheel_body": ([P.w, 0, P.rF], P.mF)}
    coms = body_coms(model, data)
    for name, (com, mass) in expected.items():
        assert_allclose(coms[name][0], com, rtol=0, atol=1e-15, err_msg=name)
        assert coms[name][1] == mass
    mean = sum(mass * com for com, mass in coms.values()) / sum(mass for _, mass in coms.values())
    assert_allclose(total_com, mean, rtol=1e-15)
    assert_allclose(total_com, [(85 * 0.3 + 4 * 0.9 + 3 * 1.02) / 94, 0, 80.95 / 94], rtol=1e-15)  # by hand


def test_bicycle_inertia_products_change_sign_with_the_axes():
    model = pin.buildModelFromXML(whipple_bicycle_urdf(), pin.JointModelFreeFlyer())
    rear = model.inertias[1].inertia  # the rear frame with rider, about its centre of mass
    fork = model.inertias[model.getJointId("steer")].inertia
    assert_allclose(rear, [[9.2, 0, -2.4], [0, 11.0, 0], [-2.4, 0, 2.8]], rtol=1e-15)
    assert_allclose(fork, [[0.05892, 0, 0.00756], [0, 0.06, 0], [0.00756, 0, 0.00708]], rtol=1e-15)
    for name, axial, diametral in (("rear_wheel", P.IRyy, P.IRxx), ("front_wheel", P.IFyy, P.IFxx)):
        wheel = model.inertias[model.getJointId(name)]
        assert_allclose(wheel.inertia, np.diag([diametral, axial, diametral]), rtol=1e-15)


def test_bicycle_steer_axis_gives_the_trail():
    model = pin.buildModelFromXML(whipple_bicycle_urdf(), pin.JointModelFreeFlyer())
    data = model.createData()
    pin.forwardKinematics(model, data, upright(model))
    steer = data.oMi[model.getJointId("steer")]
    axis = steer.rotation @ model.joints[model.getJointId("steer")].extract().axis
    assert_allclose(axis, [math.sin(P.lam), 0, -math.cos(P.lam)], rtol=0, atol=2e-16)  # pointing down
    ground = steer.translation - steer.translation[2] / axis[2] * axis
    assert_allclose(ground, [P.w + P.c, 0, 0], rtol=0, atol=1e-15)  # trail c behind the axis
    front = data.oMi[model.getJointId("front_wheel")].translation
    assert_allclose(front, [P.w, 0, P.rF], rtol=0, atol=1e-15)


def test_bicycle_other_parameters():
    text = whipple_bicycle_urdf(WhippleParameters(mB=60.0, rF=0.3, w=1.1))
    model = pin.buildModelFromXML(text, pin.JointModelFreeFlyer())
    data = model.createData()
    assert_allclose(pin.computeTotalMass(model), 69.0, rtol=1e-15)
    pin.forwardKinematics(model, data, upright(model))
    assert_allclose(data.oMi[model.getJointId("front_wheel")].translation, [1.1, 0, 0.3], atol=1e-15)


def test_bundled_bicycle_is_the_generator_output():
    path = pinlin.data_path("urdf/whipple_bicycle.urdf")
    assert path.read_text() == whipple_bicycle_urdf()


@pytest.mark.parametrize("hoop, axial, diametral", [(False, 0.5, 0.25), (True, 1.0, 0.5)])
def test_rolling_disk(hoop, axial, diametral):
    r, m = 0.4, 3.0
    text = rolling_disk_urdf(r, m, hoop=hoop)
    robot = pinlin.load_urdf_string(text)
    assert robot.joint_names == ("x", "y", "z", "heading", "lean", "spin")
    model = pin.buildModelFromXML(text)
    assert [i.mass for i in model.inertias[1:6]] == [0.0] * 5  # massless slides and hinges
    disk = model.inertias[6]
    assert disk.mass == m
    assert_allclose(disk.inertia, m * r * r * np.diag([diametral, axial, diametral]), rtol=1e-15)
    data = model.createData()
    q = pin.neutral(model)
    q[2] = r
    Mq = pin.crba(model, data, q)
    assert np.linalg.eigvalsh(np.triu(Mq) + np.triu(Mq, 1).T).min() > 0


def test_free_body():
    text = free_body_urdf(1.0, 2.0, 2.5, 4.0)
    robot = pinlin.load_urdf_string(text, free_flyer=True)
    assert robot.model.nv == 6
    assert_allclose(robot.model.inertias[1].inertia, np.diag([1.0, 2.0, 2.5]))
    assert robot.model.inertias[1].mass == 4.0


def test_top():
    m, l, A, C = 1.5, 0.2, 0.1, 0.08
    robot = pinlin.load_urdf_string(top_urdf(m, l, A, C))
    model = robot.model
    top = model.inertias[model.getJointId("spin")]
    assert_allclose(top.lever, [0, 0, l])
    about_pivot = top.inertia + m * (l * l * np.eye(3) - np.outer(top.lever, top.lever))
    assert_allclose(about_pivot, np.diag([A, A, C]), rtol=1e-15)
    data = model.createData()
    Mq = pin.crba(model, data, pin.neutral(model))
    assert_allclose(np.triu(Mq) + np.triu(Mq, 1).T, np.diag([A, A, C]), rtol=1e-15)  # regular when sleeping


@pytest.mark.parametrize("call, match", [
    (lambda: WhippleParameters(mB=-85.0), "mB: must be positive"),
    (lambda: WhippleParameters(rR=0.0), "rR: must be positive"),
    (lambda: WhippleParameters(w=float("nan")), "w: must be finite"),
    (lambda: WhippleParameters(c="trail"), "c: expected a real number"),
    (lambda: WhippleParameters(lam=2.0), r"lam: steer axis tilt must lie in \(-pi/2, pi/2\)"),
    (lambda: WhippleParameters(IBxz=6.0), "IBxz: tensor of body B is not positive definite"),
    (lambda: WhippleParameters(IByy=30.0), "IB: principal moments .* triangle inequality"),
    (lambda: WhippleParameters(IRyy=0.2), "IRxx/IRyy: principal moments"),
    (lambda: whipple_bicycle_urdf({"mB": 85.0}), "params: expected WhippleParameters, got dict"),
    (lambda: rolling_disk_urdf(0.0, 1.0), "radius: must be positive, got 0.0"),
    (lambda: rolling_disk_urdf(-0.3, 1.0), "radius: must be positive"),
    (lambda: rolling_disk_urdf(0.3, -1.0), "mass: must be positive"),
    (lambda: rolling_disk_urdf(None, 1.0), "radius: expected a real number, got None"),
    (lambda: rolling_disk_urdf("0.3", 1.0), "radius: expected a real number, got '0.3'"),
    (lambda: rolling_disk_urdf(0.3, True), "mass: expected a real number, got True"),
    (lambda: free_body_urdf(1.0, 1.0, 3.0, 1.0), r"I1/I2/I3: principal moments \(1.0, 1.0, 3.0\)"),
    (lambda: free_body_urdf(1.0, 2.0, 2.0, -2.0), "mass: must be positive"),
    (lambda: free_body_urdf(0.0, 2.0, 2.0, 1.0), "I1: must be positive"),
    (lambda: top_urdf(1.0, 0.2, 0.03, 0.01), "A: the moment about the pivot must exceed m l"),
    (lambda: top_urdf(1.0, 0.2, 0.1, 0.2), "A/C: principal moments"),
    (lambda: top_urdf(-1.0, 0.2, 0.1, 0.05), "mass: must be positive"),
    (lambda: top_urdf(1.0, float("inf"), 0.1, 0.05), "l: must be finite"),
])
def test_bad_parameters(call, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        call()


def test_whipple_parameters_are_keywords_only():
    with pytest.raises(TypeError):
        WhippleParameters(1.02)
