"""Elements between frames: LinearSpringDamper and Bushing against independent computations.

References: Pinocchio's frame Jacobians and its fext derivative (through DeadWrench),
Pinocchio's log6, finite differences of the elements' potential energies, mpmath at
50 digits for the SE(3) log.  The closed-form mechanical cases are in
tests/reference/test_reference_frame_elements.py; check_element on every type in
tests/model/test_element_protocol.py.
"""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from helpers import mp_log6_jacobian
from pinlin.linearization.assembly import assemble
from pinlin.model.elements.se3 import log_expansion
from pinlin.model.evaluation import Evaluation
from pinlin.model.scene_file import load_scene

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


@pytest.fixture(scope="module")
def ur5():
    return pinlin.load_example("ur5")


@pytest.fixture(scope="module")
def q_ur5():
    return np.random.default_rng(5).uniform(-2.0, 2.0, 6)


def _kinematics(robot, q):
    model = robot.model
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    return model, data


def _stiffness(scene, q):
    return assemble(scene, scene.check_configuration(q), stiffness=True, damping=True)


# ----------------------------------------------------------------------------- spring-damper


def test_spring_damper_matches_spec_formula(ur5, q_ur5):
    """K = J_rel^T [k u u^T + (T/l)(I - u u^T)] J_rel + (dead-force term of T u at a, -T u at b), theory: elements between frames.

    J_rel from Pinocchio's frame Jacobians; the dead-force term from two DeadWrench
    elements, i.e. Pinocchio's fext derivative plus DeadWrench's correction.
    """
    k, c, l0 = 250.0, 3.0, 0.2
    spring = pinlin.LinearSpringDamper("tool0", "upper_arm_link", stiffness=k, damping=c, rest_length=l0)
    scene = pinlin.Scene(ur5, [spring], gravity=(0, 0, 0))
    model, data = _kinematics(ur5, q_ur5)
    fa, fb = ur5.frame_id("tool0"), ur5.frame_id("upper_arm_link")
    d = data.oMf[fb].translation - data.oMf[fa].translation
    l = np.linalg.norm(d)
    u = d / l
    T = k * (l - l0)
    J_rel = (pin.getFrameJacobian(model, data, fb, LWA) - pin.getFrameJacobian(model, data, fa, LWA))[:3]
    P = k * np.outer(u, u) + T / l * (np.eye(3) - np.outer(u, u))
    dead = pinlin.Scene(
        ur5, [pinlin.DeadWrench("tool0", force=T * u), pinlin.DeadWrench("upper_arm_link", force=-T * u)], gravity=(0, 0, 0)
    )
    asm = _stiffness(scene, q_ur5)
    assert_allclose(asm.K, J_rel.T @ P @ J_rel + _stiffness(dead, q_ur5).K, rtol=1e-12, atol=1e-12 * k)
    assert_allclose(asm.C, c * J_rel.T @ np.outer(u, u) @ J_rel, rtol=1e-12, atol=1e-12 * c)
    assert_allclose(-asm.residual, -J_rel.T @ (T * u), rtol=1e-12, atol=1e-12 * k)


def test_spring_force_is_the_gradient_of_its_energy(ur5, q_ur5):
    """Q = -dV/dq with V = k (l - l0)^2 / 2, by central differences of V on the manifold."""
    k, l0 = 120.0, 0.35
    spring = pinlin.LinearSpringDamper("wrist_2_link", (0.3, -0.2, 0.8), stiffness=k, rest_length=l0)
    scene = pinlin.Scene(ur5, [spring])
    fid = ur5.frame_id("wrist_2_link")

    def energy(q):
        _, data = _kinematics(ur5, q)
        return 0.5 * k * (np.linalg.norm(data.oMf[fid].translation - spring.target) - l0) ** 2

    h = 1e-6
    grad = [(energy(q_ur5 + h * e) - energy(q_ur5 - h * e)) / (2 * h) for e in np.eye(6)]
    Q = spring.generalized_force(Evaluation(scene, q_ur5, np.zeros(6)))
    assert_allclose(Q, -np.array(grad), rtol=1e-8, atol=1e-8 * np.abs(grad).max())


