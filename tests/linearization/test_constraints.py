"""Constraints: Jacobians and constraint stiffness by finite differences, assembly, KKT equilibrium,
coordinates, contacts and every bad-input path (theory: constraints)."""

import math

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from constrained_cases import BUNDLED
from helpers import rel_err
from pinlin.linearization.constraint_set import evaluate_constraints
from pinlin.model.constraints import dead_wrench_stiffness

G = 9.81


@pytest.fixture(scope="module")
def four_bar():
    return pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))


@pytest.fixture(scope="module")
def four_bar_scene(four_bar):
    spring = pinlin.JointSpring("crank_joint", 50.0, rest=0.2)
    return pinlin.Scene(four_bar, [spring], constraints=[pinlin.PointConstraint("rocker_tip", (0.7, 0, 0), name="loop")])


def _fd_tangent(f, model, q, h=1e-6):
    """Central differences of f(q) along each tangent direction (pin.integrate)."""
    cols = []
    for e in np.eye(model.nv):
        cols.append((f(pin.integrate(model, q, h * e)) - f(pin.integrate(model, q, -h * e))) / (2 * h))
    return np.column_stack(cols)


def _branchy_robot():
    """A free-flyer with a spherical joint, a planar joint and an unaligned revolute: every supported kind."""
    model = pin.Model()
    rng = np.random.default_rng(5)
    ff = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "base")
    model.appendBodyToJoint(ff, pin.Inertia.Random(), pin.SE3.Identity())
    s = model.addJoint(ff, pin.JointModelSpherical(), pin.SE3(np.eye(3), np.array([0.2, 0.0, -0.1])), "ball")
    model.appendBodyToJoint(s, pin.Inertia.Random(), pin.SE3.Identity())
    p = model.addJoint(s, pin.JointModelPlanar(), pin.SE3(np.eye(3), np.array([0.3, 0.1, -0.5])), "plane")
    model.appendBodyToJoint(p, pin.Inertia.Random(), pin.SE3.Identity())
    axis = np.array([0.3, 0.5, 0.8]) / np.linalg.norm([0.3, 0.5, 0.8])
    r = model.addJoint(p, pin.JointModelRevoluteUnaligned(axis), pin.SE3(np.eye(3), np.array([0.2, 0.1, -0.4])), "hinge")
    model.appendBodyToJoint(r, pin.Inertia.Random(), pin.SE3.Identity())
    placement = pin.SE3(pin.rpy.rpyToMatrix(*rng.normal(size=3)), np.array([0.1, 0.2, -0.3]))
    model.addFrame(pin.Frame("tip", r, placement, pin.FrameType.OP_FRAME))
    model.addFrame(pin.Frame("arm", s, pin.SE3(np.eye(3), np.array([0.0, 0.4, 0.1])), pin.FrameType.OP_FRAME))
    return pinlin.Robot(model, "<branchy>")


# ----------------------------------------------------------------------------- Jacobians, K_lambda


@pytest.mark.parametrize("kind", ["point-world", "point-frame", "frame-world", "frame-frame"])
def test_jacobians_and_constraint_stiffness_match_finite_differences(kind):
    robot = _branchy_robot()
    rng = np.random.default_rng(11)
    H = pin.SE3(pin.rpy.rpyToMatrix(*rng.normal(size=3)), rng.normal(size=3)).homogeneous
    constraint = {
        "point-world": pinlin.PointConstraint("tip", (0.3, -0.2, 0.1)),
        "point-frame": pinlin.PointConstraint("tip", "arm"),
        "frame-world": pinlin.FrameConstraint("tip", H),
        "frame-frame": pinlin.FrameConstraint("tip", "arm"),
    }[kind]
    scene = pinlin.Scene(robot, constraints=[constraint], gravity=(0, 0, 0))
    q = pin.integrate(robot.model, robot.neutral(), rng.normal(size=robot.nv))
    state = evaluate_constraints(scene, q, closure=True)
    # dPhi/dq exactly, by central differences on the manifold
    J_fd = _fd_tangent(lambda x: evaluate_constraints(scene, x).phi, robot.model, q)
    assert rel_err(state.J_closure, J_fd) < 1e-8
    if kind.startswith("point"):
        assert_allclose(state.J, state.J_closure, atol=0)
    # K_lambda = d(J_c^T lambda)/dq at fixed lambda
    lam = rng.normal(size=constraint.size) * 10
    K_fd = _fd_tangent(lambda x: evaluate_constraints(scene, x).J.T @ lam, robot.model, q)
    assert rel_err(pinlin.constraint_stiffness(scene, q, lam), K_fd) < 1e-8


