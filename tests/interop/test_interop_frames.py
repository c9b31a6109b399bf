"""Frame inputs and outputs of state_space: closed forms, finite differences, prescribed joints, constraints.

- Double pendulum (theory: double pendulum, joints about +y, bars along -z): the tip is at
  p = (-(l1 sin phi1 + l2 sin phi2), 0, -(l1 cos phi1 + l2 cos phi2)) with phi1 = theta1,
  phi2 = theta1 + theta2, so dp/dtheta and the generalized forces Q = (dp/dtheta)^T F of a
  tip force (virtual work) are closed forms, at the hanging position and at a deflected
  equilibrium.
- UR5 (3-D, example-robot-data): rows and columns against central differences of the
  frame's position and orientation, taken with pin.integrate.
"""

import numpy as np
import pinocchio as pin
import pytest
from interop_cases import L1, L2, double_pendulum, double_pendulum_scene, rotating_ring
from numpy.testing import assert_allclose

import pinlin
from pinlin.model.evaluation import Evaluation

control = pytest.importorskip("control")

#: Rows and columns built from Pinocchio's Jacobians: exact up to a few eps of the link lengths.
KINEMATIC_TOL = 1e-13
#: Central differences with step H: truncation O(H^2) ~ 1e-10 relative, rounding eps/H ~ 1e-10.
H = 1e-5
FD_TOL = 1e-8
#: Agreement of frequency responses.
AGREEMENT = 1e-10


def tip_jacobian(theta) -> np.ndarray:
    """dp/dtheta of the double pendulum's tip (3 x 2), closed form."""
    phi1, phi2 = theta[0], theta[0] + theta[1]
    d2 = np.array([-L2 * np.cos(phi2), 0.0, L2 * np.sin(phi2)])
    d1 = np.array([-L1 * np.cos(phi1), 0.0, L1 * np.sin(phi1)]) + d2
    return np.column_stack([d1, d2])


def deflected_pendulum():
    """The double pendulum held sideways by a dead force at the tip, at its equilibrium."""
    scene = double_pendulum_scene(P=0.0, extra=[pinlin.DeadWrench("tip", force=(3.0, 0.0, 0.0))])
    eq = pinlin.find_equilibrium(scene, np.array([0.3, 0.2]))
    assert abs(eq.q[0]) > 0.1  # really deflected
    return scene, pinlin.linearize(scene, eq.q)


# ---------------------------------------------------------------- closed forms


def test_outputs_at_hanging_position():
    scene, sys = double_pendulum()
    model = pinlin.state_space(sys, outputs=["position:tip", "velocity:tip:x"], scene=scene)
    assert model.output_names == ("position:tip:x", "position:tip:y", "position:tip:z", "velocity:tip:x")
    J = tip_jacobian(np.zeros(2))  # x row: -(l1 + l2), -l2; y and z rows zero
    expected = np.zeros((4, 4))
    expected[:3, :2] = J
    expected[3, 2:] = J[0]
    assert_allclose(model.C, expected, rtol=0, atol=KINEMATIC_TOL)


def test_wrench_inputs_at_hanging_position():
    """Q = (dp/dtheta)^T F for forces; a torque about y acts on both joints (axes +y): Q = (1, 1)."""
    scene, sys = double_pendulum()
    model = pinlin.state_space(
        sys, inputs=["follower:tip:fx", "dead:tip:fx", "dead:tip:ty", "follower:tip:tz"], scene=scene
    )
    Q = sys.M @ model.B[2:]
    J = tip_jacobian(np.zeros(2))
    expected = np.column_stack([J[0], J[0], [1.0, 1.0], [0.0, 0.0]])
    assert_allclose(Q, expected, rtol=0, atol=KINEMATIC_TOL)
    assert not np.any(model.B[:2])


def test_outputs_and_inputs_at_deflected_equilibrium():
    scene, sys = deflected_pendulum()
    theta = sys.q
    phi2 = theta[0] + theta[1]
    J = tip_jacobian(theta)
    ex_tip = np.array([np.cos(phi2), 0.0, -np.sin(phi2)])  # the tip frame's x axis in world axes
    model = pinlin.state_space(
        sys,
        inputs=["dead:tip:fx", "dead:tip:fz", "follower:tip:fx"],
        outputs=["position:tip:x", "velocity:tip:z"],
        scene=scene,
    )
    assert_allclose(model.C[0, :2], J[0], rtol=0, atol=KINEMATIC_TOL)
    assert_allclose(model.C[1, 2:], J[2], rtol=0, atol=KINEMATIC_TOL)
    Q = sys.M @ model.B[2:]
    assert_allclose(Q, np.column_stack([J[0], J[2], J.T @ ex_tip]), rtol=0, atol=KINEMATIC_TOL)