def test_zero_length_spring_through_coincident_points(ur5, q_ur5):
    """rest_length = 0: force k d, stiffness k J_rel^T J_rel, defined where the points coincide."""
    model, data = _kinematics(ur5, q_ur5)
    fid = ur5.frame_id("tool0")
    point = data.oMf[fid].translation.copy()
    spring = pinlin.LinearSpringDamper("tool0", point, stiffness=40.0)
    scene = pinlin.Scene(ur5, [spring, pinlin.RayleighDamping(0.0, 0.5)], gravity=(0, 0, 0))
    J = pin.getFrameJacobian(model, data, fid, LWA)[:3]
    asm = _stiffness(scene, q_ur5)
    assert_allclose(asm.K, 40.0 * J.T @ J, rtol=1e-12, atol=1e-12)
    assert_allclose(asm.C, 0.5 * 40.0 * J.T @ J, rtol=1e-12, atol=1e-12)  # Rayleigh: isotropic energy
    assert_allclose(asm.residual, 0.0, atol=1e-15)


@pytest.mark.parametrize(
    "rest, damping, match",
    [(0.5, 0.0, r"rest_length = 0.5 m"), (0.0, 2.0, r"damping = 2 N s/m")],
)
def test_coincident_points_have_no_direction(ur5, q_ur5, rest, damping, match):
    _, data = _kinematics(ur5, q_ur5)
    point = data.oMf[ur5.frame_id("tool0")].translation.copy()
    spring = pinlin.LinearSpringDamper("tool0", point, stiffness=40.0, damping=damping, rest_length=rest)
    scene = pinlin.Scene(ur5, [spring])
    with pytest.raises(pinlin.ConfigurationError, match=r"the two points coincide .*no direction.*" + match):
        pinlin.linearize(scene, q_ur5, balancing=True)


# ----------------------------------------------------------------------------- bushing


def _relative_jacobian(robot, q, frame, target):
    """J_r = J_a - Ad(aMb) J_b (LOCAL frame Jacobians) from Pinocchio."""
    model, data = _kinematics(robot, q)
    fa, fb = robot.frame_id(frame), robot.frame_id(target)
    Ja = pin.getFrameJacobian(model, data, fa, pin.LOCAL)
    Jb = pin.getFrameJacobian(model, data, fb, pin.LOCAL)
    aMb = data.oMf[fa].actInv(data.oMf[fb])
    return Ja - aMb.action @ Jb, data.oMf[fa], data.oMf[fb]


def test_bushing_at_zero_deflection(ur5, q_ur5):
    """e = 0 (offset = the current relative placement): K = J_r^T K6 J_r, C = J_r^T D6 J_r (theory: elements between frames)."""
    rng = np.random.default_rng(7)
    A = rng.normal(size=(6, 6))
    K6, D6 = A @ A.T + np.eye(6), np.diag([1.0, 2.0, 3.0, 0.1, 0.2, 0.3])
    Jr, oMa, oMb = _relative_jacobian(ur5, q_ur5, "tool0", "forearm_link")
    bushing = pinlin.Bushing("tool0", "forearm_link", stiffness=K6, damping=D6, offset=oMb.actInv(oMa))
    scene = pinlin.Scene(ur5, [bushing, pinlin.RayleighDamping(0.0, 0.1)], gravity=(0, 0, 0))
    asm = _stiffness(scene, q_ur5)
    assert_allclose(asm.residual, 0.0, atol=1e-12)
    assert_allclose(asm.K, Jr.T @ K6 @ Jr, rtol=1e-11, atol=1e-11 * np.abs(K6).max())
    assert_allclose(asm.C, Jr.T @ (D6 + 0.1 * K6) @ Jr, rtol=1e-11, atol=1e-11 * np.abs(K6).max())