def test_frame_constraint_velocity_form_is_dphi_on_the_manifold():
    robot = _branchy_robot()
    rng = np.random.default_rng(2)
    q = pin.integrate(robot.model, robot.neutral(), rng.normal(size=robot.nv))
    data = robot.model.createData()
    pin.framesForwardKinematics(robot.model, data, q)
    target = data.oMf[robot.frame_id("tip")].homogeneous  # satisfied at q
    scene = pinlin.Scene(robot, constraints=[pinlin.FrameConstraint("tip", target)])
    state = evaluate_constraints(scene, q, closure=True)
    assert np.abs(state.phi).max() < 1e-12
    assert_allclose(state.J, state.J_closure, atol=1e-12)


def test_dead_wrench_stiffness_of_no_wrench_is_zero():
    before = np.ones((3, 3), dtype=bool)
    assert not dead_wrench_stiffness(np.zeros((0, 6, 3)), np.zeros((0, 3)), None, before).any()


# ----------------------------------------------------------------------------- assembly


def test_close_loops_from_an_open_chain(four_bar_scene):
    result = pinlin.close_loops(four_bar_scene, [0.3, 0.2, -0.4])
    assert result.initial_gap > 0.1 and result.gap <= 1e-12 and result.iterations <= 10
    state = evaluate_constraints(four_bar_scene, result.q)
    assert np.abs(state.phi).max() < 1e-12
    assert result.error == result.gap and set(result.to_dict()) >= {"method", "error", "elapsed", "q", "gap"}


def test_close_loops_holds_the_input_joint(four_bar_scene):
    theta = math.radians(100)
    q0 = BUNDLED.joints(math.radians(90))
    q0[0] = theta - BUNDLED.theta_ref
    result = pinlin.close_loops(four_bar_scene, q0, hold=["crank_joint"])
    assert result.q[0] == q0[0]
    assert_allclose(result.q, BUNDLED.joints(theta), atol=1e-10)


def test_unreachable_target_says_by_how_many_metres():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, length=1.0))
    scene = pinlin.Scene(robot, constraints=[pinlin.PointConstraint("tip", (0.0, 0.0, -3.0), name="anchor")])
    with pytest.raises(pinlin.AssemblyError, match=r"gap of 2(\.0*\d*)? m at constraint 'anchor'") as info:
        pinlin.close_loops(scene, [0.3, 0.2])
    assert_allclose(info.value.gap, 2.0, rtol=1e-5)  # the chain (length 1) stretched toward the point
    assert isinstance(info.value, pinlin.ConstraintViolationError) and info.value.constraints == ("anchor",)
    with pytest.raises(pinlin.AssemblyError, match="gap of 2"):
        pinlin.find_equilibrium(scene, [0.3, 0.2])


def test_close_loops_bad_input(four_bar_scene, four_bar):
    with pytest.raises(pinlin.ParameterError, match="has no constraints"):
        pinlin.close_loops(pinlin.Scene(four_bar), np.zeros(3))
    with pytest.raises(pinlin.ParameterError, match="tol"):
        pinlin.close_loops(four_bar_scene, np.zeros(3), tol=-1.0)
    with pytest.raises(pinlin.JointNotFoundError, match="unknown joint 'crank'"):
        pinlin.close_loops(four_bar_scene, np.zeros(3), hold=["crank"])
    with pytest.raises(pinlin.ConfigurationError, match="nq = 3"):
        pinlin.close_loops(four_bar_scene, np.zeros(2))


# ----------------------------------------------------------------------------- equilibrium


def test_equilibrium_reports_assembly_forces_and_redundancy(four_bar_scene):
    eq = pinlin.find_equilibrium(four_bar_scene, [0.3, 0.2, -0.4])
    assert eq.error < 1e-12 and eq.constraint_gap < 1e-12
    assert eq.notes[0].startswith("assembly step: q0 violated the constraints by")
    assert eq.assembly.initial_gap > 0.1 and eq.redundant == 1
    assert any("minimum-norm" in n for n in eq.notes) and eq.method.startswith("newton-kkt")
    (force,) = eq.constraint_forces
    assert force.constraint == "loop" and force.torque is None
    assert force.force[1] == pytest.approx(0.0, abs=1e-12)  # minimum norm: nothing out of the plane
    # the force balances the tree: r(q) = J_c^T lambda
    r = pinlin.equilibrium_residual(four_bar_scene, eq.q)
    J = evaluate_constraints(four_bar_scene, eq.q).J
    assert_allclose(r, J.T @ force.force, atol=1e-12 * np.abs(r).max())
    d = eq.to_dict()
    assert d["constraint_forces"][0]["constraint"] == "loop" and d["redundant"] == 1


