"""Elements: their forces and derivatives against closed forms, and their bad input."""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from helpers import fd_jacobians, rel_err
from pinlin.linearization.assembly import assemble


@pytest.fixture(scope="module")
def chain3():
    return pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3, damping=[0.1, 0.2, 0.3]))


def test_urdf_damping_is_opt_in(chain3):
    q = np.zeros(3)
    off = pinlin.linearize(pinlin.Scene(chain3), q)
    assert off.is_zero("D")
    on = pinlin.linearize(pinlin.Scene(chain3, urdf_damping=True), q)
    assert_allclose(on.D, np.diag([0.1, 0.2, 0.3]), rtol=1e-15)
    assert sum(e.kind == "damper" for e in pinlin.Scene(chain3, urdf_damping=True).elements) == 3


def test_rayleigh_damping_closed_form(chain3):
    springs = [pinlin.JointSpring(f"joint{i}", k) for i, k in zip((1, 2, 3), (5.0, 7.0, 11.0))]
    scene = pinlin.Scene(chain3, springs + [pinlin.RayleighDamping(alpha=0.3, beta=0.02)])
    sys = pinlin.linearize(scene, np.zeros(3))
    assert_allclose(sys.D, 0.3 * sys.M + 0.02 * np.diag([5.0, 7.0, 11.0]), rtol=1e-14)


def test_rayleigh_skips_prescribed_joints():
    robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf(2.0))
    scene = pinlin.Scene(
        robot, [pinlin.JointSpring("x", 10.0), pinlin.RayleighDamping(0.5, 0.1)], prescribed={"ring": 1.0}
    )
    sys = pinlin.linearize(scene, scene.neutral())
    assert_allclose(sys.D, np.diag([0.5 * 2.0 + 0.1 * 10.0, 0.5 * 2.0]), rtol=1e-14)
    assert "crba" not in sys.calls  # M came from the RNEA derivative pass


def test_spring_rest_and_force(chain3):
    scene = pinlin.Scene(chain3, [pinlin.JointSpring("joint2", 4.0, rest=0.25)], gravity=(0, 0, 0))
    r = pinlin.equilibrium_residual(scene, [0.0, 1.0, 0.0])
    assert_allclose(r, [0.0, 4.0 * 0.75, 0.0], atol=1e-15)
    eq = pinlin.find_equilibrium(scene)
    assert_allclose(eq.q, [0.0, 0.25, 0.0], atol=1e-14)