def test_bushing_deflection_is_pinocchio_log6(ur5, q_ur5):
    """e = log6(O^-1 oMb^-1 oMa), compared with Pinocchio's log6 at a generic (large) deflection."""
    offset = pin.SE3(pin.rpy.rpyToMatrix(0.2, -0.5, 0.9), np.array([0.1, -0.3, 0.2]))
    bushing = pinlin.Bushing("tool0", "base_link", stiffness=np.ones(6), offset=offset)
    scene = pinlin.Scene(ur5, [bushing])
    _, oMa, oMb = _relative_jacobian(ur5, q_ur5, "tool0", "base_link")
    expected = pin.log6(offset.inverse() * oMb.actInv(oMa)).vector
    e = bushing.deflection(Evaluation(scene, q_ur5, np.zeros(6)))
    assert np.linalg.norm(e[3:]) > 1.0
    assert_allclose(e, expected, rtol=1e-12, atol=1e-12)


def test_bushing_force_is_the_gradient_of_its_energy(ur5, q_ur5):
    """Without damping the bushing is conservative: Q = -dV/dq, V = e^T K6 e / 2 with Pinocchio's log6."""
    rng = np.random.default_rng(8)
    A = rng.normal(size=(6, 6))
    K6 = A @ A.T + np.eye(6)
    target = pin.SE3(pin.rpy.rpyToMatrix(0.4, 0.1, -0.7), np.array([0.3, 0.2, 0.5]))
    bushing = pinlin.Bushing("wrist_3_link", target, stiffness=K6)
    scene = pinlin.Scene(ur5, [bushing])
    fid = ur5.frame_id("wrist_3_link")

    def energy(q):
        _, data = _kinematics(ur5, q)
        e = pin.log6(target.actInv(data.oMf[fid])).vector
        return 0.5 * e @ K6 @ e

    h = 1e-6
    grad = np.array([(energy(q_ur5 + h * e) - energy(q_ur5 - h * e)) / (2 * h) for e in np.eye(6)])
    Q = bushing.generalized_force(Evaluation(scene, q_ur5, np.zeros(6)))
    assert_allclose(Q, -grad, rtol=1e-7, atol=1e-7 * np.abs(grad).max())


# ----------------------------------------------------------------------------- the SE(3) log to second order


@pytest.mark.parametrize("angle", [3e-4, 1e-3, 0.5, 2.0])
def test_log_jacobian_against_mpmath(angle):
    """Our J_log (the series of se3.py) to 1e-14 everywhere, including the small angles where
    Pinocchio 4.1's Jlog6 loses up to 5e-7 (the reason the bushing does not use it)."""
    rng = np.random.default_rng(int(angle * 1e4))
    w = rng.normal(size=3)
    R = pin.exp3(angle * w / np.linalg.norm(w))
    p = rng.normal(size=3)
    J, _ = log_expansion(R, p, pin.log3(R))
    assert_allclose(J, mp_log6_jacobian(R, p), rtol=0, atol=1e-14)


@pytest.mark.parametrize("angle", [1e-7, 0.3, 1.5, 3.0])
def test_log_second_order_against_differences(angle):
    """E2 (second derivatives of log6(X exp xi)) against differences of Pinocchio's log6, symmetric."""
    rng = np.random.default_rng(3)
    w = rng.normal(size=3)
    X = pin.SE3(pin.exp3(angle * w / np.linalg.norm(w)), rng.normal(size=3))
    J, E2 = log_expansion(X.rotation, X.translation, pin.log3(X.rotation))
    h = 1e-4

    def e(xi):
        return pin.log6(X * pin.exp6(xi)).vector

    E2_fd = np.zeros((6, 6, 6))
    for i, ei in enumerate(np.eye(6) * h):
        for j, ej in enumerate(np.eye(6) * h):
            E2_fd[:, i, j] = (e(ei + ej) - e(ei - ej) - e(ej - ei) + e(-ei - ej)) / (4 * h * h)
    assert_allclose(E2, E2.transpose(0, 2, 1), atol=1e-14)
    assert_allclose(E2, E2_fd, rtol=1e-5, atol=1e-6)  # differences of log6 near pi: 1e-6 truncation