def test_equilibrium_without_assembly_has_no_assembly_note(four_bar_scene):
    eq = pinlin.find_equilibrium(four_bar_scene, BUNDLED.joints(math.radians(80)))
    assert not any(n.startswith("assembly") for n in eq.notes)


def test_equilibrium_no_convergence_is_reported(four_bar_scene):
    with pytest.raises(pinlin.ConvergenceError, match="no convergence in 1 iteration "):
        pinlin.find_equilibrium(four_bar_scene, [0.3, 0.2, -0.4], max_iterations=1)
    with pytest.raises(pinlin.ParameterError, match="max_iterations"):
        pinlin.find_equilibrium(four_bar_scene, np.zeros(3), max_iterations=-1)


# ----------------------------------------------------------------------------- linearize


def test_linearized_constrained_system(four_bar_scene):
    eq = pinlin.find_equilibrium(four_bar_scene, np.zeros(3))
    sys = pinlin.linearize(four_bar_scene, eq.q)
    J = evaluate_constraints(four_bar_scene, eq.q).J
    assert sys.n == 1 and sys.basis.shape == (3, 1) and np.abs(J @ sys.basis).max() < 1e-14
    assert sys.basis_names == four_bar_scene.dof_names
    assert sys.dof_names[0] in four_bar_scene.dof_names
    assert sys.basis[four_bar_scene.dof_names.index(sys.dof_names[0]), 0] == 1.0
    assert sys.basis_condition >= 1.0 and sys.constraint_forces[0].constraint == "loop"
    assert sys.calls[:2] == ("computeJointJacobians", "updateFramePlacements")
    assert_allclose(sys.expand(np.array([2.0])), 2 * sys.basis[:, 0])
    assert sys.expand(np.ones((1, 4))).shape == (3, 4)
    with pytest.raises(pinlin.ParameterError, match="first axis has length n = 1"):
        sys.expand(np.ones(3))
    d = sys.to_dict()
    assert len(d["basis"]) == 3 and d["constraint_forces"][0]["constraint"] == "loop"
    assert "basis=3x1" in repr(sys)


def test_every_coordinate_choice_gives_the_same_frequency(four_bar_scene):
    eq = pinlin.find_equilibrium(four_bar_scene, np.zeros(3))
    choices = [None, ["crank_joint"], ["coupler_joint"], ["rocker_joint"], "orthonormal"]
    omega2 = [s.K[0, 0] / s.M[0, 0] for s in (pinlin.linearize(four_bar_scene, eq.q, coordinates=c) for c in choices)]
    assert_allclose(omega2, omega2[0], rtol=1e-12)


def test_unconstrained_scene_has_no_basis_and_refuses_coordinates(four_bar):
    scene = pinlin.Scene(four_bar, [pinlin.JointSpring("crank_joint", 5.0)])
    sys = pinlin.linearize(scene, np.zeros(3), balancing=True)
    assert sys.basis is None and sys.constraint_forces == () and sys.basis_condition is None
    assert "computeJointJacobians" not in sys.calls
    assert_allclose(sys.expand(np.ones(3)), np.ones(3))
    with pytest.raises(pinlin.ParameterError, match="coordinates: applies to scenes with constraints only"):
        pinlin.linearize(scene, np.zeros(3), coordinates=["crank_joint"])


def test_constraint_stiffness_is_subtracted(four_bar_scene):
    """K_z = B^T (K - K_lambda) B with K the tree's stiffness (the unconstrained assembly)."""
    from pinlin.linearization.assembly import assemble

    q = pinlin.find_equilibrium(four_bar_scene, np.zeros(3)).q
    sys = pinlin.linearize(four_bar_scene, q)
    lam = sys.constraint_forces[0].force
    K = assemble(four_bar_scene, q).K
    B = sys.basis
    assert_allclose(sys.K, B.T @ (K - pinlin.constraint_stiffness(four_bar_scene, q, lam)) @ B, rtol=1e-12)


