"""find_equilibrium: Newton on the configuration manifold (theory: equilibrium)."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin


def double_pendulum(**kw):
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    return pinlin.Scene(robot, **kw)


@pytest.mark.parametrize(
    "start, expected",
    [((0.3, -0.2), (0, 0)), ((2.9, 0.2), (np.pi, 0)), ((0.2, 3.0), (0, np.pi)), ((3.0, -0.1), (np.pi, 0))],
)
def test_four_equilibria_of_example_6_2(start, expected):
    """Without springs and load the double pendulum has (0,0), (pi,0), (0,pi), (pi,pi) in absolute
    angles; in relative URDF angles theta2 = phi2 - phi1 the same set, found from nearby starts."""
    eq = pinlin.find_equilibrium(double_pendulum(), start)
    assert_allclose(eq.q, expected, atol=1e-10)
    assert eq.relative_residual <= 1e-12
    assert eq.history[-1] == eq.residual
    assert len(eq.history) == eq.iterations + 1


def test_spring_equilibrium_closed_form():
    """One bar (m, l) with a spring k at rest angle a, zero gravity -> theta = a; with gravity,
    k (theta - a) + m g l/2 sin(theta) = 0, solved by bisection as reference."""
    m, l, k, a, g = 2.0, 0.8, 15.0, 0.9, 9.81
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(1, length=l, mass=m))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", k, rest=a)], gravity=(0, 0, -g))
    eq = pinlin.find_equilibrium(scene)
    lo, hi = 0.0, a
    for _ in range(200):
        mid = (lo + hi) / 2
        if k * (mid - a) + m * g * l / 2 * np.sin(mid) > 0:
            hi = mid
        else:
            lo = mid
    assert_allclose(eq.q, [lo], rtol=1e-12)
    sys = pinlin.linearize(scene, eq.q)
    assert_allclose(sys.S, [[k + m * g * l / 2 * np.cos(lo)]], rtol=1e-10)


def test_floating_base_under_gravity_has_no_equilibrium():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, radius=0.05), free_flyer=True)
    with pytest.raises(pinlin.ConvergenceError, match="residual history") as info:
        pinlin.find_equilibrium(pinlin.Scene(robot))
    assert len(info.value.history) >= 1
    assert info.value.history[0] > 1.0  # the weight of the chain, unbalanced


def test_floating_base_in_zero_gravity_is_in_equilibrium():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(2, radius=0.05), free_flyer=True)
    eq = pinlin.find_equilibrium(pinlin.Scene(robot, gravity=(0, 0, 0)))
    assert eq.iterations == 0 and eq.residual == 0.0


def test_iteration_limit_reports_history():
    scene = double_pendulum(elements=[pinlin.JointSpring("joint1", 1.0, rest=1.0)])
    with pytest.raises(pinlin.ConvergenceError, match="no convergence in 1 iteration ") as info:
        pinlin.find_equilibrium(scene, [2.0, 0.5], max_iterations=1)
    assert len(info.value.history) == 2


def test_bad_arguments():
    scene = double_pendulum()
    with pytest.raises(pinlin.ConfigurationError, match=r"q0 has shape \(3,\).*nq = 2"):
        pinlin.find_equilibrium(scene, [0.0, 0.0, 0.0])
    with pytest.raises(pinlin.ConfigurationError, match="non-finite"):
        pinlin.find_equilibrium(scene, [0.0, np.nan])
    with pytest.raises(pinlin.ParameterError, match="tol: must be a positive number"):
        pinlin.find_equilibrium(scene, tol=-1.0)
    with pytest.raises(pinlin.ParameterError, match="max_iterations"):
        pinlin.find_equilibrium(scene, max_iterations=2.5)


def test_stall_far_from_equilibrium_is_reported_with_advice():
    """A 50-link chain curled by 5 rad against its springs: the residual norm stalls (Newton's known limit)."""
    n = 50
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n))
    scene = pinlin.Scene(robot, [pinlin.JointSpring(f"joint{i + 1}", 5.0) for i in range(n)])
    with pytest.raises(pinlin.ConvergenceError, match="stalled at a local minimum of ||r||") as info:
        pinlin.find_equilibrium(scene, np.full(n, 0.1), max_iterations=30)
    assert info.value.history[-1] > 1.0


_TURN_AND_SWING = """<robot name="turn_and_swing">
  <link name="base"/>
  <link name="turret"><inertial><mass value="1"/><origin xyz="0 0 0"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="bob"><inertial><mass value="2"/><origin xyz="0 0 -0.5"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="turn" type="continuous"><parent link="base"/><child link="turret"/><axis xyz="0 0 1"/></joint>
  <joint name="swing" type="revolute"><parent link="turret"/><child link="bob"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"""