# ----------------------------------------------------------------------------- groups, calls, Rayleigh


def test_calls_and_rayleigh_closed_form():
    """Elastic pendulum with Rayleigh damping: D = alpha m I + beta k u u^T (u vertical);
    the elements need frame kinematics only (no kinematic Hessian, no extra algorithm)."""
    k, m, l0, alpha, beta = 40.0, 1.3, 0.5, 0.3, 0.02
    urdf = f"""<robot name="p"><link name="base"/><link name="slide"/>
      <link name="bob"><inertial><mass value="{m}"/><inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="x" type="prismatic"><parent link="base"/><child link="slide"/><axis xyz="1 0 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint>
      <joint name="z" type="prismatic"><parent link="slide"/><child link="bob"/><axis xyz="0 0 1"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint></robot>"""
    robot = pinlin.load_urdf_string(urdf)
    spring = pinlin.LinearSpringDamper("bob", (0, 0, 0), stiffness=k, rest_length=l0)
    scene = pinlin.Scene(robot, [spring, pinlin.RayleighDamping(alpha, beta)])
    assert scene.needs == {"frame_kinematics", "mass_matrix"}
    sys = pinlin.linearize(scene, [0.0, -(l0 + m * 9.81 / k)])
    assert_allclose(sys.D, np.diag([alpha * m, alpha * m + beta * k]), rtol=1e-14)
    assert set(sys.calls) == {"computeGeneralizedGravityDerivatives", "crba", "computeJointJacobians", "updateFramePlacements"}


# ----------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: pinlin.LinearSpringDamper("tip", "base", stiffness=-1.0), r"LinearSpringDamper\('tip'\).stiffness: must be finite and >= 0"),
        (lambda: pinlin.LinearSpringDamper("tip", "base", stiffness=np.nan), r"stiffness: must be finite and >= 0, got nan"),
        (lambda: pinlin.LinearSpringDamper("tip", "base", stiffness=1.0, damping=np.inf), r"damping: must be finite"),
        (lambda: pinlin.LinearSpringDamper("tip", "base", stiffness=1.0, rest_length=-0.1), r"rest_length: must be finite and >= 0"),
        (lambda: pinlin.LinearSpringDamper("tip", "base", stiffness="stiff"), r"stiffness: expected a number"),
        (lambda: pinlin.LinearSpringDamper("tip", (1.0, 2.0), stiffness=1.0), r"target: expected 3 numbers"),
        (lambda: pinlin.LinearSpringDamper("tip", (0.0, np.nan, 0.0), stiffness=1.0), r"target: must be finite"),
        (lambda: pinlin.LinearSpringDamper(3, "base", stiffness=1.0), r"frame: expected a frame name"),
        (lambda: pinlin.LinearSpringDamper("tip", "tip", stiffness=1.0), r"target: is the frame itself"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=[[1.0, 2.0], [0.0, 1.0]]), r"Bushing\('tip'\).stiffness: a matrix must be symmetric"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=np.diag([1.0, 1, 1, 1, 1, -1])), r"stiffness: a matrix must be positive semi-definite"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=np.eye(6) + np.eye(6, k=1)), r"stiffness: a matrix must be symmetric"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=[1.0, 2.0, 3.0]), r"stiffness: expected 6 values \(translations, then rotations\)"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=5.0), r"stiffness: expected 6 values .* got shape \(\)"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=[1.0, 1, 1, 1, np.nan, 1]), r"stiffness: must be finite"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=np.ones(6), damping=[1.0, 1, 1, 1, 1, -1]), r"damping: must be non-negative"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=np.ones(6), offset=np.diag([1.0, 1.0, 2.0, 1.0])), r"offset: the 3x3 block is not a rotation"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=np.ones(6), offset=np.eye(3)), r"offset: expected a pin.SE3, a 4x4 homogeneous matrix .* got shape \(3, 3\)"),
        (lambda: pinlin.Bushing("tip", "base", stiffness=np.ones(6), offset={"xyz": (0, 0, 1), "ypr": (0, 0, 1)}), r"offset: unknown key 'ypr'"),
        (lambda: pinlin.Bushing("tip", np.ones((4, 4)), stiffness=np.ones(6)), r"target: the last row of a homogeneous matrix"),
        (lambda: pinlin.Bushing("tip", "tip", stiffness=np.ones(6)), r"target: is the frame itself"),
    ],
)
def test_bad_parameters(make, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        make()


def test_unknown_frames_and_unsupported_joints():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2))
    with pytest.raises(pinlin.FrameNotFoundError, match=r"unknown frame 'hand'.*'tip'"):
        pinlin.Scene(robot, [pinlin.LinearSpringDamper("hand", "tip", stiffness=1.0)])
    with pytest.raises(pinlin.FrameNotFoundError, match=r"unknown frame 'hand'"):
        pinlin.Scene(robot, [pinlin.Bushing("tip", "hand", stiffness=np.ones(6))])
    model = pin.Model()
    jid = model.addJoint(0, pin.JointModelSphericalZYX(), pin.SE3.Identity(), "ball")
    model.appendBodyToJoint(jid, pin.Inertia.FromSphere(1.0, 0.1), pin.SE3.Identity())
    model.addFrame(pin.Frame("bob", jid, 0, pin.SE3.Identity(), pin.FrameType.OP_FRAME))
    zyx = pinlin.Robot(model, "<zyx>")
    with pytest.raises(pinlin.ParameterError, match=r"joint 'ball' \(JointModelSphericalZYX\) moves frame 'bob'"):
        pinlin.Scene(zyx, [pinlin.LinearSpringDamper("bob", (0, 0, 1.0), stiffness=1.0)])