# ----------------------------------------------------------------------------- bad input


def test_unknown_frames(four_bar):
    with pytest.raises(pinlin.FrameNotFoundError, match="unknown frame 'toe'.*'rocker_tip'"):
        pinlin.Scene(four_bar, constraints=[pinlin.PointConstraint("toe", (0, 0, 0))])
    with pytest.raises(pinlin.FrameNotFoundError, match="unknown frame 'nowhere'"):
        pinlin.Scene(four_bar, constraints=[pinlin.FrameConstraint("rocker_tip", "nowhere")])


def test_linearize_at_a_violating_configuration(four_bar_scene):
    q = BUNDLED.joints(math.radians(80)) + np.array([0.0, 0.0, 0.01])
    with pytest.raises(pinlin.ConstraintViolationError, match=r"'loop' is open by 0\.00\d+ m") as info:
        pinlin.linearize(four_bar_scene, q)
    assert 0.001 < info.value.gap < 0.01 and info.value.constraints == ("loop",)
    assert isinstance(info.value, pinlin.InputError)


def test_not_an_equilibrium_with_constraints(four_bar_scene):
    q = BUNDLED.joints(math.radians(80))
    with pytest.raises(pinlin.NotAnEquilibriumError, match="r - J_c\\^T lambda.*balancing=True"):
        pinlin.linearize(four_bar_scene, q)
    sys = pinlin.linearize(four_bar_scene, q, balancing=True)
    assert sys.balancing.shape == (1,) and any("minimum-norm joint forces" in n for n in sys.notes)


def test_bad_coordinates(four_bar_scene):
    q = pinlin.find_equilibrium(four_bar_scene, np.zeros(3)).q
    with pytest.raises(pinlin.ParameterError, match=r"give 2 degree\(s\) of freedom; the constraints leave n = .* = 1"):
        pinlin.linearize(four_bar_scene, q, coordinates=["crank_joint", "rocker_joint"])
    with pytest.raises(pinlin.JointNotFoundError, match="unknown joint 'knee' in coordinates"):
        pinlin.linearize(four_bar_scene, q, coordinates=["knee"])
    with pytest.raises(pinlin.ParameterError, match="'orthonormal' or a list of joint names, got 'qr'"):
        pinlin.linearize(four_bar_scene, q, coordinates="qr")
    with pytest.raises(pinlin.ParameterError, match="twice"):
        pinlin.linearize(four_bar_scene, q, coordinates=["crank_joint", "crank_joint"])


def test_coordinates_that_cannot_drive_the_linkage():
    """The folded double pendulum: joint 2 is locked by the pin, so it cannot be the coordinate."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, length=1.0))
    scene = pinlin.Scene(robot, constraints=[pinlin.PointConstraint("tip", (0, 0, 0))])
    q = np.array([0.0, math.pi])
    with pytest.raises(pinlin.ParameterError, match=r"\['joint2'\] cannot serve as coordinates.*\['joint1'\] cannot follow"):
        pinlin.linearize(scene, q, coordinates=["joint2"])


def test_nearly_singular_coordinates_warn(four_bar_scene):
    """With the crank pointing at the rocker's pivot (O2, A, O4 in line) the crank and coupler joints
    move the loop's tip along one line: they cannot follow the rocker joint, cond(J_d) blows up."""
    q = BUNDLED.joints(1e-7)
    with pytest.warns(pinlin.AccuracyWarning, match=r"\['rocker_joint'\] are nearly singular.*cond\(J_d\) = \d\.\d+e\+0[6-9]"):
        pinlin.linearize(four_bar_scene, q, balancing=True, coordinates=["rocker_joint"])
    crank = pinlin.linearize(four_bar_scene, q, balancing=True, coordinates=["crank_joint"])
    assert crank.basis_condition < 10  # the crank drives this Grashof crank-rocker everywhere


def test_prescribed_velocities_with_constraints_are_refused(four_bar):
    with pytest.raises(pinlin.PrescribedJointError, match="cannot have prescribed joint velocities.*J_c-dot"):
        pinlin.Scene(four_bar, prescribed={"crank_joint": 1.0}, constraints=[pinlin.PointConstraint("rocker_tip", (0.7, 0, 0))])


