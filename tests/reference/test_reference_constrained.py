"""Constrained systems against closed forms and Pinocchio's own constrained dynamics (theory: constraints).

- Planar four-bar (URDF open chain + point constraint, and the same from MJCF) with a crank
  spring under gravity: omega^2 = K_eff / M_eff by the energy method along the loop
  (tests/constrained_cases.py), to 1e-8 at two crank angles.
- A double pendulum whose tip is pinned: pinned at a generic point it has no motion left
  (planar, rank J_c = 2 = nv); pinned at its pivot with equal links it folds into one
  rigid compound pendulum, one DOF: omega^2 = (k_1 + g sum m_i d_i) / I_O.
- A parallelogram linkage equals the single pendulum of the same mass moment and inertia.
- solo12 standing on four point contacts with springs on every leg joint: the vertical
  contact forces carry its weight, six coordinates remain, the modes agree with finite
  differences of ``pinocchio.constraintDynamics`` projected on ker J_c, K_z with central
  differences of the constrained residual on the manifold, and the eigenvalues do not
  depend on the coordinates.
"""

import math

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from constrained_cases import BUNDLED, PARALLELOGRAM

G = 9.81
#: Crank spring [N m/rad]: stiffer than gravity's softening, so each crank angle is a stable equilibrium.
K_CRANK = 50.0


def four_bar_scene(robot, theta0, frame="rocker_tip", target=(0.7, 0.0, 0.0)):
    rest = BUNDLED.spring_rest(theta0, K_CRANK, G)
    constraints = None if robot.constraints else [pinlin.PointConstraint(frame, target)]
    return pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", K_CRANK, rest=rest)], constraints=constraints)


@pytest.mark.parametrize("source", ["urdf", "mjcf"])
@pytest.mark.parametrize("theta0_deg", [75.0, 130.0])
def test_four_bar_frequency_energy_method(source, theta0_deg):
    theta0 = math.radians(theta0_deg)
    if source == "urdf":
        robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    else:
        robot = pinlin.load_mjcf(pinlin.data_path("mjcf/four_bar.xml"))
    scene = four_bar_scene(robot, theta0)
    # start from the file's assembled pose (crank at 60 degrees): Newton walks the loop to theta0
    eq = pinlin.find_equilibrium(scene, np.zeros(3))
    assert_allclose(eq.q, BUNDLED.joints(theta0), atol=1e-10)
    assert eq.redundant == 1  # the planar loop's out-of-plane equation
    sys = pinlin.linearize(scene, eq.q)
    assert sys.n == 1
    omega2 = pinlin.modal_analysis(sys).natural_frequency.max() ** 2
    assert_allclose(omega2, BUNDLED.omega2(theta0, K_CRANK, G), rtol=1e-8)
    # with the crank as the coordinate, M and K are exactly M_eff and K_eff
    crank = pinlin.linearize(scene, eq.q, coordinates=["crank_joint"])
    M_eff, _, V2 = BUNDLED.energy(theta0, G)
    assert_allclose(crank.M[0, 0], M_eff, rtol=1e-9)
    assert_allclose(crank.K[0, 0], K_CRANK + V2, rtol=1e-9)


def test_bundled_four_bar_matches_the_case_geometry():
    """The bundled files are the linkage of constrained_cases.BUNDLED (assembled at q = 0)."""
    from_file = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    generated = pinlin.load_urdf_string(BUNDLED.urdf())
    q = np.array([0.2, -0.1, 0.3])
    data = [r.model.createData() for r in (from_file, generated)]
    assert_allclose(pin.crba(from_file.model, data[0], q), pin.crba(generated.model, data[1], q), rtol=1e-14)
    pin.framesForwardKinematics(from_file.model, data[0], np.zeros(3))
    assert_allclose(data[0].oMf[from_file.frame_id("rocker_tip")].translation, [0.7, 0, 0], atol=1e-15)


def test_four_bar_without_k_lambda_is_wrong():
    """Dropping the constraint-force stiffness K_lambda (Exudyn's error) changes the frequency by percent."""
    theta0 = math.radians(75.0)
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    scene = four_bar_scene(robot, theta0)
    q = BUNDLED.joints(theta0)
    sys = pinlin.linearize(scene, q, coordinates=["crank_joint"])
    lam = np.concatenate([f.force for f in sys.constraint_forces])
    K_lambda = pinlin.constraint_stiffness(scene, q, lam)
    wrong = sys.K[0, 0] + (sys.basis.T @ K_lambda @ sys.basis)[0, 0]
    assert abs(wrong / sys.K[0, 0] - 1) > 0.01
    assert_allclose(sys.K[0, 0] / sys.M[0, 0], BUNDLED.omega2(theta0, K_CRANK, G), rtol=1e-9)


