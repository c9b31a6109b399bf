"""The element protocol (docs/elements.md): its worked example, and check_element on every element type.

check_element compares an element's analytic derivatives (what it adds to
linearize's K and C) with central differences of its generalized force on the
manifold; an element passes at <= 1e-6 at generic deflected configurations of ur5
and of a free-floating body, with and without preload.
"""

import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.linearization.assembly import assemble
from pinlin.model.elements.base import ElementGroup
from pinlin.model.evaluation import Evaluation
from pinlin.testing import check_element

DOCS = Path(__file__).resolve().parents[2] / "docs" / "elements.md"
#: Largest mismatch accepted (docs/elements.md): exact derivatives give about 1e-9.
TOL = 1e-6


def worked_example() -> dict:
    """Run the worked example of docs/elements.md as it stands; return its namespace."""
    text = DOCS.read_text(encoding="utf-8").split("## Worked example", 1)[1]
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    namespace: dict = {"__name__": "docs_elements_example"}
    exec(compile(code, str(DOCS), "exec"), namespace)  # noqa: S102 - our own documentation
    return namespace


def test_worked_example_runs_and_matches_closed_form():
    """k3 e^3 + k1 e = 1.5 (Cardano) and omega^2 = (k1 + 3 k3 e0^2) / I_zz."""
    ns = worked_example()
    k1, k3, tau, izz = 4.0, 30.0, 1.5, 0.05
    p, r = k1 / k3, -tau / k3  # e^3 + p e + r = 0, one real root (p > 0)
    disc = np.sqrt(r**2 / 4 + p**3 / 27)
    e0 = np.cbrt(-r / 2 + disc) + np.cbrt(-r / 2 - disc)
    assert_allclose(ns["eq"].q, [e0], rtol=1e-12)
    assert_allclose(ns["omega"], np.sqrt((k1 + 3 * k3 * e0**2) / izz), rtol=1e-12)
    assert ns["mismatch"] <= TOL
    spring = ns["spring"]
    assert spring.kind == "cubic_spring" and isinstance(spring, pinlin.Element)
    # deflected away from equilibrium, and with Rayleigh damping reading its elastic stiffness
    scene = pinlin.Scene(ns["robot"], [spring, pinlin.RayleighDamping(0.0, 0.1)], gravity=(0, 0, 0))
    assert check_element(spring, scene, [0.7]) <= TOL
    sys = pinlin.linearize(scene, [0.7], balancing=True)
    assert_allclose(sys.D, [[0.1 * (k1 + 3 * k3 * 0.7**2)]], rtol=1e-14)


def test_worked_example_bad_input():
    CubicJointSpring = worked_example()["CubicJointSpring"]
    with pytest.raises(pinlin.ParameterError, match=r"CubicJointSpring\('spin'\).k3: must be finite and >= 0"):
        CubicJointSpring("spin", k1=1.0, k3=-2.0)
    with pytest.raises(pinlin.ParameterError, match=r"\.rest: must be finite, got nan"):
        CubicJointSpring("spin", k1=1.0, k3=2.0, rest=np.nan)
    with pytest.raises(pinlin.ParameterError, match="expected a number"):
        CubicJointSpring("spin", k1="stiff", k3=2.0)
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2), free_flyer=True)
    with pytest.raises(pinlin.ParameterError, match="needs a 1-DOF joint with nq = 1, got JointModelFreeFlyer"):
        pinlin.Scene(robot, [CubicJointSpring("root_joint", 1.0, 1.0)])
    with pytest.raises(pinlin.JointNotFoundError, match="unknown joint 'knee'"):
        pinlin.Scene(robot, [CubicJointSpring("knee", 1.0, 1.0)])


def test_check_element_catches_a_wrong_derivative():
    CubicJointSpring = worked_example()["CubicJointSpring"]

    class Wrong(CubicJointSpring):
        def add_stiffness(self, ev, K):  # forgets the cubic term
            i, _ = self._deflection(ev)
            K[i, i] += self.k1

    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1))
    scene = pinlin.Scene(robot)
    assert check_element(Wrong("joint1", 4.0, 30.0), scene, [0.5]) > 0.5


def test_check_element_bad_input():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2))
    scene = pinlin.Scene(robot)
    spring = pinlin.JointSpring("joint1", 1.0)
    with pytest.raises(pinlin.ParameterError, match="element: expected a pinlin element"):
        check_element("spring", scene, [0.0, 0.0])
    with pytest.raises(pinlin.ParameterError, match="step: must be a positive number"):
        check_element(spring, scene, [0.0, 0.0], step=0.0)
    with pytest.raises(pinlin.ConfigurationError, match="v must be 2 finite numbers"):
        check_element(spring, scene, [0.0, 0.0], v=[1.0])
    with pytest.raises(pinlin.ConfigurationError, match="needs a full Pinocchio configuration of size nq = 2"):
        check_element(spring, scene, [0.0])