# ----------------------------------------------------------------------------- scene files

SCENE = """
[robot]
urdf = "double_pendulum.urdf"
[[spring_damper]]
frame = "tip"
target = [0.1, 0.0, 0.2]
stiffness = 100.0
damping = 1.0
rest_length = 0.5
[[spring_damper]]
frame = "tip"
target = "link1"
stiffness = 20.0
[[bushing]]
frame = "tip"
target = { xyz = [0.0, 0.0, -1.2], rpy = [0.0, 0.1, 0.0] }
stiffness = [1e4, 1e4, 1e4, 50.0, 50.0, 50.0]
damping = [10.0, 10.0, 10.0, 0.1, 0.1, 0.1]
offset = { xyz = [0.0, 0.0, 0.1] }
"""


def test_scene_file_tables(tmp_path):
    path = tmp_path / "frames.toml"
    path.write_text(SCENE, encoding="utf-8")
    scene = load_scene(path).scene
    s1, s2, b = scene.elements
    assert (s1.frame, s1.stiffness, s1.damping, s1.rest_length) == ("tip", 100.0, 1.0, 0.5)
    assert_allclose(s1.target, [0.1, 0.0, 0.2])
    assert (s2.target, s2.damping, s2.rest_length) == ("link1", 0.0, 0.0)
    assert_allclose(b.target[:3, 3], [0.0, 0.0, -1.2])
    assert_allclose(b.target[:3, :3], pin.rpy.rpyToMatrix(0.0, 0.1, 0.0))
    assert_allclose(np.diag(b.damping), [10.0, 10.0, 10.0, 0.1, 0.1, 0.1])
    assert_allclose(b.offset[:3, 3], [0.0, 0.0, 0.1])