def test_pinned_double_pendulum_generic_point_has_no_motion_left():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, length=1.0))
    scene = pinlin.Scene(robot, constraints=[pinlin.PointConstraint("tip", (0.3, 0.0, -0.6))])
    q = pinlin.close_loops(scene, [0.4, -0.8]).q
    with pytest.raises(pinlin.OverconstrainedError, match=r"no motion left.*rank J_c = 2") as info:
        pinlin.linearize(scene, q)
    assert (info.value.rank, info.value.nv) == (2, 2)


def test_pinned_double_pendulum_folded_is_a_compound_pendulum():
    """Equal links (l = 0.5 each, uniform bars m) pinned at the pivot: the tip stays at O only folded
    (theta_2 = pi), and the folded pair swings about O as one rigid body."""
    m, l, k1 = 1.3, 0.5, 4.0
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, length=2 * l, mass=2 * m))
    # a spring on joint 2 loads the pin (its torque is held by the pin force)
    springs = [pinlin.JointSpring("joint1", k1), pinlin.JointSpring("joint2", 2.0, rest=math.pi - 0.3)]
    scene = pinlin.Scene(robot, springs, gravity=(0, 0, -G), constraints=[pinlin.PointConstraint("tip", (0, 0, 0))])
    eq = pinlin.find_equilibrium(scene, [0.2, math.pi - 0.15])
    assert_allclose(eq.q, [0.0, math.pi], atol=1e-10)
    assert eq.redundant == 2 and any("minimum-norm" in n for n in eq.notes)
    assert abs(eq.constraint_forces[0].force[0]) > 0.1  # the pin holds the joint-2 spring
    sys = pinlin.linearize(scene, eq.q)
    assert sys.n == 1 and sys.dof_names == ("joint1",)
    I_O = 2 * (m * l**2 / 12) + m * (l / 2) ** 2 + m * (l / 2) ** 2  # both COMs at l/2 from O
    K_O = k1 + G * (m * l / 2 + m * l / 2)
    assert_allclose(sys.M, [[I_O]], rtol=1e-6)  # the generator's bars have a small thickness inertia
    omega2 = pinlin.modal_analysis(sys).natural_frequency.max() ** 2
    assert_allclose(omega2, K_O / sys.M[0, 0], rtol=1e-10)


def test_parallelogram_equals_its_single_pendulum():
    theta0 = -math.pi / 2 + 0.25
    robot = pinlin.load_urdf_string(PARALLELOGRAM.urdf())
    tip = (PARALLELOGRAM.ground, 0.0, 0.0)
    scene = pinlin.Scene(robot, constraints=[pinlin.PointConstraint("rocker_tip", tip)])
    q = PARALLELOGRAM.joints(theta0)
    sys = pinlin.linearize(scene, q, coordinates=["crank_joint"], balancing=True)
    crank, coupler, rocker = PARALLELOGRAM.crank, PARALLELOGRAM.coupler, PARALLELOGRAM.rocker
    a = crank.length
    # crank and rocker turn about their pivots, the coupler translates on a circle of radius a
    I_O = crank.inertia + crank.mass * crank.com**2 + rocker.inertia + rocker.mass * (a - rocker.com) ** 2
    I_O += coupler.mass * a**2
    moment = crank.mass * crank.com + rocker.mass * (a - rocker.com) + coupler.mass * a
    mass = crank.mass + coupler.mass + rocker.mass
    d = moment / mass
    pendulum = pinlin.load_urdf_string(
        f"""<robot name="p"><link name="base"/><link name="bar"><inertial><origin xyz="{d!r} 0 0"/>
        <mass value="{mass!r}"/><inertia ixx="1" iyy="{I_O - mass * d * d!r}" izz="1" ixy="0" ixz="0" iyz="0"/>
        </inertial></link><joint name="j" type="revolute"><parent link="base"/><child link="bar"/>
        <origin rpy="0 {-PARALLELOGRAM.theta_ref!r} 0"/><axis xyz="0 -1 0"/>
        <limit lower="-6" upper="6" effort="1" velocity="1"/></joint></robot>"""
    )
    single = pinlin.linearize(pinlin.Scene(pendulum), [q[0]], balancing=True)
    assert_allclose(sys.M, single.M, rtol=1e-12)
    assert_allclose(sys.K, single.K, rtol=1e-11)
    assert_allclose(sys.balancing, single.balancing, rtol=1e-11)
    assert_allclose(sys.K[0, 0], -G * moment * math.sin(theta0), rtol=1e-12)  # V = g m d sin(theta)