# ----------------------------------------------------------------------------- every element type


def spd(rng, n, scale):
    A = rng.normal(size=(n, n))
    return scale * (A @ A.T + n * np.eye(n)) / n


def ur5_case(preload: bool):
    """ur5 at a generic configuration; every element loaded (preload) or at rest at q."""
    rng = np.random.default_rng(12)
    robot = pinlin.load_example("ur5")
    q = rng.uniform(-2.5, 2.5, robot.nq)
    v = rng.normal(size=robot.nv)
    scene0 = pinlin.Scene(robot, gravity=(0, 0, 0))
    ev = pinlin.model.evaluation.Evaluation(scene0, q, np.zeros(robot.nv))
    tool, arm = (robot.frame_id(f) for f in ("tool0", "upper_arm_link"))
    length = np.linalg.norm(ev.frame_position(tool) - ev.frame_position(arm))
    relative = ev.frame_placement(arm).actInv(ev.frame_placement(tool))
    world = pin.SE3(pin.rpy.rpyToMatrix(0.3, 0.2, -0.4), np.array([0.2, 0.1, 0.6]))
    elements = [
        pinlin.JointSpring("elbow_joint", 30.0, rest=q[2] - (0.4 if preload else 0.0)),
        pinlin.JointDamper("wrist_1_joint", 0.7),
        pinlin.RayleighDamping(0.1, 0.02),
        pinlin.FollowerWrench("tool0", force=(3.0, -2.0, 1.0) if preload else (0, 0, 0), torque=(0.2, 0.1, -0.3)),
        pinlin.DeadWrench("wrist_2_link", force=(1.0, 2.0, -4.0), torque=(0.3, -0.2, 0.1) if preload else (0, 0, 0)),
        pinlin.LinearSpringDamper(
            "tool0", "upper_arm_link", stiffness=300.0, damping=4.0, rest_length=length * (0.7 if preload else 1.0)
        ),
        pinlin.LinearSpringDamper("forearm_link", (0.3, -0.4, 0.9), stiffness=80.0, damping=1.5, rest_length=0.2),
        pinlin.Bushing(
            "tool0", "upper_arm_link", stiffness=spd(rng, 6, 100.0), damping=spd(rng, 6, 1.0),
            offset=relative * (pin.exp6(rng.normal(size=6) * 0.3) if preload else pin.SE3.Identity()),
        ),
        pinlin.Bushing("wrist_3_link", world, stiffness=[200.0, 300.0, 400.0, 10.0, 20.0, 30.0], damping=[1.0] * 6),
    ]
    return pinlin.Scene(robot, elements), q, v


def free_body_case(preload: bool):
    """A free-floating two-link body (nq = 9, nv = 8) at a generic configuration."""
    rng = np.random.default_rng(21)
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, [0.6, 0.4], [1.2, 0.8]), free_flyer=True)
    # numpy's rng does not seed Pinocchio: unseeded, about 1 draw in 40 nearly straightens the chain, where the
    # tip-base spring's central differences lose digits to rounding (mismatch ~ 1/h)
    pin.seed(21)
    q = pin.randomConfiguration(robot.model, -2.0 * np.ones(robot.nq), 2.0 * np.ones(robot.nq))
    v = rng.normal(size=robot.nv)
    scene0 = pinlin.Scene(robot, gravity=(0, 0, 0))
    ev = pinlin.model.evaluation.Evaluation(scene0, q, np.zeros(robot.nv))
    tip, base = (robot.frame_id(f) for f in ("tip", "base"))
    length = np.linalg.norm(ev.frame_position(tip) - ev.frame_position(base))
    base_placement = ev.frame_placement(base)
    rest = pin.neutral(robot.model)[:7] if preload else q[:7]
    elements = [
        pinlin.JointSpring("root_joint", spd(rng, 6, 50.0), rest=rest),
        pinlin.JointSpring("joint2", 12.0, rest=0.3),
        pinlin.JointDamper("root_joint", [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]),
        pinlin.RayleighDamping(0.2, 0.05),
        pinlin.FollowerWrench("tip", force=(1.0, -2.0, 3.0), torque=(0.1, 0.2, -0.1) if preload else (0, 0, 0)),
        pinlin.DeadWrench("link1", force=(0.0, 0.0, -9.0), torque=(0.3, 0.0, -0.2) if preload else (0, 0, 0)),
        pinlin.LinearSpringDamper("tip", "base", stiffness=200.0, damping=3.0, rest_length=length * (0.6 if preload else 1.0)),
        pinlin.LinearSpringDamper("link1", (0.5, 0.5, 0.5), stiffness=40.0, damping=1.0, rest_length=0.3),
        pinlin.Bushing(
            "base", base_placement * (pin.exp6(rng.normal(size=6) * 0.4) if preload else pin.SE3.Identity()),
            stiffness=spd(rng, 6, 80.0), damping=spd(rng, 6, 0.5),
        ),
        pinlin.Bushing("tip", "link1", stiffness=[50.0, 60.0, 70.0, 2.0, 3.0, 4.0], damping=[0.5] * 6),
    ]
    return pinlin.Scene(robot, elements), q, v