def test_singular_stiffness_steps_are_reported():
    """A turret about the vertical has no stiffness at all (K singular at every iterate): Newton takes
    minimum-norm least-squares steps, reaches the hanging pendulum, and says so in the result."""
    robot = pinlin.load_urdf_string(_TURN_AND_SWING)
    scene = pinlin.Scene(robot)
    eq = pinlin.find_equilibrium(scene, np.array([1.0, 0.0, 0.4]))  # continuous joint: (cos, sin)
    assert_allclose(eq.q[2], 0.0, atol=1e-10)
    assert_allclose(eq.q[:2], [1.0, 0.0], atol=1e-12)  # the minimum-norm step never turns the turret
    assert eq.method.startswith("newton (least-squares steps at iterations [0")
    assert "minimum-norm" in eq.notes[0]


def test_equilibrium_result_convention():
    import json

    eq = pinlin.find_equilibrium(double_pendulum(), (0.3, -0.2))
    assert eq.method == "newton" and eq.notes == ()
    assert eq.error == eq.relative_residual <= 1e-12
    d = json.loads(json.dumps(eq.to_dict()))
    assert d["type"] == "EquilibriumResult" and d["iterations"] == eq.iterations
    assert_allclose(d["q"], eq.q)
    sys = pinlin.linearize(double_pendulum(), eq.q)
    d = json.loads(json.dumps(sys.to_dict()))
    assert d["method"] == "analytic" and d["error"] == sys.residual
    assert_allclose(d["S"], sys.S)
    assert len(repr(sys).splitlines()) == 1


# --- bad input gets a clear error, never a history of inf and a "relative nan"

SLIDER = """<robot name="slider"><link name="world_link"/>
  <link name="block"><inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <joint name="slide" type="prismatic"><parent link="world_link"/><child link="block"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"""


def test_start_at_1e300_rad_is_refused_naming_the_joint():
    """q = [1e300, 0]: doubles that large are ~1e284 rad apart, so the angle says nothing about the position."""
    scene = double_pendulum(elements=[pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", 2.0)])
    with pytest.raises(pinlin.ConfigurationError, match=r"q0\[0\] = 1e\+300 rad on revolute joint 'joint1' is beyond"):
        pinlin.find_equilibrium(scene, [1e300, 0.0])
    with pytest.raises(pinlin.ConfigurationError, match="beyond 2.83e\\+16 rad"):
        pinlin.linearize(scene, [0.0, -1e17])


def test_huge_but_finite_forces_keep_a_finite_history():
    """A slider 1e200 m from its spring's rest: ||r|| = 6e200 squares past double precision, the norm does not."""
    scene = pinlin.Scene(pinlin.load_urdf_string(SLIDER), [pinlin.JointSpring("slide", 6.0)])
    eq = pinlin.find_equilibrium(scene, [1e200])
    assert eq.history[0] == pytest.approx(6e200, rel=1e-15)  # k x: the spring alone acts along the slide
    assert eq.q[0] == 0.0 and eq.iterations == 1  # Newton on a linear spring: one step


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")  # numpy, in the spring's force
def test_overflowing_forces_at_the_start_are_a_clear_error():
    scene = pinlin.Scene(pinlin.load_urdf_string(SLIDER), [pinlin.JointSpring("slide", 6.0)])
    with pytest.raises(pinlin.ConfigurationError, match=r"non-finite generalized forces on \['slide'\].*overflow"):
        pinlin.find_equilibrium(scene, [1e308])


@pytest.mark.parametrize("min_step", [0.0, -1e-3, 1.0, 2.0, np.nan, np.inf, "small", None])
def test_min_step_is_validated(min_step):
    with pytest.raises(pinlin.ParameterError, match=r"min_step: must be a line-search fraction in \(0, 1\)"):
        pinlin.find_equilibrium(double_pendulum(), [0.1, 0.0], min_step=min_step)


def test_min_step_is_validated_with_constraints_too():
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    loop = pinlin.PointConstraint("rocker_tip", (1.0, 0.0, 0.0))
    with pytest.raises(pinlin.ParameterError, match="min_step"):
        pinlin.find_equilibrium(pinlin.Scene(robot, constraints=[loop]), min_step=0.0)


def test_zero_quaternion_is_not_taken_as_the_identity():
    robot = pinlin.load_example("solo12", free_flyer=True)
    q0 = robot.neutral()
    q0[3:7] = 0.0
    with pytest.raises(pinlin.ConfigurationError, match=r"q0\[3:7\] = \[0.0, 0.0, 0.0, 0.0\] of joint 'root_joint' is not"):
        pinlin.find_equilibrium(pinlin.Scene(robot, gravity=(0, 0, 0)), q0)


def test_find_equilibrium_old_tol_keyword_warns_and_still_works():
    scene = double_pendulum()
    with pytest.warns(DeprecationWarning, match=r"find_equilibrium\(tol=...\) is deprecated .* use rtol=..."):
        old = pinlin.find_equilibrium(scene, np.array([0.1, -0.1]), tol=1e-10)
    new = pinlin.find_equilibrium(scene, np.array([0.1, -0.1]), rtol=1e-10)
    np.testing.assert_array_equal(old.q, new.q)
    assert new.relative_residual <= 1e-10
    with pytest.raises(pinlin.ParameterError, match="rtol: must be a positive number"):
        pinlin.find_equilibrium(scene, rtol=0.0)
