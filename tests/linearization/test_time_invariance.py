"""Time invariance of prescribed joints: proofs once per scene, the numerical check elsewhere (issues 13, 14).

A proof (:mod:`pinlin.linearization.time_invariance`) replaces the two extra
assemblies per prescribed joint that the numerical check costs; every proof is
checked here against that numerical check, and every refusal against a closed form.
The rotor pendulum: a pendulum (swing about y, 1 m, arm of 1 kg with its centre of
mass at 0.5 m) carrying a rotor (0.5 kg, inertia diag(ixx, iyy, 0.04)) that spins
about the arm's axis z at Omega = 10 rad/s.  Its rotor's kinetic energy is
(ixx sin^2 phi + iyy cos^2 phi) swing_dot^2 / 2 + ..., so with ixx != iyy the swing's
mass and damping depend on the spin angle phi: M(phi) = M0 + (ixx - iyy) sin^2 phi and
C(phi) = (ixx - iyy) sin(2 phi) Omega (Lagrange's equation of the swing).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.linearization.assembly import assemble
from pinlin.linearization.time_invariance import (
    PERIODIC_TEST_ANGLES,
    SYMMETRY_TOL,
    invariance_proofs,
    numeric_change,
)

OMEGA = 10.0
#: A proof must agree with the numerical check to rounding: the equations at the moved
#: joint differ from those at q by a few eps of the system's scales.
ROUNDING = 1e-14


def rotor_urdf(ixx: float = 0.02, iyy: float = 0.02, com: str = "0 0 0") -> str:
    return f"""<?xml version="1.0"?>
<robot name="rotor_pendulum">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="0 0 -0.5"/><mass value="1.0"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="swing" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-10" upper="10" effort="1" velocity="1"/></joint>
  <link name="rotor"><inertial><origin xyz="{com}"/><mass value="0.5"/>
    <inertia ixx="{ixx}" iyy="{iyy}" izz="0.04" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="spin" type="continuous"><parent link="arm"/><child link="rotor"/>
    <origin xyz="0 0 -1.0"/><axis xyz="0 0 1"/></joint>
  <link name="rim"/>
  <joint name="rim_joint" type="fixed"><parent link="rotor"/><child link="rim"/><origin xyz="0.2 0 0"/></joint>