CASES = {"ur5": ur5_case, "free_body": free_body_case}
KINDS = sorted({"spring", "damper", "rayleigh", "follower", "dead", "spring_damper", "bushing"})


@pytest.mark.parametrize("preload", [True, False], ids=["preload", "unloaded"])
@pytest.mark.parametrize("case", sorted(CASES))
def test_check_element_every_type(case, preload):
    scene, q, v = CASES[case](preload)
    assert sorted({e.kind for e in scene.elements}) == KINDS  # every built-in type is covered
    for element in scene.elements:
        assert check_element(element, scene, q) <= TOL, element
        if element.kind != "rayleigh":  # see below
            assert check_element(element, scene, q, v) <= TOL, element


def test_frame_elements_at_rest_length_are_unloaded():
    """'Without preload' really means no force: the spring at its length, the bushing at its offset."""
    for make in CASES.values():
        scene, q, _ = make(False)
        ev = pinlin.model.evaluation.Evaluation(scene, q, np.zeros(scene.model.nv))
        spring = next(e for e in scene.elements if e.kind == "spring_damper")
        bushing = next(e for e in scene.elements if e.kind == "bushing")
        assert np.linalg.norm(spring.generalized_force(ev)) < 1e-12
        assert np.linalg.norm(bushing.generalized_force(ev)) < 1e-12


def test_rayleigh_at_free_velocities_leaves_out_its_q_derivative():
    """The documented limit: -(alpha M(q) + beta K_e) v_free has a q-derivative RayleighDamping does not add.

    linearize never meets it (free velocities are zero at every operating point);
    check_element sees it at a v with free velocities.
    """
    scene, q, v = ur5_case(True)
    rayleigh = next(e for e in scene.elements if e.kind == "rayleigh")
    assert check_element(rayleigh, scene, q) <= TOL
    assert check_element(rayleigh, scene, q, v) > 1e-3


def test_element_classes_declare_the_protocol():
    scene, q, _ = ur5_case(True)
    allowed = {"frame_kinematics", "mass_matrix"}
    for element in scene.elements:
        assert isinstance(element.kind, str) and element.needs() <= allowed
        group = type(element).group((element,), scene.robot)
        assert isinstance(group, ElementGroup)
    assert scene.needs == allowed


# ----------------------------------------------------------------------------- groups and joints of frame elements


@pytest.fixture(scope="module")
def ur5():
    return pinlin.load_example("ur5")


@pytest.fixture(scope="module")
def q_ur5():
    return np.random.default_rng(5).uniform(-2.0, 2.0, 6)


def test_groups_equal_the_sum_of_their_elements(ur5, q_ur5):
    """The vectorized groups give what the elements give one by one (force, K, C, elastic K)."""
    rng = np.random.default_rng(9)
    frames = ["shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link", "tool0"]
    elements = [
        pinlin.LinearSpringDamper(a, b, stiffness=rng.uniform(10, 100), damping=rng.uniform(0, 2), rest_length=rng.uniform(0, 0.3))
        for a, b in zip(frames, frames[2:] + ["base_link", "base_link"])
    ] + [
        pinlin.Bushing(a, b, stiffness=rng.uniform(1, 10, 6), damping=rng.uniform(0, 1, 6))
        for a, b in (("tool0", "upper_arm_link"), ("wrist_1_link", "shoulder_link"))
    ]
    scene = pinlin.Scene(ur5, elements, prescribed={"shoulder_pan_joint": 1.3})
    ev = Evaluation(scene, q_ur5, scene.v0)
    for cls in (pinlin.LinearSpringDamper, pinlin.Bushing):
        members = tuple(e for e in elements if isinstance(e, cls))
        group = cls.group(members, ur5)
        for method in ("add_stiffness", "add_damping", "add_elastic_stiffness"):
            together, alone = np.zeros((6, 6)), np.zeros((6, 6))
            getattr(group, method)(ev, together)
            for e in members:
                getattr(e, method)(ev, alone)
            assert_allclose(together, alone, rtol=1e-13, atol=1e-13 * np.abs(alone).max())
        Q = np.zeros(6)
        group.add_force(ev, Q)
        assert_allclose(Q, sum(e.generalized_force(ev) for e in members), rtol=1e-13, atol=1e-13)