def test_parallelogram_flat_is_singular():
    """All four pivots in line (the parallelogram's change point): J_c loses rank, named."""
    robot = pinlin.load_urdf_string(PARALLELOGRAM.urdf())
    scene = pinlin.Scene(robot, constraints=[pinlin.PointConstraint("rocker_tip", (0.8, 0, 0), name="loop")])
    r1, r2, r3 = PARALLELOGRAM.reference()
    q_flat = np.array([0.0 - r1, 0.0 - r2, math.pi - r3])  # crank, coupler along +x; rocker back to O4
    with pytest.raises(pinlin.SingularConstraintError, match=r"rank 1 at q but rank 2.*\['loop'\].*toggle") as info:
        pinlin.linearize(scene, q_flat, balancing=True)
    assert (info.value.rank, info.value.nearby_rank, info.value.constraints) == (1, 2, ("loop",))


# ----------------------------------------------------------------------------- solo12 standing

FEET = ("FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT")
#: Leg joint stiffness [N m/rad]: holds the 2.5 kg robot with a few degrees of sag.
K_LEG = 20.0


@pytest.fixture(scope="module")
def standing():
    robot = pinlin.load_example("solo12", free_flyer=True)
    q0 = robot.reference_configurations["standing"].copy()
    springs = [pinlin.JointSpring(j, K_LEG, rest=q0[robot.joint(j).idx_q]) for j in robot.joint_names[1:]]
    contacts = pinlin.ground_contacts(robot, q0, FEET, friction=0.8)
    scene = pinlin.Scene(robot, springs, gravity=(0, 0, -G), constraints=contacts)
    eq = pinlin.find_equilibrium(scene, q0)
    return scene, eq, pinlin.linearize(scene, eq.q)


def test_solo12_contact_forces_carry_the_weight(standing):
    scene, eq, sys = standing
    weight = G * sum(inertia.mass for inertia in scene.model.inertias)
    vertical = sum(f.force[2] for f in eq.constraint_forces)
    assert_allclose(vertical, weight, rtol=1e-9)
    assert_allclose(sum(f.force[:2] for f in eq.constraint_forces), [0, 0], atol=1e-9 * weight)
    assert [f.constraint for f in eq.constraint_forces] == list(FEET)
    assert all(c.feasible and c.normal_force > 0 for c in eq.contacts)
    assert eq.redundant == 0 and eq.error < 1e-12
    assert sys.n == 6 and sys.basis.shape == (18, 6)
    assert any("bilateral" in note for note in sys.notes)


def _dof_springs(scene, q):
    """Generalized spring forces on the leg joints (revolute: -k (q - rest)), free-flyer unloaded."""
    tau = np.zeros(scene.model.nv)
    for e in scene.elements:
        j = scene.robot.joint(e.joint)
        tau[j.idx_v] = -float(e.stiffness) * (q[j.idx_q] - float(e.rest))
    return tau


def test_solo12_modes_match_pinocchio_constraint_dynamics(standing):
    """Finite differences of constraintDynamics (3D contacts, no Baumgarte) in z, zdot with x = B z."""
    scene, eq, sys = standing
    model = scene.model
    data = model.createData()
    cmodels = pin.StdVec_RigidConstraintModel()
    for c in scene.constraints:
        frame = model.frames[scene.robot.frame_id(c.frame)]
        cmodels.append(
            pin.RigidConstraintModel(
                pin.ContactType.CONTACT_3D, model, frame.parentJoint, frame.placement, 0,
                pin.SE3(np.eye(3), np.array(c.target)), pin.ReferenceFrame.LOCAL_WORLD_ALIGNED,
            )
        )  # fmt: skip
    cdatas = pin.StdVec_RigidConstraintData()
    for cm in cmodels:
        cdatas.append(cm.createData())
    pin.initConstraintDynamics(model, data, cmodels, cdatas)
    prox = pin.ProximalSettings(1e-14, 1e-12, 1)
    B = sys.basis
    left = np.linalg.pinv(B)

    def zdd(z, zd):
        q = pin.integrate(model, eq.q, B @ z)
        a = pin.constraintDynamics(model, data, q, B @ zd, _dof_springs(scene, q), cmodels, cdatas, prox)
        return left @ a

    n, h = sys.n, 1e-6
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    for k in range(n):
        e = np.zeros(n)
        e[k] = h
        A[n:, k] = (zdd(e, 0 * e) - zdd(-e, 0 * e)) / (2 * h)
        A[n:, n + k] = (zdd(0 * e, e) - zdd(0 * e, -e)) / (2 * h)
    reference = np.linalg.eigvals(A)
    reference = reference[np.argsort(reference.imag)]
    modes = pinlin.modal_analysis(sys).eigenvalues
    modes = modes[np.argsort(modes.imag)]
    assert_allclose(modes, reference, rtol=1e-6, atol=1e-6 * np.abs(reference).max())