@pytest.mark.parametrize(
    "old, new, match",
    [
        ('target = "link1"', "target = 3", r"\[spring_damper\[2\].target\] expected a frame name or a world point"),
        ('target = "link1"', 'target = "hand"', r"\[spring_damper\[2\]\] unknown frame 'hand'"),
        ("stiffness = 20.0", "stiffness = -20.0", r"\[spring_damper\[2\]\] LinearSpringDamper\('tip'\).stiffness: must be finite and >= 0"),
        ("stiffness = 20.0", "length = 20.0", r"\[spring_damper\[2\].length\] unknown key"),
        ("offset = { xyz = [0.0, 0.0, 0.1] }", "offset = { xyz = [0.0, 0.1] }", r"\[bushing\[1\].offset.xyz\] expected 3 finite numbers"),
        ("offset = { xyz = [0.0, 0.0, 0.1] }", "offset = { shift = 1 }", r"\[bushing\[1\].offset.shift\] unknown key"),
        ("offset = { xyz = [0.0, 0.0, 0.1] }", "offset = 2", r"\[bushing\[1\].offset\] expected a table"),
        ("stiffness = [1e4, 1e4, 1e4, 50.0, 50.0, 50.0]", "stiffness = [1.0, 2.0]", r"\[bushing\[1\]\] Bushing\('tip'\).stiffness: expected 6 values"),
    ],
)
def test_scene_file_errors_name_key_and_table(tmp_path, old, new, match):
    path = tmp_path / "bad.toml"
    assert SCENE.count(old) == 1
    path.write_text(SCENE.replace(old, new), encoding="utf-8")
    with pytest.raises(pinlin.SceneFileError, match=match):
        load_scene(path)


# ----------------------------------------------------------------------------- stacked kinematics and log


@pytest.mark.parametrize("count", [2, 40])  # few frames: read one by one; many: one conversion of data.oMf
def test_frame_placements_and_positions_read_from_pinocchio(ur5, q_ur5, count):
    """Evaluation.frame_homogeneous / frame_positions against Pinocchio's own placements, read-only, memoized."""
    scene = pinlin.Scene(ur5)
    model, data = _kinematics(ur5, q_ur5)
    ids = tuple(range(1, model.nframes))[:count]
    ev = Evaluation(scene, q_ur5, np.zeros(ur5.nv))
    H = ev.frame_homogeneous(ids)
    p = ev.frame_positions(ids)
    assert H.shape == (len(ids), 4, 4) and p.shape == (len(ids), 3)
    for k, f in enumerate(ids):
        assert_allclose(H[k], data.oMf[f].homogeneous, rtol=0, atol=1e-15)
        assert_allclose(p[k], data.oMf[f].translation, rtol=0, atol=1e-15)
    assert not H.flags.writeable and not p.flags.writeable
    assert ev.frame_homogeneous(ids) is H and ev.frame_positions(ids) is p


def test_stacked_log_expansion_against_log6_differences():
    """J_log and E2 computed for a stack of placements at once (the bushing group's use), each against
    Pinocchio's Jlog6 and central differences of its log6: the stacked products keep every axis apart."""
    rng = np.random.default_rng(11)
    angles = [0.0, 1e-7, 0.3, 1.5, 2.5, 3.0]  # nearer pi the differences of log6 lose more than 1e-6
    Xs = []
    for a in angles:
        w = rng.normal(size=3)
        Xs.append(pin.SE3(pin.exp3(a * w / np.linalg.norm(w)), rng.normal(size=3)))
    R = np.array([X.rotation for X in Xs])
    p = np.array([X.translation for X in Xs])
    J, E2 = log_expansion(R, p, np.array([pin.log3(r) for r in R]))
    assert J.shape == (6, 6, 6) and E2.shape == (6, 6, 6, 6)
    h = 1e-4
    for k, X in enumerate(Xs):
        if angles[k] >= 0.3:  # Pinocchio's Jlog6 is accurate away from small angles
            assert_allclose(J[k], pin.Jlog6(X), rtol=0, atol=1e-12)

        def e(xi, X=X):
            return pin.log6(X * pin.exp6(xi)).vector

        fd = np.zeros((6, 6, 6))
        for i, ei in enumerate(np.eye(6) * h):
            for j, ej in enumerate(np.eye(6) * h):
                fd[:, i, j] = (e(ei + ej) - e(ei - ej) - e(ej - ei) + e(-ei - ej)) / (4 * h * h)
        assert_allclose(E2[k], fd, rtol=1e-5, atol=1e-6)  # differences of log6 near pi: 1e-6 truncation