def test_constraints_must_be_constraints(four_bar):
    with pytest.raises(pinlin.ParameterError, match=r"constraints\[0\]: expected a PointConstraint or FrameConstraint"):
        pinlin.Scene(four_bar, constraints=[pinlin.JointSpring("crank_joint", 1.0)])


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: pinlin.PointConstraint("tip", (1.0, 2.0)), r"target: expected 3 numbers"),
        (lambda: pinlin.PointConstraint("tip", (0, 0, np.nan)), r"target: must be finite"),
        (lambda: pinlin.PointConstraint("tip", "base", contact=True), r"a contact needs a fixed world point"),
        (lambda: pinlin.PointConstraint("tip", (0, 0, 0), friction=0.5), r"friction applies to contacts only"),
        (lambda: pinlin.PointConstraint("tip", (0, 0, 0), contact=True, friction=-1), r"friction: must be a finite number >= 0"),
        (lambda: pinlin.PointConstraint("tip", (0, 0, 0), contact=True, normal=(0, 0, 0)), r"normal: must not be zero"),
        (lambda: pinlin.PointConstraint(3, (0, 0, 0)), r"expected a frame name"),
        (lambda: pinlin.FrameConstraint("tip", np.eye(3)), r"4x4 placement, got shape \(3, 3\)"),
        (lambda: pinlin.FrameConstraint("tip", 2 * np.eye(4)), r"not a placement"),
        (lambda: pinlin.FrameConstraint("tip", "tip").check(pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1))), r"its own target"),
    ],
)
def test_bad_constraint_parameters(make, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        make()


def test_unsupported_joint_kind_is_refused():
    model = pin.Model()
    composite = pin.JointModelComposite()
    composite.addJoint(pin.JointModelRX())
    composite.addJoint(pin.JointModelRY())
    j = model.addJoint(0, composite, pin.SE3.Identity(), "gimbal")
    model.appendBodyToJoint(j, pin.Inertia.Random(), pin.SE3.Identity())
    model.addFrame(pin.Frame("tip", j, pin.SE3(np.eye(3), np.array([0, 0, -1.0])), pin.FrameType.OP_FRAME))
    robot = pinlin.Robot(model)
    with pytest.raises(pinlin.ParameterError, match=r"joint 'gimbal' \(JointModelComposite\) moves frame 'tip'"):
        pinlin.Scene(robot, constraints=[pinlin.PointConstraint("tip", (0, 0, -1))])


# ----------------------------------------------------------------------------- contacts


def _box_on_ground(push=(0.0, 0.0, 0.0), friction=0.5):
    """A free-floating box (1 kg) held by one contact at its centre under gravity, plus a dead force."""
    urdf = """<robot name="box"><link name="box"><inertial><mass value="1"/>
      <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>"""
    robot = pinlin.load_urdf_string(urdf, free_flyer=True)
    contact = pinlin.PointConstraint("box", (0.0, 0.0, 0.0), contact=True, friction=friction, name="floor")
    return pinlin.Scene(robot, [pinlin.DeadWrench("box", force=push)], gravity=(0, 0, -G), constraints=[contact])


def test_contact_that_must_pull():
    scene = _box_on_ground(push=(0.0, 0.0, 20.0))  # lifted by 20 N against its 9.81 N weight
    eq = pinlin.find_equilibrium(scene, scene.neutral())
    (contact,) = eq.contacts
    assert contact.pulls and not contact.feasible
    assert_allclose(contact.normal_force, 9.81 - 20.0, rtol=1e-12)
    assert any("'floor': the ground must pull" in n for n in eq.notes)


def test_the_verdict_quotes_a_violated_contact():
    """The stability verdict's reason says the contact would have to pull (the linearization
    keeps it bilateral); a contact that holds adds nothing to the reason."""
    scene = _box_on_ground(push=(0.0, 0.0, 20.0))
    eq = pinlin.find_equilibrium(scene, scene.neutral())
    modes = pinlin.modal_analysis(pinlin.linearize(scene, eq.q))
    assert "but contact 'floor': the ground must pull (normal force -10.19 N)" in modes.stability.reason
    held = _box_on_ground()
    eq = pinlin.find_equilibrium(held, held.neutral())
    assert "contact 'floor'" not in pinlin.modal_analysis(pinlin.linearize(held, eq.q)).stability.reason


def test_contact_that_would_slip():
    scene = _box_on_ground(push=(6.0, 0.0, 0.0), friction=0.5)  # 6 N sideways, mu N = 4.9 N
    eq = pinlin.find_equilibrium(scene, scene.neutral())
    (contact,) = eq.contacts
    assert contact.slips and not contact.pulls
    assert_allclose(contact.friction_needed, 6.0 / 9.81, rtol=1e-12)
    assert any("needs friction coefficient 0.612 > mu = 0.5" in n for n in eq.notes)


# ----------------------------------------------------------------------------- downstream analyses


def test_downstream_analyses_of_a_constrained_system(four_bar_scene):
    """Modes, frequency and free responses run unchanged on z; shapes expand to every joint."""
    eq = pinlin.find_equilibrium(four_bar_scene, np.zeros(3))
    sys = pinlin.linearize(four_bar_scene, eq.q, coordinates=["crank_joint"])
    k, m = sys.K[0, 0], sys.M[0, 0]
    modes = pinlin.modal_analysis(sys)
    assert_allclose(modes.natural_frequency, [math.sqrt(k / m)] * 2, rtol=1e-12)
    shape = sys.expand(modes.right[:, 0])
    J = evaluate_constraints(four_bar_scene, eq.q).J
    assert shape.shape == (3,) and np.abs(J @ shape).max() < 1e-12 * np.abs(shape).max()
    omega = np.array([0.5, 2.0]) * math.sqrt(k / m)
    frf = pinlin.frequency_response(sys, omega, inputs="crank_joint", outputs="crank_joint")
    assert_allclose(frf.response.ravel(), 1 / (k - m * omega**2), rtol=1e-12)
    t = np.linspace(0, 1, 5)
    free = pinlin.free_response(sys, [0.01], [0.0], t)
    assert_allclose(np.asarray(free)[:, 0], 0.01 * np.cos(math.sqrt(k / m) * t), rtol=1e-10, atol=1e-14)


def test_cli_reports_a_constrained_scene(capsys):
    from pinlin.cli import main

    assert main(["analyze", str(pinlin.data_path("scenes/four_bar.toml"))]) == 0
    out = capsys.readouterr().out
    assert "newton-kkt" in out and "redundant" in out and "ASYMPTOTICALLY STABLE" in out


def test_helper_bad_input(four_bar_scene, four_bar):
    with pytest.raises(pinlin.FrameNotFoundError, match="unknown frame 'paw'"):
        pinlin.ground_contacts(four_bar, np.zeros(3), ["paw"])
    with pytest.raises(pinlin.ConfigurationError, match=r"3 finite numbers \(nq\), got shape \(2,\)"):
        pinlin.ground_contacts(four_bar, np.zeros(2), ["rocker_tip"])
    with pytest.raises(pinlin.ParameterError, match="scene: has no constraints"):
        pinlin.constraint_stiffness(pinlin.Scene(four_bar), np.zeros(3), np.zeros(3))
    with pytest.raises(pinlin.ParameterError, match=r"lam: expected 3 finite multipliers, got shape \(2,\)"):
        pinlin.constraint_stiffness(four_bar_scene, np.zeros(3), np.zeros(2))
    with pytest.raises(pinlin.ParameterError, match="is not a contact"):
        four_bar_scene.constraints[0].contact_status(np.zeros(3))


def test_ground_contacts_and_scene_replace(four_bar, four_bar_scene):
    (c,) = pinlin.ground_contacts(four_bar, BUNDLED.joints(1.0), ["rocker_tip"], friction=0.3)
    assert c.contact and c.friction == 0.3 and c.name == "rocker_tip"
    assert_allclose(c.target, [0.7, 0.0, 0.0], atol=1e-12)  # the loop is closed at that q
    assert four_bar_scene.replace(gravity=(0, 0, 0)).constraints == four_bar_scene.constraints
    assert "1 constraints (m = 3)" in repr(four_bar_scene)


def test_close_loops_old_tol_keyword_warns_and_still_works(four_bar_scene):
    with pytest.warns(DeprecationWarning, match=r"close_loops\(tol=...\) is deprecated .* use closure_tol=..."):
        old = pinlin.close_loops(four_bar_scene, np.zeros(3), tol=1e-9)
    new = pinlin.close_loops(four_bar_scene, np.zeros(3), closure_tol=1e-9)
    np.testing.assert_array_equal(old.q, new.q)
    assert new.gap <= 1e-9
    with pytest.raises(pinlin.ParameterError, match="closure_tol: must be a positive number"):
        pinlin.close_loops(four_bar_scene, np.zeros(3), closure_tol=float("nan"))