def test_frame_response_equals_projected_flexibility():
    """y = c^T x with u entering as f = b u: c^T H(i omega) b from pinlin's frequency response."""
    scene, sys = deflected_pendulum()
    J = tip_jacobian(sys.q)
    omega = np.linspace(0.1, 30.0, 31)
    model = pinlin.state_space(
        sys, inputs=["dead:tip:fx", "joint2"], outputs=["position:tip:x", "velocity:tip:z"], scene=scene
    )
    ctl = control.frequency_response(model.to_control(), omega).complex
    H = pinlin.frequency_response(sys, omega).response  # (n, n, frequencies)
    b = np.column_stack([J[0], [0.0, 1.0]])
    expected = np.stack(
        [np.einsum("i,ijw,jk->kw", J[0], H, b), 1j * omega * np.einsum("i,ijw,jk->kw", J[2], H, b)]
    )
    assert_allclose(ctl, expected, rtol=AGREEMENT, atol=AGREEMENT * np.abs(expected).max())


def test_wrench_element_inputs_scale_and_name():
    scene, sys = deflected_pendulum()
    wrench = pinlin.DeadWrench("tip", force=(1.0, 0.0, 2.0))
    model = pinlin.state_space(
        sys,
        inputs=[
            wrench,
            ("pull", pinlin.FollowerWrench("tip", force=(0, 0, -1.0))),
            "dead:tip:fx",
            "dead:tip:fz",
        ],
        scene=scene,
    )
    assert model.input_names == ("dead:tip", "pull", "dead:tip:fx", "dead:tip:fz")
    B = model.B
    assert_allclose(B[:, 0], B[:, 2] + 2 * B[:, 3], rtol=0, atol=KINEMATIC_TOL * np.abs(B).max())
    assert_allclose(
        sys.M @ B[2:, 0], pinlin.generalized_force(scene, sys.q, wrench), rtol=0, atol=KINEMATIC_TOL
    )


# ---------------------------------------------------------------- finite differences, 3-D


def ur5():
    robot = pinlin.load_example("ur5")
    elements = [pinlin.JointSpring(j, 50.0) for j in robot.joint_names]
    scene = pinlin.Scene(robot, elements)
    q = np.random.default_rng(3).uniform(-1.5, 1.5, robot.nq)
    return scene, pinlin.linearize(scene, q, balancing=True)


def test_ur5_rows_and_columns_against_finite_differences():
    """Rows: dp/dq.  Columns by virtual work: Q = (dp/dq)^T F + (dtheta/dq)^T T, with dtheta the
    world-axes small rotation log3(R R0^T) of the frame."""
    scene, sys = ur5()
    fid = scene.robot.frame_id("tool0")
    force, torque = np.array([0.3, -1.0, 0.7]), np.array([0.2, 0.5, -0.4])

    def pose(dq):
        ev = Evaluation(scene, pin.integrate(scene.model, sys.q, dq), scene.v0)
        return ev.frame_position(fid), ev.frame_rotation(fid)

    n = sys.n
    R0 = pose(np.zeros(n))[1]
    dp, dtheta = np.zeros((3, n)), np.zeros((3, n))
    for k in range(n):
        e = np.zeros(n)
        e[k] = H
        (p_plus, R_plus), (p_minus, R_minus) = pose(e), pose(-e)
        dp[:, k] = (p_plus - p_minus) / (2 * H)
        dtheta[:, k] = (pin.log3(R_plus @ R0.T) - pin.log3(R_minus @ R0.T)) / (2 * H)
    model = pinlin.state_space(
        sys,
        inputs=[pinlin.DeadWrench("tool0", force, torque), "follower:tool0:fy"],
        outputs=["position:tool0", "velocity:tool0:y"],
        scene=scene,
    )
    scale = np.abs(dp).max()
    assert_allclose(model.C[:3, :n], dp, rtol=0, atol=FD_TOL * scale)
    assert_allclose(model.C[3, n:], dp[1], rtol=0, atol=FD_TOL * scale)
    Q = sys.M @ model.B[n:]
    Q_dead = dp.T @ force + dtheta.T @ torque
    assert_allclose(Q[:, 0], Q_dead, rtol=0, atol=FD_TOL * np.abs(Q_dead).max())
    assert_allclose(Q[:, 1], dp.T @ R0[:, 1], rtol=0, atol=FD_TOL * scale)  # along the frame's own y axis