def _project(model, q, scene, tol=1e-14):
    """Gauss-Newton back onto the contacts (minimum-norm steps), with Pinocchio's frame Jacobians."""
    data = model.createData()
    for _ in range(20):
        pin.framesForwardKinematics(model, data, q)
        phi = np.concatenate([data.oMf[scene.robot.frame_id(c.frame)].translation - c.target for c in scene.constraints])
        if np.abs(phi).max() < tol:
            return q
        pin.computeJointJacobians(model, data, q)
        J = np.vstack([
            pin.getFrameJacobian(model, data, scene.robot.frame_id(c.frame), pin.LOCAL_WORLD_ALIGNED)[:3]
            for c in scene.constraints
        ])  # fmt: skip
        q = pin.integrate(model, q, -np.linalg.pinv(J) @ phi)
    raise AssertionError("projection did not converge")


def test_solo12_stiffness_matches_constrained_residual_on_manifold(standing):
    """K_z = d/dz [B^T (r - J_c^T lambda)](q(z)), q(z) = the manifold point above q0 + B z (central differences)."""
    scene, eq, sys = standing
    model = scene.model
    data = model.createData()

    def reduced_residual(z):
        q = _project(model, pin.integrate(model, eq.q, sys.basis @ z), scene)
        r = pin.computeGeneralizedGravity(model, data, q) - _dof_springs(scene, q)
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        J = np.vstack([
            pin.getFrameJacobian(model, data, scene.robot.frame_id(c.frame), pin.LOCAL_WORLD_ALIGNED)[:3]
            for c in scene.constraints
        ])  # fmt: skip
        lam = np.linalg.lstsq(J.T, r, rcond=None)[0]
        return sys.basis.T @ (r - J.T @ lam)

    h = 1e-5
    K_fd = np.column_stack([
        (reduced_residual(h * e) - reduced_residual(-h * e)) / (2 * h) for e in np.eye(sys.n)
    ])  # fmt: skip
    assert_allclose(sys.K, K_fd, rtol=1e-6, atol=1e-6 * np.abs(K_fd).max())


def test_solo12_eigenvalues_do_not_depend_on_coordinates(standing):
    scene, eq, sys = standing
    # the base's six degrees of freedom: each leg follows its foot (the classic stance coordinates)
    user = pinlin.linearize(scene, eq.q, coordinates=["root_joint"])
    systems = [sys, user, pinlin.linearize(scene, eq.q, coordinates="orthonormal")]
    assert user.dof_names == tuple(f"root_joint[{k}]" for k in range(6))
    assert systems[2].dof_names == ("z1", "z2", "z3", "z4", "z5", "z6") and systems[2].basis_condition == 1.0
    lams = [np.sort(pinlin.modal_analysis(s).eigenvalues.imag) for s in systems]
    for other in lams[1:]:
        assert_allclose(other, lams[0], rtol=1e-12)
    model = scene.model
    data = model.createData()
    pin.computeJointJacobians(model, data, eq.q)
    pin.updateFramePlacements(model, data)
    J = np.vstack([
        pin.getFrameJacobian(model, data, scene.robot.frame_id(f), pin.LOCAL_WORLD_ALIGNED)[:3] for f in FEET
    ])  # fmt: skip
    for s in systems:  # every basis spans ker J_c: the feet do not move
        assert np.linalg.matrix_rank(s.basis) == 6
        assert np.abs(J @ s.basis).max() < 1e-12 * np.abs(J).max() * np.abs(s.basis).max()
