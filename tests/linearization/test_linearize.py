"""linearize: operating-point checks, balancing, structure, and the Pinocchio calls each scene makes."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from helpers import MASSLESS_LINK_URDF


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
    text = MASSLESS_LINK_URDF
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
    # one pass at q, no crba; the ring (a root joint about the vertical) is proved time-invariant,
    # so the numerical check adds no pass
    assert sys.calls == ("computeRNEADerivatives",)
    assert any("'ring' by symmetry: a root joint turning about a fixed axis along gravity" in n for n in sys.notes)


def test_calls_prescribed_velocity_checked_numerically():
    """An element the symmetry proof does not know: one pass, then two per prescribed joint."""
    robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf())
    spring = pinlin.LinearSpringDamper("particle", "ring", stiffness=5.0)
    scene = pinlin.Scene(robot, [spring], prescribed={"ring": 1.0})
    sys = pinlin.linearize(scene, scene.neutral())
    assert sys.calls == ("computeRNEADerivatives", "computeJointJacobians", "updateFramePlacements") * 3
    assert any("'ring']: relative change" in n and "checked numerically" in n for n in sys.notes)


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


# --- parameters and configurations


@pytest.mark.parametrize("value", [-1e-12, np.nan, np.inf, "tight", True])
def test_structure_tol_is_validated(chain, value):
    with pytest.raises(pinlin.ParameterError, match="structure_tol: must be None or a finite number >= 0"):
        pinlin.linearize(pinlin.Scene(chain), np.zeros(3), structure_tol=value)


@pytest.mark.parametrize("name, value", [("rank_tol", 1.0), ("rank_tol", 0.0), ("constraint_tol", -1.0),
                                         ("constraint_tol", np.nan), ("equilibrium_tol", "1e-8")])
def test_other_tolerances_are_validated(chain, name, value):
    with pytest.raises(pinlin.ParameterError, match=f"{name}: must be a finite positive number"):
        pinlin.linearize(pinlin.Scene(chain), np.zeros(3), **{name: value})


def test_zero_quaternion_and_zero_complex_number_are_refused():
    robot = pinlin.load_example("solo12", free_flyer=True)
    q = robot.neutral()
    q[3:7] = 0.0
    with pytest.raises(pinlin.ConfigurationError, match=r"q\[3:7\].*'root_joint' is not a rotation: its length 0"):
        pinlin.linearize(pinlin.Scene(robot), q, balancing=True)
    table = pinlin.load_urdf_string(pinlin.turntable_urdf())
    with pytest.raises(pinlin.ConfigurationError, match=r"q\[0:2\] = \[0.0, 0.0\] of joint 'table'"):
        pinlin.linearize(pinlin.Scene(table), [0.0, 0.0, 0.1, 0.2], balancing=True)
    # a quaternion that is merely not normalized is normalized, as Pinocchio does
    q[3:7] = (0.0, 0.0, 0.0, 2.0)
    assert pinlin.linearize(pinlin.Scene(robot, gravity=(0, 0, 0)), q).q[3:7].tolist() == [0.0, 0.0, 0.0, 1.0]


def test_complex_configuration_is_refused(chain):
    with pytest.raises(pinlin.ConfigurationError, match="q must be real, got complex entries"):
        pinlin.linearize(pinlin.Scene(chain), np.array([0.1j, 0.0, 0.0]))


def test_element_damping_rounding_is_made_symmetric_and_reported(chain):
    """A spring-damper between frames adds g^T c g, whose products need not be symmetric in floating point."""
    damper = pinlin.LinearSpringDamper("tip", (0.3, 0.0, 0.2), stiffness=0.0, damping=0.7)
    sys = pinlin.linearize(pinlin.Scene(chain, [damper]), [0.4, -0.3, 0.2], balancing=True)
    assert np.array_equal(sys.D, sys.D.T) and sys.is_zero("G")
    assert all(size < 1e-15 for key, size in sys.dropped.items() if key.startswith("G"))


def test_c_and_k_are_formed_on_access_and_read_only(chain):
    scene = pinlin.Scene(chain, [pinlin.FollowerWrench("tip", force=(0, 0, 1.0)), pinlin.JointDamper("joint2", 0.3)])
    sys = pinlin.linearize(scene, np.zeros(3))
    assert "C" not in vars(sys) and "K" not in vars(sys)
    assert np.array_equal(sys.C, sys.D + sys.G) and np.array_equal(sys.K, sys.S + sys.N)
    assert sys.C is sys.C and not sys.K.flags.writeable
    data = sys.to_dict()
    assert list(data)[-2:] == ["C", "K"] and data["K"] == (sys.S + sys.N).tolist()


def test_no_invalid_escape_sequences_in_linearization_docstrings():
    """A docstring with \\p or \\q (math) must be raw or escaped: Python warns about invalid escapes."""
    import warnings
    from pathlib import Path

    root = Path(pinlin.__file__).parent
    for path in [*sorted((root / "linearization").glob("*.py")), root / "model" / "scene.py"]:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            compile(path.read_text(encoding="utf-8"), str(path), "exec")


def test_free_coordinates_around_a_prescribed_joint_are_restricted_exactly(chain):
    """A joint held still in the middle of the chain: its rows and columns are left out (not contiguous)."""
    springs = [pinlin.JointSpring(j, 5.0) for j in chain.joint_names]
    held = pinlin.Scene(chain, springs, prescribed={"joint2": 0.0})
    full = pinlin.linearize(pinlin.Scene(chain, springs), [0.1, 0.2, 0.3], balancing=True)
    part = pinlin.linearize(held, [0.1, 0.2, 0.3], balancing=True)
    keep = np.ix_([0, 2], [0, 2])
    for name in ("M", "D", "S"):
        assert np.array_equal(getattr(part, name), getattr(full, name)[keep])
    assert np.array_equal(part.balancing, full.balancing[[0, 2]])
    assert part.dof_names == ("joint1", "joint3")