def test_groups_shared_by_threads(ur5):
    """The groups keep their last evaluation's geometry; threads sharing a scene must never mix them."""
    from concurrent.futures import ThreadPoolExecutor

    rng = np.random.default_rng(11)
    elements = [
        pinlin.LinearSpringDamper("tool0", "upper_arm_link", stiffness=200.0, damping=2.0, rest_length=0.3),
        pinlin.Bushing("wrist_1_link", "shoulder_link", stiffness=[50.0, 60, 70, 5, 6, 7], damping=[1.0] * 6),
    ]
    scene = pinlin.Scene(ur5, elements)
    points = [rng.uniform(-2, 2, 6) for _ in range(8)]
    expected = [assemble(scene, scene.check_configuration(q), stiffness=True, damping=True) for q in points]

    def work(i):
        asm = assemble(scene, points[i % len(points)], stiffness=True, damping=True)
        return i, asm.K, asm.C, asm.residual

    with ThreadPoolExecutor(max_workers=4) as pool:
        for i, K, C, r in pool.map(work, range(64)):
            ref = expected[i % len(points)]
            assert_allclose(K, ref.K, rtol=1e-13, atol=1e-12)
            assert_allclose(C, ref.C, rtol=1e-13, atol=1e-12)
            assert_allclose(r, ref.residual, rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize(
    "joint", [pin.JointModelSpherical(), pin.JointModelPlanar(), pin.JointModelTranslation(), pin.JointModelFreeFlyer()],
    ids=lambda j: j.shortname(),
)
def test_multi_dof_joints_follow_the_derivative_rule(joint):
    """d xi_k/dq_l = [xi_l, xi_k] within a multi-DOF joint too (frame_pairs): check_element on each accepted type."""
    model = pin.Model()
    j1 = model.addJoint(0, joint, pin.SE3(np.eye(3), np.array([0.1, 0.2, 0.3])), "j1")
    model.appendBodyToJoint(j1, pin.Inertia(2.0, np.array([0.1, 0.0, 0.05]), np.diag([0.1, 0.2, 0.3])), pin.SE3.Identity())
    j2 = model.addJoint(j1, pin.JointModelRY(), pin.SE3(pin.rpy.rpyToMatrix(0.2, 0.1, 0.3), np.array([0.4, 0.0, 0.1])), "j2")
    model.appendBodyToJoint(j2, pin.Inertia(1.0, np.zeros(3), np.diag([0.1, 0.1, 0.1])), pin.SE3.Identity())
    model.addFrame(pin.Frame("a", j1, 0, pin.SE3(np.eye(3), np.array([0.2, -0.1, 0.05])), pin.FrameType.OP_FRAME))
    model.addFrame(pin.Frame("b", j2, 0, pin.SE3(pin.rpy.rpyToMatrix(0.3, -0.2, 0.1), np.array([0.3, 0.1, -0.2])), pin.FrameType.OP_FRAME))
    robot = pinlin.Robot(model, "<multi-dof>")
    rng = np.random.default_rng(4)
    q = pin.integrate(model, pin.neutral(model), rng.uniform(-1.0, 1.0, model.nv))
    v = rng.normal(size=model.nv)
    world = pin.SE3(pin.rpy.rpyToMatrix(0.5, 0.2, -0.3), np.array([0.4, 0.3, -0.2]))
    elements = [
        pinlin.LinearSpringDamper("b", (0.5, 0.5, 0.5), stiffness=100.0, damping=2.0, rest_length=0.1),
        pinlin.LinearSpringDamper("a", (-0.3, 0.2, 0.6), stiffness=80.0, damping=1.0, rest_length=0.2),
        pinlin.Bushing("b", "a", stiffness=[10.0, 20, 30, 1, 2, 3], damping=[1.0] * 6, offset=world),
        pinlin.Bushing("a", world, stiffness=[10.0, 20, 30, 1, 2, 3], damping=[1.0] * 6),
    ]
    scene = pinlin.Scene(robot, elements)
    for element in elements:
        assert pinlin.testing.check_element(element, scene, q) <= 1e-6, element
        assert pinlin.testing.check_element(element, scene, q, v) <= 1e-6, element