# ---------------------------------------------------------------- prescribed joints

ROTOR_PENDULUM = """<?xml version="1.0"?>
<robot name="rotor_pendulum">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="0 0 -0.5"/><mass value="1.0"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="swing" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-10" upper="10" effort="1" velocity="1"/></joint>
  <link name="rotor"><inertial><mass value="0.5"/>
    <inertia ixx="0.02" iyy="0.02" izz="0.04" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="spin" type="continuous"><parent link="arm"/><child link="rotor"/>
    <origin xyz="0 0 -1.0"/><axis xyz="0 0 1"/></joint>
  <link name="rim"/>
  <joint name="rim_joint" type="fixed"><parent link="rotor"/><child link="rim"/><origin xyz="0.2 0 0"/></joint>
  <link name="hub"/>
  <joint name="hub_joint" type="fixed"><parent link="rotor"/><child link="hub"/><origin xyz="0 0 -0.1"/></joint>
</robot>
"""


def rotor_pendulum():
    """A pendulum (swing about y, 1 m) carrying a rotor spinning about the pendulum's axis."""
    robot = pinlin.load_urdf_string(ROTOR_PENDULUM)
    # the damper keeps C nonzero: linearize's time-invariance test divides by |C| (see the report)
    elements = [pinlin.JointSpring("swing", 2.0), pinlin.JointDamper("swing", 0.1)]
    scene = pinlin.Scene(robot, elements, prescribed={"spin": 10.0})
    return scene, pinlin.linearize(scene, robot.neutral())


def test_frames_on_the_spin_axis_are_allowed_and_carried_ones_refused():
    scene, sys = rotor_pendulum()
    model = pinlin.state_space(
        sys,
        inputs=["dead:hub:fx", "follower:hub:fz"],
        outputs=["position:rotor:x", "position:hub:x"],
        scene=scene,
    )
    # hub and rotor centre lie on the spin axis: their motion is the swing's, at 1.0 and 1.1 m
    assert_allclose(model.C[:, :1], [[-1.0], [-1.1]], rtol=0, atol=KINEMATIC_TOL)
    # a dead force on the hub: Q = -1.1 F_x; a follower force along the spin axis has no moment
    assert_allclose(sys.M @ model.B[1:], [[-1.1, 0.0]], rtol=0, atol=KINEMATIC_TOL)
    # a follower force across the axis on the rim turns with the rotor
    with pytest.raises(
        pinlin.TimePeriodicError, match="'follower:rim:fx' depends on the position of prescribed joint 'spin'"
    ):
        pinlin.state_space(sys, inputs="follower:rim:fx", scene=scene)
    with pytest.raises(
        pinlin.TimePeriodicError, match="frame 'rim' is carried around by prescribed joint 'spin'"
    ):
        pinlin.state_space(sys, outputs="position:rim:x", scene=scene)
    # a dead vertical force on the rim has the moment arm 0.2 cos(spin angle) about the swing axis,
    # while a dead horizontal one has the constant arm 1 m (the rim's depth): only the first is refused
    with pytest.raises(
        pinlin.TimePeriodicError, match="'dead:rim:fz' depends on the position of prescribed joint 'spin'"
    ):
        pinlin.state_space(sys, inputs="dead:rim:fz", scene=scene)
    model = pinlin.state_space(sys, inputs="dead:rim:fx", scene=scene)
    assert_allclose(sys.M @ model.B[1:], [[-1.0]], rtol=0, atol=KINEMATIC_TOL)


def test_follower_but_not_dead_wrench_on_rotating_ring():
    """The particle rides on the ring: a follower force in the ring's x is the generalized force (1, 0)."""
    scene, sys = rotating_ring()
    model = pinlin.state_space(sys, inputs=["follower:particle:fx", "dead:particle:fz"], scene=scene)
    assert_allclose(sys.M @ model.B[2:], [[1.0, 0.0], [0.0, 0.0]], rtol=0, atol=KINEMATIC_TOL)
    with pytest.raises(pinlin.TimePeriodicError, match="prescribed joint 'ring'"):
        pinlin.state_space(sys, inputs="dead:particle:fx", scene=scene)
    # the particle sits on the axis at r = 0, but x and y turn with the ring
    with pytest.raises(
        pinlin.TimePeriodicError,
        match="'velocity:particle:x' depends on the position of prescribed joint 'ring'",
    ):
        pinlin.state_space(sys, outputs="velocity:particle", scene=scene)


