"""linearize: operating-point checks, balancing, structure, and the Pinocchio calls each scene makes."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin


@pytest.fixture(scope="module")
def chain():
    return pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3))


def test_not_an_equilibrium(chain):
    scene = pinlin.Scene(chain)
    with pytest.raises(pinlin.NotAnEquilibriumError, match="not an equilibrium.*balancing=True") as info:
        pinlin.linearize(scene, [0.3, 0.0, 0.0])
    assert info.value.relative_residual > 1e-8


def test_balancing_single_bar_closed_form():
    """A bar (m, l) held at angle t0 by a motor: tau_b = m g l/2 sin(t0), stiffness m g l/2 cos(t0)."""
    m, l, g, t0 = 1.5, 0.6, 9.81, 0.8
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1, length=l, mass=m))
    sys = pinlin.linearize(pinlin.Scene(robot, gravity=(0, 0, -g)), [t0], balancing=True)
    assert_allclose(sys.balancing, [m * g * l / 2 * np.sin(t0)], rtol=1e-13)
    assert_allclose(sys.S, [[m * g * l / 2 * np.cos(t0)]], rtol=1e-13)
    assert any("actuator" in note for note in sys.notes)


def test_wrong_configuration_size(chain):
    with pytest.raises(pinlin.ConfigurationError, match=r"q has shape \(2,\).*nq = 3"):
        pinlin.linearize(pinlin.Scene(chain), [0.0, 0.0])
    with pytest.raises(pinlin.ConfigurationError, match="array of numbers"):
        pinlin.linearize(pinlin.Scene(chain), ["a", "b", "c"])


def test_singular_mass_names_the_massless_joint():
    text = """<robot name="x"><link name="base"/>
      <link name="bar"><inertial><mass value="1"/><origin xyz="0 0 -0.5"/>
        <inertia ixx="0.1" iyy="0.1" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="ghost"/>
      <joint name="hinge" type="revolute"><parent link="base"/><child link="bar"/><axis xyz="0 1 0"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
      <joint name="ghost_joint" type="revolute"><parent link="bar"/><child link="ghost"/><axis xyz="0 1 0"/>
        <limit lower="-3" upper="3" effort="1" velocity="1"/></joint></robot>"""
    robot = pinlin.load_urdf_string(text)
    with pytest.raises(pinlin.SingularMassError, match=r"joints \['ghost_joint'\].*lock them") as info:
        pinlin.linearize(pinlin.Scene(robot), [0.0, 0.0])
    assert info.value.joints == ("ghost_joint",)
    # the remedy works
    locked = pinlin.load_urdf_string(text, locked=["ghost_joint"])
    assert pinlin.linearize(pinlin.Scene(locked), [0.0]).n == 1


def test_bad_tolerances(chain):
    scene = pinlin.Scene(chain)
    with pytest.raises(pinlin.ParameterError, match="equilibrium_tol"):
        pinlin.linearize(scene, np.zeros(3), equilibrium_tol=0.0)
    with pytest.raises(pinlin.ParameterError, match="periodic_tol"):
        pinlin.linearize(scene, np.zeros(3), periodic_tol=np.nan)


# --- leave out what the scene does not need: the Pinocchio algorithms each kind of scene triggers


def test_calls_gravity_only(chain):
    sys = pinlin.linearize(pinlin.Scene(chain), np.zeros(3))
    assert sys.calls == ("computeGeneralizedGravityDerivatives", "crba")


def test_calls_zero_gravity_springs(chain):
    sys = pinlin.linearize(pinlin.Scene(chain, [pinlin.JointSpring("joint1", 1.0)], gravity=(0, 0, 0)), np.zeros(3))
    assert sys.calls == ("crba",)


def test_calls_follower_wrench(chain):
    scene = pinlin.Scene(chain, [pinlin.FollowerWrench("tip", force=(0, 0, 1.0))])
    assert pinlin.linearize(scene, np.zeros(3)).calls == ("computeStaticTorqueDerivatives", "crba")


def test_calls_dead_wrench(chain):
    scene = pinlin.Scene(chain, [pinlin.DeadWrench("tip", force=(0, 0, -1.0))])
    assert pinlin.linearize(scene, np.zeros(3)).calls == (
        "computeJointJacobians",
        "updateFramePlacements",
        "computeStaticTorqueDerivatives",
        "crba",
    )


def test_calls_prescribed_velocity():
    robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("x", 5.0), pinlin.JointSpring("y", 5.0)], prescribed={"ring": 1.0})
    sys = pinlin.linearize(scene, scene.neutral())
    # one pass at q, then two per prescribed joint for the time-invariance check; no crba
    assert sys.calls == ("computeRNEADerivatives",) * 3


def test_zero_prescribed_velocity_uses_static_path():
    robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("x", 5.0), pinlin.JointSpring("y", 5.0)], prescribed={"ring": 0.0})
    sys = pinlin.linearize(scene, scene.neutral())
    assert "computeRNEADerivatives" not in sys.calls[:2]
    assert sys.is_zero("G")


def test_rounding_skew_part_is_dropped_and_reported():
    robot = pinlin.load_example("ur5")
    springs = [pinlin.JointSpring(n, 500.0) for n in robot.joint_names]
    scene = pinlin.Scene(robot, springs)
    eq = pinlin.find_equilibrium(scene)
    sys = pinlin.linearize(scene, eq.q)
    assert sys.is_zero("N") and sys.is_zero("G") and sys.is_zero("D")
    assert all(v < 1e-12 for v in sys.dropped.values())


def test_structure_tol_keeps_tiny_circulatory_part_when_asked(chain):
    """A follower load that is tiny against the stiffness is still a real N when structure_tol is 0."""
    springs = [pinlin.JointSpring(f"joint{i}", 1e6) for i in (1, 2, 3)]
    scene = pinlin.Scene(chain, springs + [pinlin.FollowerWrench("tip", force=(0, 0, 1e-6))])
    sys = pinlin.linearize(scene, np.zeros(3), structure_tol=0.0)
    # absolute angles: Q_i = -P l_i sin(phi_3 - phi_i), i < 3, so N_phi[i, 3] = P l_i / 2;
    # relative URDF angles: phi = T theta with T lower-triangular ones
    P, l = 1e-6, 1 / 3
    N_phi = np.zeros((3, 3))
    N_phi[:2, 2] = P * l / 2
    N_phi[2, :2] = -P * l / 2
    T = np.tril(np.ones((3, 3)))
    assert_allclose(sys.N, T.T @ N_phi @ T, rtol=1e-6, atol=1e-15)
    assert pinlin.linearize(scene, np.zeros(3)).is_zero("N") is False  # default tol keeps it too