</robot>
"""


def rotor_scene(extra=(), **inertia):
    robot = pinlin.load_urdf_string(rotor_urdf(**inertia))
    return pinlin.Scene(robot, [pinlin.JointSpring("swing", 2.0), *extra], prescribed={"spin": OMEGA})


def check_numerically(scene, q):
    """The numerical check's change for every prescribed joint (the proofs' referee)."""
    base = assemble(scene, scene.check_configuration(q), stiffness=True, damping=True, mass=True)
    return numeric_change(scene, scene.check_configuration(q), base, list(scene.prescribed), tol=1.0)[0]


def turntable(gravity=(0.0, 0.0, -9.81), elements=()):
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(0.5, 1.3))
    spring = pinlin.JointSpring("slider", 10.0, rest=0.3)
    return pinlin.Scene(robot, [spring, *elements], gravity=gravity, prescribed={"table": 1.5})


def turntable_q(scene):
    q = scene.neutral()
    q[3] = (10.0 * 0.3 + 1.3 * 1.5**2 * 0.5) / (10.0 - 1.3 * 1.5**2)  # r0 of SPEC 7.2
    return q


# ----------------------------------------------------------------------------- proofs


def test_root_turntable_is_proved_and_costs_one_pass():
    scene = turntable()
    assert set(scene.linearization_plan.proofs) == {"table"}
    q = turntable_q(scene)
    sys = pinlin.linearize(scene, q)
    assert sys.calls == ("computeRNEADerivatives",)
    assert any("root joint turning about a fixed axis along gravity" in note for note in sys.notes)
    assert check_numerically(scene, q) < ROUNDING


def test_axisymmetric_rotor_on_undamped_pendulum_is_proved():
    """The spurious TimePeriodicError of issue 13: C is exactly zero here (n = 1: no gyroscopic term)."""
    scene = rotor_scene()
    proof = scene.linearization_plan.proofs["spin"]
    assert "axisymmetric rigid rotor" in proof.note and proof.departure == 0.0
    sys = pinlin.linearize(scene, scene.neutral())
    assert sys.calls == ("computeRNEADerivatives",)
    assert sys.is_zero("C")
    assert check_numerically(scene, scene.neutral()) < ROUNDING


def test_unknown_element_falls_back_to_the_numerical_check_with_a_system_scale():
    """An undamped scene (C = 0) checked numerically: rounding in C no longer reads as a 1e291 change."""
    anchor = pinlin.LinearSpringDamper("arm", (0.0, 0.0, -0.5), stiffness=1.0)
    scene = rotor_scene(extra=[anchor])
    assert scene.linearization_plan.unproved == ("spin",)
    sys = pinlin.linearize(scene, scene.neutral())
    assert sys.is_zero("C")
    assert sys.calls.count("computeRNEADerivatives") == 1 + len(PERIODIC_TEST_ANGLES)
    assert any("checked numerically" in note for note in sys.notes)
    assert check_numerically(scene, scene.neutral()) < ROUNDING


def test_root_slider_at_constant_speed_is_proved():
    """A cart driven at constant speed (Galilean invariance), with a pendulum and a tilted gravity."""
    urdf = """<robot name="cart"><link name="world_link"/>
      <link name="cart"><inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>
      </inertial></link>
      <joint name="drive" type="prismatic"><parent link="world_link"/><child link="cart"/><axis xyz="1 0 0"/>
        <limit lower="-100" upper="100" effort="1" velocity="1"/></joint>
      <link name="bob"><inertial><origin xyz="0 0 -0.8"/><mass value="0.7"/>
        <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="hinge" type="revolute"><parent link="cart"/><child link="bob"/><axis xyz="0 1 0"/>
        <limit lower="-10" upper="10" effort="1" velocity="1"/></joint></robot>"""
    robot = pinlin.load_urdf_string(urdf)
    scene = pinlin.Scene(robot, [pinlin.JointSpring("hinge", 3.0)], gravity=(0.5, 0.0, -9.81), prescribed={"drive": 4.0})
    assert "sliding along a fixed axis" in scene.linearization_plan.proofs["drive"].note
    sys = pinlin.linearize(scene, [0.3, 0.0], balancing=True)
    assert sys.calls == ("computeRNEADerivatives",)
    assert check_numerically(scene, [0.3, 0.0]) < ROUNDING


def test_dead_force_along_the_table_axis_is_proved_across_it_refused():
    along = turntable(elements=[pinlin.DeadWrench("particle", force=(0.0, 0.0, -2.0))])
    assert "table" in along.linearization_plan.proofs
    across = turntable(elements=[pinlin.DeadWrench("particle", force=(2.0, 0.0, 0.0))])
    assert across.linearization_plan.unproved == ("table",)
    with pytest.raises(pinlin.TimePeriodicError, match="depend on the position of prescribed joint 'table'"):
        pinlin.linearize(across, turntable_q(across), balancing=True)


def test_joint_held_still_needs_no_check():
    robot = pinlin.load_urdf_string(rotor_urdf(ixx=0.03))  # unbalanced, but it does not turn
    scene = pinlin.Scene(robot, [pinlin.JointSpring("swing", 2.0)], prescribed={"spin": 0.0})
    assert "held still" in scene.linearization_plan.proofs["spin"].note
    sys = pinlin.linearize(scene, robot.neutral())
    assert sys.calls == ("computeGeneralizedGravityDerivatives", "crba")


def test_a_proof_departing_from_symmetry_is_used_only_within_periodic_tol():
    """An inertia off by 1e-13 relative: proved for the default periodic_tol, checked for a tighter one."""
    scene = rotor_scene(ixx=0.02 * (1 + 1e-13))
    proof = scene.linearization_plan.proofs["spin"]
    assert 0 < proof.departure <= SYMMETRY_TOL
    assert pinlin.linearize(scene, scene.neutral()).calls == ("computeRNEADerivatives",)
    tight = pinlin.linearize(scene, scene.neutral(), periodic_tol=proof.departure / 10)
    assert tight.calls == ("computeRNEADerivatives",) * (1 + len(PERIODIC_TEST_ANGLES))


def test_invariance_proofs_of_scenes_without_prescribed_joints_are_empty():
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    assert invariance_proofs(pinlin.Scene(robot)) == {}


# ----------------------------------------------------------------------------- refusals, with their figure


@pytest.mark.parametrize("inertia", [{"ixx": 0.03}, {"com": "0.01 0 0"}])
def test_unbalanced_rotor_is_not_proved(inertia):
    assert rotor_scene(**inertia).linearization_plan.unproved == ("spin",)


def test_unbalanced_rotor_on_undamped_pendulum_reports_a_relative_change_of_physical_size():
    """C(0) = 0 exactly; the change is measured against C's system scale ||C|| + w ||M||, w^2 = ||K||/||M|| + Omega^2.

    At phi = 1 rad (the first test angle) C = (ixx - iyy) sin(2) Omega = 0.0909 N m s, the largest
    change against its scale (M changes by (ixx - iyy) sin^2(1) = 0.0071 kg m^2 of 0.87).
    """
    scene = rotor_scene(ixx=0.03)
    with pytest.raises(pinlin.TimePeriodicError, match=r"relative change 9\.81e-03 after 1\.0 rad") as info:
        pinlin.linearize(scene, scene.neutral())
    M0 = 1.0 * 0.5**2 + 0.1 + 0.5 * 1.0**2 + 0.02  # arm about the pivot, rotor's point mass and iyy
    K0 = 2.0 + 9.81 * (1.0 * 0.5 + 0.5 * 1.0)  # spring and gravity
    w = math.sqrt(K0 / M0 + OMEGA**2)
    expected = 0.01 * math.sin(2.0) * OMEGA / (w * M0)
    assert info.value.joint == "spin"
    assert info.value.variation == pytest.approx(expected, rel=1e-10)


def test_tilted_turntable_is_refused():
    scene = turntable(gravity=(9.81, 0.0, 0.0))
    assert scene.linearization_plan.unproved == ("table",)
    with pytest.raises(pinlin.TimePeriodicError, match="time-periodic") as info:
        pinlin.linearize(scene, turntable_q(scene), balancing=True)
    assert 1e-3 < info.value.variation < 10.0  # a change of physical size, never a division by `tiny`


def test_matrices_do_not_depend_on_the_angle_of_a_proved_joint():
    scene = rotor_scene()
    systems = []
    for angle in (0.0, 0.7, 2.9):
        q = scene.neutral()
        q[1:3] = math.cos(angle), math.sin(angle)
        systems.append(pinlin.linearize(scene, q))
    for other in systems[1:]:
        for name in ("M", "C", "K"):
            assert_allclose(getattr(other, name), getattr(systems[0], name), rtol=1e-14, atol=1e-14)
    assert np.array_equal(systems[0].M, [[1.0 * 0.5**2 + 0.1 + 0.5 + 0.02]])
