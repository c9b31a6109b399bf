"""The rolling-contact kernels: contact point, Jacobian, P0 = d(J v)/dq and K_lam = d(J^T lam)/dq.

Every derivative is checked against central differences on the configuration manifold
(``pin.integrate``, Richardson-extrapolated) on two models: a disk on slides and hinges
(x, y, z, heading, lean, then a continuous spin joint) and a free-flyer disk whose wheel
frame is offset and turned from the body (so the axle is not a frame axis).  The upright and
the leaning disk's contact point and Jacobian are checked against hand values.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

from pinlin.errors import ConstraintError, ParameterError
from pinlin.linearization.moving_frame import moving_frame_matrix
from pinlin.model.constraints.rolling_contact import (
    contact_force_stiffness,
    contact_jacobian,
    contact_point,
    contact_velocity_derivative,
)

RADIUS = 0.3
MASS = 2.0
#: Diametral and axial moments [kg m^2] of a uniform disk (m r^2 / 4, m r^2 / 2) and of a hoop (m r^2 / 2, m r^2).
UNIFORM, HOOP = (0.045, 0.09), (0.09, 0.18)


def _disk_inertia(diametral, axial):
    return (f'<inertial><origin xyz="0 0 0"/><mass value="{MASS}"/><inertia ixx="{diametral}" iyy="{axial}" '
            f'izz="{diametral}" ixy="0" ixz="0" iyz="0"/></inertial>')


DISK_INERTIA = _disk_inertia(*UNIFORM)


def _joint(name, kind, parent, child, axis):
    limit = '<limit lower="-10" upper="10" effort="1" velocity="1"/>' if kind != "continuous" else ""
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="0 0 0"/><axis xyz="{axis}"/>{limit}</joint>')


def _hinges_urdf(inertia=UNIFORM):
    return (
        '<robot name="disk_on_hinges"><link name="ground"/><link name="sx"/><link name="sy"/><link name="sz"/>'
        f'<link name="yaw"/><link name="roll"/><link name="disk">{_disk_inertia(*inertia)}</link>'
        + _joint("x", "prismatic", "ground", "sx", "1 0 0")
        + _joint("y", "prismatic", "sx", "sy", "0 1 0")
        + _joint("z", "prismatic", "sy", "sz", "0 0 1")
        + _joint("heading", "revolute", "sz", "yaw", "0 0 1")
        + _joint("lean", "revolute", "yaw", "roll", "1 0 0")
        + _joint("spin", "continuous", "roll", "disk", "0 1 0")
        + "</robot>"
    )

#: The wheel frame of the free disk: offset from the body origin and turned, so the axle in it is not (0, 1, 0).
FRAME_RPY = (0.4, -0.7, 1.1)
FREE_URDF = (
    f'<robot name="free_disk"><link name="body">{DISK_INERTIA}</link><link name="wheel"/>'
    '<joint name="mount" type="fixed"><parent link="body"/><child link="wheel"/>'
    f'<origin xyz="0.05 -0.02 0.1" rpy="{FRAME_RPY[0]} {FRAME_RPY[1]} {FRAME_RPY[2]}"/></joint></robot>'
)


def _hinges(inertia=UNIFORM):
    model = pin.buildModelFromXML(_hinges_urdf(inertia))
    return model, model.getFrameId("disk"), np.array([0.0, 1.0, 0.0])


def _free():
    model = pin.buildModelFromXML(FREE_URDF, pin.JointModelFreeFlyer())
    fid = model.getFrameId("wheel")
    axis = pin.rpy.rpyToMatrix(*FRAME_RPY).T @ np.array([0.0, 1.0, 0.0])  # the body's y axis, in the wheel frame
    return model, fid, axis


MODELS = {"hinges": _hinges, "free": _free}
NORMALS = {"up": np.array([0.0, 0.0, 1.0]), "tilted": np.array([0.1, -0.2, 1.0]) / math.sqrt(1.05)}


def _configuration(kind, model, rng):
    """Random position, heading and spin, lean in [-1.3, 1.3] rad."""
    heading, lean, spin = rng.uniform(-math.pi, math.pi), rng.uniform(-1.3, 1.3), rng.uniform(-math.pi, math.pi)
    position = rng.uniform(-1.0, 1.0, 3)
    if kind == "hinges":
        return np.array([*position, heading, lean, math.cos(spin), math.sin(spin)])
    R = pin.rpy.rpyToMatrix(0.0, 0.0, heading) @ pin.rpy.rpyToMatrix(lean, 0.0, 0.0) @ pin.rpy.rpyToMatrix(0, spin, 0)
    return np.concatenate([position, pin.Quaternion(R).coeffs()])


def _tangent_fd(model, f, q, h=1e-3):
    """d f(integrate(q, dq)) / d dq at 0: central differences, Richardson-extrapolated (error O(h^4))."""
    def central(step, e):
        return (f(pin.integrate(model, q, step * e)) - f(pin.integrate(model, q, -step * e))) / (2 * step)

    cols = [(4 * central(h / 2, e) - central(h, e)) / 3 for e in np.eye(model.nv)]
    return np.stack(cols, axis=-1)


def _rel(a, b):
    return np.linalg.norm(a - b) / np.linalg.norm(b)


CASES = [(kind, normal, seed) for kind in MODELS for normal in NORMALS for seed in range(4)]


@pytest.mark.parametrize("kind, normal, seed", CASES)
def test_derivatives_match_finite_differences(kind, normal, seed):
    model, fid, axis = MODELS[kind]()
    n = NORMALS[normal]
    data = model.createData()
    rng = np.random.default_rng(seed)
    q = _configuration(kind, model, rng)
    v, lam = rng.normal(size=model.nv), rng.normal(size=3) * 10
    args = (model, data, fid, RADIUS, axis, n)

    def jac(qq):
        return contact_jacobian(*args, qq, height=0.05)

    J, _ = jac(q)
    # the holonomic condition's gradient is the normal row
    dh = _tangent_fd(model, lambda qq: np.array([jac(qq)[1]]), q)[0]
    assert _rel(n @ J, dh) < 1e-7
    # the contact point's velocity: J v is the velocity of the material point at c (o + omega x (c - o))
    pin.forwardKinematics(model, data, q, v)
    frame_vel = pin.getFrameVelocity(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    pin.updateFramePlacement(model, data, fid)
    c = contact_point(*args, q)
    expected = frame_vel.linear + np.cross(frame_vel.angular, c - data.oMf[fid].translation)
    assert_allclose(J @ v, expected, rtol=1e-13, atol=1e-13 * np.linalg.norm(v))
    P0 = contact_velocity_derivative(*args, q, v)
    assert _rel(P0, _tangent_fd(model, lambda qq: jac(qq)[0] @ v, q)) < 1e-7
    K = contact_force_stiffness(*args, q, lam)
    assert _rel(K, _tangent_fd(model, lambda qq: jac(qq)[0].T @ lam, q)) < 1e-7


@pytest.mark.parametrize("kind", MODELS)
def test_drift_is_p0_times_v(kind):
    """d/dt(J(q(t))) v along q(t) = integrate(q, t v) equals P0(q, v) v."""
    model, fid, axis = MODELS[kind]()
    data = model.createData()
    rng = np.random.default_rng(7)
    q, v = _configuration(kind, model, rng), rng.normal(size=model.nv)
    args = (model, data, fid, RADIUS, axis, NORMALS["up"])

    def along(t):
        return contact_jacobian(*args, pin.integrate(model, q, t * v))[0] @ v

    h = 1e-3
    drift = (4 * (along(h / 2) - along(-h / 2)) / h - (along(h) - along(-h)) / (2 * h)) / 3
    assert _rel(contact_velocity_derivative(*args, q, v) @ v, drift) < 1e-7


def test_upright_disk_hand_values():
    """Upright, heading 0: c below the centre; J from the slides, and r x (spin, lean) rates."""
    model, fid, axis = _hinges()
    q = np.array([0.4, -0.2, RADIUS, 0.0, 0.0, 1.0, 0.0])
    data = model.createData()
    args = (model, data, fid, RADIUS, axis, NORMALS["up"])
    assert_allclose(contact_point(*args, q), [0.4, -0.2, 0.0], atol=1e-15)
    J, h = contact_jacobian(*args, q)
    r = RADIUS
    assert_allclose(J, [[1, 0, 0, 0, 0, -r], [0, 1, 0, 0, r, 0], [0, 0, 1, 0, 0, 0]], atol=1e-15)
    assert h == pytest.approx(0.0, abs=1e-15)


def test_leaning_disk_hand_values():
    """Lean phi (about x after heading 0): u = (0, -sin phi, cos phi), c = o - r u, h = z - r cos phi."""
    model, fid, axis = _hinges()
    phi, z = 0.7, 0.5
    q = np.array([0.1, 0.2, z, 0.0, phi, 1.0, 0.0])
    args = (model, model.createData(), fid, RADIUS, axis, NORMALS["up"])
    u = np.array([0.0, -math.sin(phi), math.cos(phi)])
    assert_allclose(contact_point(*args, q), np.array([0.1, 0.2, z]) - RADIUS * u, atol=1e-15)
    J, h = contact_jacobian(*args, q, height=0.01)
    assert h == pytest.approx(z - RADIUS * math.cos(phi) - 0.01, abs=1e-15)
    # the spin column: r u x a_w with a_w = (0, cos phi, sin phi): the contact point moves along -x
    assert_allclose(J[:, 5], [-RADIUS, 0.0, 0.0], atol=1e-15)
    # the lean column: rotation about x at the centre moves the contact point along y only: r u x e_x
    assert_allclose(J[:, 4], RADIUS * np.cross(u, [1.0, 0.0, 0.0]), atol=1e-15)


def test_flat_wheel_is_refused():
    model, fid, axis = _hinges()
    q = np.array([0.0, 0.0, 0.0, 0.3, math.pi / 2, 1.0, 0.0])  # axle vertical
    args = (model, model.createData(), fid, RADIUS, axis, NORMALS["up"])
    for kernel, extra in ((contact_point, ()), (contact_jacobian, ()), (contact_velocity_derivative, (np.ones(6),)),
                          (contact_force_stiffness, ((0, 0, 1.0),))):
        with pytest.raises(ConstraintError, match="wheel frame 'disk'.*lies flat") as err:
            kernel(*args, q, *extra)
        assert err.value.constraints == ("disk",)
    # just off flat, the contact point exists
    q[4] = math.pi / 2 - 1e-4
    assert np.all(np.isfinite(contact_point(*args, q)))


@pytest.mark.parametrize(
    "change, match",
    [
        ({"radius": 0.0}, "radius: must be a finite number > 0"),
        ({"radius": math.nan}, "radius: must be a finite number > 0"),
        ({"radius": "big"}, "radius"),
        ({"axis": (0, 0, 0)}, "axis: must not be zero"),
        ({"normal": (0, 0)}, "normal: expected 3 numbers"),
        ({"frame_id": 99}, r"frame_id: expected a frame index in \[0, "),
    ],
)
def test_bad_parameters_are_refused(change, match):
    model, fid, axis = _hinges()
    params = {"frame_id": fid, "radius": RADIUS, "axis": axis, "normal": (0, 0, 1)} | change
    q = np.array([0.0, 0.0, RADIUS, 0.0, 0.0, 1.0, 0.0])
    with pytest.raises(ParameterError, match=match):
        contact_point(model, model.createData(), params["frame_id"], params["radius"], params["axis"],
                      params["normal"], q)


def test_bad_height_is_refused():
    model, fid, axis = _hinges()
    q = np.array([0.0, 0.0, RADIUS, 0.0, 0.0, 1.0, 0.0])
    with pytest.raises(ParameterError, match="height: must be a finite number"):
        contact_jacobian(model, model.createData(), fid, RADIUS, axis, (0, 0, 1), q, height=math.inf)


def test_stiffness_refuses_configuration_dependent_joints():
    model = pin.Model()
    joint = model.addJoint(0, pin.JointModelSphericalZYX(), pin.SE3.Identity(), "ball")
    fid = model.addJointFrame(joint)
    q = np.array([0.0, 0.0, 0.0])
    with pytest.raises(ParameterError, match="joint 'ball' \\(JointModelSphericalZYX\\) moves wheel frame"):
        contact_force_stiffness(model, model.createData(), fid, RADIUS, (0, 1, 0), (0, 0, 1), q, (0, 0, 1.0))


def _rolling_system(model, fid, axis, q0, v0):
    """State matrix of (x, u) for a wheel rolling at the steady motion (q0, v0), assembled from the kernels
    as the steady-motion linearization will be: J0 dv + P0 x = 0 gives dv = B u + P x (B = ker J0,
    P = -J0^+ P0); x' = dv - A x (the moving-frame term); B^T [M dv' + C dv + (K - K_lam) x] = 0."""
    data = model.createData()
    nv = model.nv
    args = (model, data, fid, RADIUS, axis, NORMALS["up"])
    J0, gap = contact_jacobian(*args, q0)
    assert abs(gap) < 1e-15
    assert_allclose(J0 @ v0, 0.0, atol=1e-15)
    K, C, M = pin.computeRNEADerivatives(model, data, q0, v0, np.zeros(nv))
    M = np.triu(M) + np.triu(M, 1).T
    tau0 = pin.rnea(model, data, q0, v0, np.zeros(nv))
    lam0 = np.linalg.lstsq(J0.T, tau0, rcond=None)[0]
    assert_allclose(J0.T @ lam0, tau0, atol=1e-12)  # steady: the contact force alone holds a = 0
    P0 = contact_velocity_derivative(*args, q0, v0)
    K_lam = contact_force_stiffness(*args, q0, lam0)
    B = scipy.linalg.null_space(J0)
    P = -np.linalg.pinv(J0) @ P0
    dv = np.hstack([P, B])
    rates = np.hstack([P - moving_frame_matrix(model, v0), B])  # x' = rates @ (x, u)
    forces = B.T @ (M @ P @ rates + C @ dv)
    forces[:, :nv] += B.T @ (K - K_lam)
    return np.vstack([rates, -np.linalg.solve(B.T @ M @ B, forces)]), lam0


def _disk_exponent(mass, diametral, axial, speed):
    """lambda of lean and heading: lambda^2 = (m g r A - C (C + m r^2) Omega^2) / (A (A + m r^2))."""
    omega = speed / RADIUS
    lam2 = (mass * 9.81 * RADIUS * diametral - axial * (axial + mass * RADIUS**2) * omega**2) / (
        diametral * (diametral + mass * RADIUS**2))
    return math.sqrt(lam2) if lam2 > 0 else 1j * math.sqrt(-lam2)


def _assert_exponents(eig, expected):
    """+-expected among eig to 1e-12 relative, every other exponent zero."""
    for target in (expected, -expected):
        assert np.min(abs(eig - target)) < 1e-12 * abs(target)
    assert np.all(np.sort(abs(eig))[:-2] < 1e-6)  # zeros: cyclic coordinates and the speed (defective: 1e-7)


@pytest.mark.parametrize("inertia, critical", [(UNIFORM, 1 / 3), (HOOP, 1 / 4)])
@pytest.mark.parametrize("ratio", [0.5, 0.9, 1.1, 3.0])
def test_rolling_disk_exponents(inertia, critical, ratio):
    """The classical rolling disk (e.g. Neimark and Fufaev, Dynamics of Nonholonomic Systems, 1972): lean
    and heading of a disk rolling upright at spin Omega = v / r have
    lambda^2 = (m g r A - C (C + m r^2) Omega^2) / (A (A + m r^2)): stable exactly for v^2 > g r / 3
    (uniform disk) and g r / 4 (hoop); all the other exponents are zero."""
    speed = math.sqrt(ratio * critical * 9.81 * RADIUS)
    model, fid, axis = _hinges(inertia)
    q0, v0 = np.array([0.0, 0.0, RADIUS, 0.0, 0.0, 1.0, 0.0]), np.array([speed, 0, 0, 0, 0, speed / RADIUS])
    system, lam0 = _rolling_system(model, fid, axis, q0, v0)
    assert_allclose(lam0, [0.0, 0.0, MASS * 9.81], atol=1e-12)  # the normal load, no friction needed
    expected = _disk_exponent(MASS, *inertia, speed)
    assert (expected.imag == 0) == (ratio < 1)
    _assert_exponents(np.linalg.eigvals(system), expected)


@pytest.mark.parametrize("speed", [0.5, 1.0, 2.0, 4.0])
def test_wheel_on_a_free_flyer_carrier(speed):
    """A free-flyer carrier (mass m_c, isotropic inertia I_c, no spin) holding a wheel on a continuous joint,
    the bicycle's layout: the disk's exponents with A + I_c and m + m_c (the carrier turns with the lean
    and the heading, not with the spin); the moving-frame term makes a turned wheel drift sideways at v."""
    m_c, I_c = 0.5, 0.01
    model = pin.Model()
    carrier = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "carrier")
    model.appendBodyToJoint(carrier, pin.Inertia(m_c, np.zeros(3), I_c * np.eye(3)), pin.SE3.Identity())
    A, C = UNIFORM
    wheel = model.addJoint(carrier, pin.JointModelRUBY(), pin.SE3.Identity(), "wheel")
    model.appendBodyToJoint(wheel, pin.Inertia(MASS, np.zeros(3), np.diag([A, C, A])), pin.SE3.Identity())
    q0 = pin.neutral(model)
    q0[2] = RADIUS
    v0 = np.array([speed, 0, 0, 0, 0, 0, speed / RADIUS])
    system, _ = _rolling_system(model, model.addJointFrame(wheel), (0.0, 1.0, 0.0), q0, v0)
    _assert_exponents(np.linalg.eigvals(system), _disk_exponent(MASS + m_c, A + I_c, C, speed))
    assert system[1, 5] == pytest.approx(speed, rel=1e-12)  # y' = v psi: from -A x alone


def test_examples_run():
    """The Examples sections of the module's docstrings, as the doctest runner sees them."""
    import doctest

    import pinlin
    import pinlin.model.constraints.rolling_contact as module

    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testmod(module, extraglobs={"np": np, "pinlin": pinlin}, optionflags=flags)
    assert result.failed == 0 and result.attempted >= 5
