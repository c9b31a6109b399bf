"""Time invariance of prescribed joints: proofs once per scene, the numerical check elsewhere.

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
from pinlin.linearization.periodicity import PERIODIC_TEST_ANGLES, numeric_change
from pinlin.linearization.plan import plan_of
from pinlin.linearization.time_invariance import (
    BODY_FIXED_LOAD,
    DEAD_LOAD,
    JOINT_SPACE,
    SYMMETRY_TOL,
    UNKNOWN,
    invariance_kind,
    invariance_proofs,
)
from pinlin.model.elements import ElementGroup

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
    q[3] = (10.0 * 0.3 + 1.3 * 1.5**2 * 0.5) / (10.0 - 1.3 * 1.5**2)  # r0 of theory: turntable
    return q


# ----------------------------------------------------------------------------- proofs


def test_root_turntable_is_proved_and_costs_one_pass():
    scene = turntable()
    assert set(plan_of(scene).proofs) == {"table"}
    q = turntable_q(scene)
    sys = pinlin.linearize(scene, q)
    assert sys.calls == ("computeRNEADerivatives",)
    assert any("root joint turning about a fixed axis along gravity" in note for note in sys.notes)
    assert check_numerically(scene, q) < ROUNDING


def test_axisymmetric_rotor_on_undamped_pendulum_is_proved():
    """A TimePeriodicError once raised spuriously here: C is exactly zero here (n = 1: no gyroscopic term)."""
    scene = rotor_scene()
    proof = plan_of(scene).proofs["spin"]
    assert "axisymmetric rigid rotor" in proof.note and proof.departure == 0.0
    sys = pinlin.linearize(scene, scene.neutral())
    assert sys.calls == ("computeRNEADerivatives",)
    assert sys.is_zero("C")
    assert check_numerically(scene, scene.neutral()) < ROUNDING


def test_unknown_element_falls_back_to_the_numerical_check_with_a_system_scale():
    """An undamped scene (C = 0) checked numerically: rounding in C no longer reads as a 1e291 change."""
    anchor = pinlin.LinearSpringDamper("arm", (0.0, 0.0, -0.5), stiffness=1.0)
    scene = rotor_scene(extra=[anchor])
    assert plan_of(scene).unproved == ("spin",)
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
    assert "sliding along a fixed axis" in plan_of(scene).proofs["drive"].note
    sys = pinlin.linearize(scene, [0.3, 0.0], balancing=True)
    assert sys.calls == ("computeRNEADerivatives",)
    assert check_numerically(scene, [0.3, 0.0]) < ROUNDING


def test_dead_force_along_the_table_axis_is_proved_across_it_refused():
    along = turntable(elements=[pinlin.DeadWrench("particle", force=(0.0, 0.0, -2.0))])
    assert "table" in plan_of(along).proofs
    across = turntable(elements=[pinlin.DeadWrench("particle", force=(2.0, 0.0, 0.0))])
    assert plan_of(across).unproved == ("table",)
    with pytest.raises(pinlin.TimePeriodicError, match="depend on the position of prescribed joint 'table'"):
        pinlin.linearize(across, turntable_q(across), balancing=True)


def test_joint_held_still_needs_no_check():
    robot = pinlin.load_urdf_string(rotor_urdf(ixx=0.03))  # unbalanced, but it does not turn
    scene = pinlin.Scene(robot, [pinlin.JointSpring("swing", 2.0)], prescribed={"spin": 0.0})
    assert "held still" in plan_of(scene).proofs["spin"].note
    sys = pinlin.linearize(scene, robot.neutral())
    assert sys.calls == ("computeGeneralizedGravityDerivatives", "crba")


def test_a_proof_departing_from_symmetry_is_used_only_within_periodic_tol():
    """An inertia off by 1e-13 relative: proved for the default periodic_tol, checked for a tighter one."""
    scene = rotor_scene(ixx=0.02 * (1 + 1e-13))
    proof = plan_of(scene).proofs["spin"]
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
    assert plan_of(rotor_scene(**inertia)).unproved == ("spin",)


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
    assert plan_of(scene).unproved == ("table",)
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


# ----------------------------------------------------------------------------- declared kinds


@pytest.mark.parametrize(
    "element, kind",
    [
        (pinlin.JointSpring("swing", 2.0), JOINT_SPACE),
        (pinlin.JointDamper("swing", 0.1), JOINT_SPACE),
        (pinlin.RayleighDamping(alpha=0.1, beta=0.01), JOINT_SPACE),
        (pinlin.FollowerWrench("rim", force=(1.0, 0.0, 0.0)), BODY_FIXED_LOAD),
        (pinlin.DeadWrench("rim", force=(1.0, 0.0, 0.0)), DEAD_LOAD),
        (pinlin.LinearSpringDamper("arm", (0.0, 0.0, -0.5), stiffness=1.0), UNKNOWN),
        (pinlin.Bushing("rim", "arm", stiffness=np.ones(6)), UNKNOWN),
    ],
)
def test_built_in_elements_declare_their_kind_on_their_own_class(element, kind):
    assert type(element).__dict__["invariance"] == kind
    assert invariance_kind(element) == kind


class SpinTunedSpring(pinlin.JointSpring):
    """A swing spring whose stiffness k (1 + cos(phi) / 2) reads the spin angle phi too, declaring nothing.

    It inherits JointSpring's claim ``invariance = "joint-space"``, which is false for it: the
    swing's K at the neutral swing is 2 (1 + cos(phi) / 2), a change of (1 - cos 1) = 0.46 N m/rad
    between phi = 0 and the first test angle, against K's scale ||K|| + w^2 ||M|| (w^2 = ||K||/||M||
    + Omega^2; C = 0, M does not change).
    """

    def _factor(self, ev) -> float:
        spin = ev.robot.joint("spin")
        c, s = ev.q[spin.idx_q : spin.idx_q + 2]
        return 1.0 + math.cos(math.atan2(s, c)) / 2

    def generalized_force(self, ev):
        return super().generalized_force(ev) * self._factor(ev)

    def add_stiffness(self, ev, K):
        K_own = np.zeros_like(K)
        super().add_stiffness(ev, K_own)
        K += K_own * self._factor(ev)  # exact at the neutral swing, where the spin column vanishes

    @classmethod
    def group(cls, elements, robot):
        return ElementGroup(elements)  # one by one: JointSpring's vectorized group reads no spin


class CopiedSpring(pinlin.JointSpring):
    """A subclass of JointSpring that changes nothing and declares nothing."""


class TorsionSpring(pinlin.Element):
    """A user-defined spring on one 1-DOF joint, Q = -k (q_j - rest), declaring it reads only its joint."""

    invariance = "joint-space"

    def __init__(self, joint: str, k: float):
        self.joint, self.k = joint, k

    def check(self, robot):
        robot.joint(self.joint)

    def generalized_force(self, ev):
        j = ev.robot.joint(self.joint)
        Q = np.zeros(ev.model.nv)
        Q[j.idx_v] = -self.k * ev.q[j.idx_q]
        return Q

    def add_stiffness(self, ev, K):
        j = ev.robot.joint(self.joint)
        K[j.idx_v, j.idx_v] += self.k


class UndeclaredTorsionSpring(TorsionSpring):
    """The same force; the claim of its parent does not carry over."""


def test_an_undeclared_subclass_of_joint_spring_is_checked_numerically():
    """A copy of JointSpring passes the numerical check; a subclass reading the spin is caught by it."""
    copied = pinlin.Scene(rotor_scene().robot, [CopiedSpring("swing", 2.0)], prescribed={"spin": OMEGA})
    assert invariance_kind(copied.elements[0]) == UNKNOWN
    assert plan_of(copied).unproved == ("spin",)
    sys = pinlin.linearize(copied, copied.neutral())
    assert sys.calls.count("computeRNEADerivatives") == 1 + len(PERIODIC_TEST_ANGLES)
    assert any("checked numerically" in note for note in sys.notes)
    proved = pinlin.linearize(rotor_scene(), copied.neutral())
    assert np.array_equal(sys.M, proved.M) and np.array_equal(sys.K, proved.K)
    tuned = pinlin.Scene(rotor_scene().robot, [SpinTunedSpring("swing", 2.0)], prescribed={"spin": OMEGA})
    assert plan_of(tuned).unproved == ("spin",)
    with pytest.raises(pinlin.TimePeriodicError, match="prescribed joint 'spin'") as info:
        pinlin.linearize(tuned, tuned.neutral())
    M0 = 1.0 * 0.5**2 + 0.1 + 0.5 * 1.0**2 + 0.02  # arm about the pivot, rotor's point mass and iyy
    K0 = 2.0 * 1.5 + 9.81 * (1.0 * 0.5 + 0.5 * 1.0)  # the tuned spring at phi = 0 and gravity
    expected = (1.0 - math.cos(1.0)) / (K0 + (K0 / M0 + OMEGA**2) * M0)  # K's change against its scale
    assert info.value.variation == pytest.approx(expected, rel=1e-10)


def test_a_user_element_declaring_joint_space_is_proved():
    robot = pinlin.load_urdf_string(rotor_urdf())
    declared = pinlin.Scene(robot, [TorsionSpring("swing", 2.0)], prescribed={"spin": OMEGA})
    assert invariance_kind(declared.elements[0]) == JOINT_SPACE
    assert plan_of(declared).proofs == plan_of(rotor_scene()).proofs
    sys = pinlin.linearize(declared, declared.neutral())
    assert sys.calls == ("computeRNEADerivatives",)
    assert sys.K[0, 0] == pytest.approx(2.0 + 9.81 * (1.0 * 0.5 + 0.5 * 1.0), rel=1e-14)  # spring and gravity
    assert check_numerically(declared, declared.neutral()) < ROUNDING
    undeclared = pinlin.Scene(robot, [UndeclaredTorsionSpring("swing", 2.0)], prescribed={"spin": OMEGA})
    assert plan_of(undeclared).unproved == ("spin",)


def test_a_user_element_declaring_an_unknown_kind_is_refused():
    class Misspelled(TorsionSpring):
        invariance = "joint_space"

    robot = pinlin.load_urdf_string(rotor_urdf())
    match = r"Misspelled\.invariance: expected one of .*'joint_space'"
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.Scene(robot, [Misspelled("swing", 2.0)])


class PlainFollower(pinlin.FollowerWrench):
    """A subclass of FollowerWrench that declares nothing: a load the rotor proof does not know."""


def test_only_declared_loads_off_the_rotor_keep_its_proof():
    """A follower force on the arm keeps the rotor's proof; an undeclared subclass of it does not."""
    on_arm = rotor_scene(extra=[pinlin.FollowerWrench("arm", force=(0.0, 0.0, 3.0))])
    assert "axisymmetric rigid rotor" in plan_of(on_arm).proofs["spin"].note
    assert check_numerically(on_arm, on_arm.neutral()) < ROUNDING
    undeclared = rotor_scene(extra=[PlainFollower("arm", force=(0.0, 0.0, 3.0))])
    assert invariance_kind(undeclared.elements[1]) == UNKNOWN
    assert plan_of(undeclared).unproved == ("spin",)