def test_spherical_joint_spring_derivative_off_rest():
    text = """<robot name="ball"><link name="base"/>
      <link name="bob"><inertial><mass value="1"/><origin xyz="0 0 -0.4"/>
        <inertia ixx="0.02" iyy="0.03" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="ball" type="floating"><parent link="base"/><child link="bob"/></joint></robot>"""
    base = pinlin.load_urdf_string(text)
    # build a spherical joint model directly: URDF has no spherical joint type
    model = pin.Model()
    jid = model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    model.appendBodyToJoint(jid, base.model.inertias[1], pin.SE3.Identity())
    model.addFrame(pin.Frame("bob", jid, 0, pin.SE3(np.eye(3), np.array([0, 0, -0.4])), pin.FrameType.OP_FRAME))
    robot = pinlin.Robot(model, "<spherical>")
    Ks = np.array([[30.0, 2.0, 0.0], [2.0, 20.0, 1.0], [0.0, 1.0, 10.0]])
    rest = pin.Quaternion(pin.utils.rpyToMatrix(0.1, -0.2, 0.3)).coeffs()
    scene = pinlin.Scene(robot, [pinlin.JointSpring("ball", Ks, rest=rest), pinlin.JointDamper("ball", [0.1, 0.2, 0.3])])
    q = pin.normalize(model, np.array([0.3, -0.1, 0.2, 0.9]))
    asm = assemble(scene, q, stiffness=True, damping=True)
    K_fd, C_fd = fd_jacobians(scene, q)
    assert rel_err(asm.K, K_fd) < 1e-6
    assert_allclose(asm.C, np.diag([0.1, 0.2, 0.3]), rtol=1e-15)
    # at rest the spring's stiffness is exactly Ks
    at_rest = pinlin.Scene(robot, [pinlin.JointSpring("ball", Ks, rest=rest)], gravity=(0, 0, 0))
    assert_allclose(pinlin.linearize(at_rest, rest).S, Ks, rtol=1e-12)


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: pinlin.JointSpring("j", -1.0), r"JointSpring\('j'\).stiffness: must be non-negative"),
        (lambda: pinlin.JointSpring("j", np.nan), "must be finite"),
        (lambda: pinlin.JointSpring("j", "stiff"), "expected a number"),
        (lambda: pinlin.JointSpring("j", [[1.0, 2.0], [0.0, 1.0]]), "must be symmetric"),
        (lambda: pinlin.JointSpring("j", [[1.0, 2.0], [2.0, 1.0]]), "positive semi-definite"),
        (lambda: pinlin.JointSpring("j", 1.0, rest=np.inf), "rest: must be finite"),
        (lambda: pinlin.JointDamper("j", -0.1), r"JointDamper\('j'\).damping: must be non-negative"),
        (lambda: pinlin.RayleighDamping(alpha=-1.0), "RayleighDamping.alpha: must be finite and >= 0"),
        (lambda: pinlin.RayleighDamping(beta=np.inf), "RayleighDamping.beta"),
        (lambda: pinlin.RayleighDamping(alpha="x"), "expected a number"),
        (lambda: pinlin.FollowerWrench("tip", force=(1.0, 2.0)), r"FollowerWrench\('tip'\).force: expected 3 numbers"),
        (lambda: pinlin.DeadWrench("tip", torque=(0, np.nan, 0)), r"DeadWrench\('tip'\).torque: must be finite"),
    ],
)
def test_element_parameters(make, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        make()


def test_elements_checked_against_robot(chain3):
    with pytest.raises(pinlin.JointNotFoundError, match=r"unknown joint 'knee'.*'joint1', 'joint2', 'joint3'"):
        pinlin.Scene(chain3, [pinlin.JointSpring("knee", 1.0)])
    with pytest.raises(pinlin.FrameNotFoundError, match=r"unknown frame 'hand'.*'tip'"):
        pinlin.Scene(chain3, [pinlin.FollowerWrench("hand", force=(1, 0, 0))])
    with pytest.raises(pinlin.ParameterError, match=r"expected a number, 1 values or a 1x1 matrix, got shape \(2,\)"):
        pinlin.Scene(chain3, [pinlin.JointSpring("joint1", [1.0, 2.0])])
    with pytest.raises(pinlin.ParameterError, match="needs a rest of 1 value"):
        pinlin.Scene(chain3, [pinlin.JointSpring("joint1", 1.0, rest=[0.0, 1.0])])
    with pytest.raises(pinlin.ParameterError, match=r"elements\[1\]: expected a pinlin element"):
        pinlin.Scene(chain3, [pinlin.JointSpring("joint1", 1.0), "spring"])


def test_scene_parameters(chain3):
    with pytest.raises(pinlin.ParameterError, match="robot: expected a pinlin.Robot"):
        pinlin.Scene("chain.urdf")
    with pytest.raises(pinlin.ParameterError, match="gravity: expected 3 numbers"):
        pinlin.Scene(chain3, gravity=(0, -9.81))
    with pytest.raises(pinlin.ParameterError, match="gravity: must be finite"):
        pinlin.Scene(chain3, gravity=(0, 0, np.nan))
    with pytest.raises(pinlin.ParameterError, match=r"prescribed\['joint1'\]: must be finite"):
        pinlin.Scene(chain3, prescribed={"joint1": np.inf})
    with pytest.raises(pinlin.JointNotFoundError, match="unknown joint 'motor'"):
        pinlin.Scene(chain3, prescribed={"motor": 1.0})
    with pytest.raises(pinlin.PrescribedJointError, match="every joint is prescribed"):
        pinlin.Scene(chain3, prescribed={"joint1": 1.0, "joint2": 1.0, "joint3": 1.0})


def test_prescribed_multi_dof_joint():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2), free_flyer=True)
    with pytest.raises(pinlin.PrescribedJointError, match="'root_joint' is a JointModelFreeFlyer with 6 degrees"):
        pinlin.Scene(robot, prescribed={"root_joint": 1.0})


def test_scene_replace(chain3):
    scene = pinlin.Scene(chain3, [pinlin.JointSpring("joint1", 2.0)])
    other = scene.replace(gravity=(0, 0, 0))
    assert not other.has_gravity and scene.has_gravity
    assert other.elements == scene.elements
    with pytest.raises(pinlin.ParameterError, match="unknown scene arguments"):
        scene.replace(colour="red")