# ---------------------------------------------------------------- constrained coordinates


def constrained(basis):
    """The double pendulum restricted to joint velocities = basis @ z (a system such as a constraint gives)."""
    scene, sys = double_pendulum()
    B = np.asarray(basis, dtype=float)
    reduced = pinlin.LinearizedSystem.from_matrices(
        B.T @ sys.M @ B, B.T @ sys.C @ B, B.T @ sys.K @ B, dof_names=("z",)
    )
    reduced = reduced.replace(q=sys.q)
    object.__setattr__(reduced, "basis", B)  # the attribute a constrained linearization sets
    return scene, reduced


def test_frame_signals_through_basis():
    """Bar 2 kept vertical (theta2 = -theta1, basis (1, -1)): the tip moves like A, by -l1 z."""
    scene, sys = constrained([[1.0], [-1.0]])
    model = pinlin.state_space(sys, inputs="follower:tip:fx", outputs=["position:tip:x", "z"], scene=scene)
    assert_allclose(model.C[0, :1], [-L1], rtol=0, atol=KINEMATIC_TOL)
    assert_allclose(sys.M @ model.B[1:], [[-L1]], rtol=0, atol=KINEMATIC_TOL)
    assert "sys.basis" in model.notes[0]


def test_basis_of_wrong_shape_refused():
    scene, sys = constrained([[1.0], [-1.0]])
    object.__setattr__(sys, "basis", np.ones((3, 1)))
    with pytest.raises(pinlin.InputError, match=r"sys.basis has shape \(3, 1\)"):
        pinlin.state_space(sys, outputs="position:tip:x", scene=scene)


@pytest.mark.skipif(
    not hasattr(pinlin, "PointConstraint"), reason="constraints (sys.basis) not in this tree yet"
)
def test_pinned_point_does_not_move():
    """A 3-link chain whose tip is pinned where a bent configuration puts it: one degree of freedom,
    along which the tip's position rows vanish and link2's origin moves."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3, length=1.5, mass=3.0))
    q_start = np.array([-0.6, 0.5, 0.4])
    target = Evaluation(pinlin.Scene(robot), q_start, np.zeros(3)).frame_position(robot.frame_id("tip"))
    scene = pinlin.Scene(
        robot,
        [pinlin.JointSpring(f"joint{i}", 2.0) for i in (1, 2, 3)],
        constraints=[pinlin.PointConstraint("tip", target)],
    )
    sys = pinlin.linearize(scene, pinlin.find_equilibrium(scene, q_start).q)
    assert sys.basis is not None and sys.n == 1
    model = pinlin.state_space(
        sys, inputs="dead:link2:fx", outputs=["position:tip", "position:link2:x"], scene=scene
    )
    assert_allclose(model.C[:3], 0.0, rtol=0, atol=KINEMATIC_TOL)
    assert np.abs(model.C[3]).max() > 0.1
    assert "sys.basis" in model.notes[0]


# ---------------------------------------------------------------- bad input


def test_bad_frame_signals():
    scene, sys = double_pendulum()
    with pytest.raises(pinlin.FrameNotFoundError, match="unknown frame 'nowhere'"):
        pinlin.state_space(sys, outputs="position:nowhere:x", scene=scene)
    with pytest.raises(pinlin.FrameNotFoundError, match="unknown frame 'elbow'"):
        pinlin.state_space(sys, inputs="dead:elbow:fx", scene=scene)
    with pytest.raises(
        pinlin.ParameterError, match=r"signals \['follower:tip:fx'\] act at frames: pass the scene"
    ):
        pinlin.state_space(sys, inputs="follower:tip:fx")
    with pytest.raises(pinlin.ParameterError, match="expected the pinlin.Scene"):
        pinlin.state_space(sys, outputs="position:tip:x", scene="scene.toml")
    plain = pinlin.LinearizedSystem.from_matrices(sys.M, sys.C, sys.K, dof_names=sys.dof_names)
    with pytest.raises(pinlin.InputError, match="no operating point"):
        pinlin.state_space(plain, outputs="position:tip:x", scene=scene)
    other_scene, _ = rotating_ring()
    with pytest.raises(pinlin.InputError, match="not the scene's"):
        pinlin.state_space(sys, outputs="position:tip:x", scene=other_scene)
