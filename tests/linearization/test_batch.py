"""linearize_many: one scene at many configurations equals linearize point by point, bitwise."""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_array_equal

import pinlin
from helpers import MASSLESS_LINK_URDF
from pinlin.errors import (
    ConfigurationError,
    NotAnEquilibriumError,
    ParameterError,
    SingularMassError,
    TimePeriodicError,
)
from pinlin.linearization import batch_common, batch_static, matrices
from pinlin.linearization.system import LinearizedSystem
from pinlin.linearization.plan import plan_of

FIELDS = ("M", "D", "G", "S", "N", "C", "K", "q", "v")
#: The at-rest path takes the norms behind residual and dropped for all points in one reduction:
#: they agree with linearize's to a few rounding errors of a sum of squares.
FIGURE_RTOL = 1e-13


def _assert_same(batched, single):
    for name in FIELDS:
        assert_array_equal(getattr(batched, name), getattr(single, name), err_msg=name)
    assert batched.residual == pytest.approx(single.residual, rel=FIGURE_RTOL, abs=1e-300)
    assert batched.dropped.keys() == single.dropped.keys()
    for key, value in single.dropped.items():
        assert batched.dropped[key] == pytest.approx(value, rel=FIGURE_RTOL)
    assert batched.calls == single.calls
    assert batched.notes == single.notes
    assert batched.dof_names == single.dof_names
    assert batched.method == single.method == "analytic"
    if single.balancing is None:
        assert batched.balancing is None
    else:
        assert_array_equal(batched.balancing, single.balancing)


def _pendulum_scene():
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf(1.3, 0.7, 0.9, 0.5))
    elements = [pinlin.JointSpring("joint1", 3.0, rest=0.1), pinlin.JointSpring("joint2", 2.0, rest=-0.2)]
    elements += [pinlin.JointDamper("joint1", 0.2), pinlin.JointDamper("joint2", 0.1)]
    elements.append(pinlin.FollowerWrench("tip", force=(0, 0, 4.0)))
    return pinlin.Scene(robot, elements)


def test_equilibria_of_a_loaded_pendulum_equal_single_calls():
    scene = _pendulum_scene()
    starts = ([0.0, 0.0], [0.3, -0.2], [-0.4, 0.5])
    qs = np.array([pinlin.find_equilibrium(scene, np.array(s)).q for s in starts])
    many = pinlin.linearize_many(scene, qs)
    assert len(many) == 3
    for q, sys in zip(qs, many):
        _assert_same(sys, pinlin.linearize(scene, q))
    # the closed-form check of one point: C is the dampers' diagonal, M is crba's
    assert_array_equal(many[0].D, np.diag([0.2, 0.1]))
    assert not many[0].G.any()


def test_floating_base_on_a_spring_mount_with_balancing():
    robot = pinlin.load_example("solo12", free_flyer=True)
    rest = next(iter(robot.reference_configurations.values()))
    elements = []
    for name in robot.joint_names:
        j = robot.joint(name)
        K = np.diag(np.arange(1.0, j.nv + 1.0)) * 50.0 if j.nv > 1 else 20.0
        elements += [pinlin.JointSpring(name, K, rest=rest[j.q_slice] if j.nq > 1 else 0.1), pinlin.JointDamper(name, 0.3)]
    scene = pinlin.Scene(robot, elements)
    pin.seed(7)  # numpy's rng does not seed Pinocchio
    qs = np.array([pin.randomConfiguration(robot.model, rest - 0.3, rest + 0.3) for _ in range(4)])
    many = pinlin.linearize_many(scene, qs, balancing=True)
    for q, sys in zip(qs, many):
        _assert_same(sys, pinlin.linearize(scene, q, balancing=True))
        assert sys.balancing is not None and np.abs(sys.balancing).max() > 0
    # off rest the free-flyer spring's stiffness is not symmetric: N is kept, and it is the single call's
    assert any(sys.N.any() for sys in many)


def test_turntable_with_a_prescribed_speed():
    a, m, k, l0, W = 0.5, 1.0, 10.0, 0.3, 2.0
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(a, m))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("slider", k, rest=l0)], prescribed={"table": W})
    r0 = (k * l0 + m * W**2 * a) / (k - m * W**2)
    qs = np.tile(scene.neutral(), (3, 1))
    qs[:, 3] = r0
    qs[1, :2] = [np.cos(0.7), np.sin(0.7)]  # the table turned: the proof makes it irrelevant
    many = pinlin.linearize_many(scene, qs)
    for q, sys in zip(qs, many):
        _assert_same(sys, pinlin.linearize(scene, q))
    # theory: turntable closed form on (arm, slider), at every table angle
    for sys in many:
        np.testing.assert_allclose(sys.M, np.diag([m * r0**2, m]), rtol=1e-14)
        np.testing.assert_allclose(sys.G, 2 * m * W * r0 * np.array([[0.0, 1.0], [-1.0, 0.0]]), rtol=1e-14)
        np.testing.assert_allclose(sys.S, np.diag([m * W**2 * a * r0, k - m * W**2]), rtol=1e-13)


def test_structure_tol_and_dropped_parts_follow_the_single_call():
    scene = _pendulum_scene()
    qs = np.array([[0.2, 0.1], [0.5, -0.3]])
    for tol in (0.0, 1e-30, 1e-6):
        many = pinlin.linearize_many(scene, qs, balancing=True, structure_tol=tol)
        for q, sys in zip(qs, many):
            _assert_same(sys, pinlin.linearize(scene, q, balancing=True, structure_tol=tol))


def test_systems_are_read_only():
    scene = _pendulum_scene()
    many = pinlin.linearize_many(scene, np.array([[0.2, 0.1], [0.5, -0.3]]), balancing=True)
    for name in ("M", "D", "G", "S", "N", "q"):
        a = getattr(many[0], name)
        with pytest.raises(ValueError, match="read-only"):
            a[0, 0] = 1.0
    with pytest.raises(ValueError, match="WRITEABLE|writeable"):
        many[1].S.setflags(write=True)  # a view of the batch's read-only stack
    assert many[0].elapsed > 0 and many[0].elapsed == many[1].elapsed


def test_bad_input():
    scene = _pendulum_scene()
    with pytest.raises(ConfigurationError, match=r"qs has shape \(2,\); .*\(P, nq\)"):
        pinlin.linearize_many(scene, [0.1, 0.2])
    with pytest.raises(ConfigurationError, match=r"qs has shape \(0, 2\)"):
        pinlin.linearize_many(scene, np.zeros((0, 2)))
    with pytest.raises(ConfigurationError, match="complex"):
        pinlin.linearize_many(scene, np.zeros((1, 2), dtype=complex))
    with pytest.raises(ConfigurationError, match="array of numbers"):
        pinlin.linearize_many(scene, [["a", "b"]])
    with pytest.raises(ConfigurationError, match=r"qs\[1\] has non-finite entries"):
        pinlin.linearize_many(scene, [[0.1, 0.2], [np.nan, 0.0]], balancing=True)
    with pytest.raises(ParameterError, match="equilibrium_tol"):
        pinlin.linearize_many(scene, [[0.1, 0.2]], equilibrium_tol=-1.0)
    q_eq = pinlin.find_equilibrium(scene, np.zeros(2)).q
    with pytest.raises(NotAnEquilibriumError, match="not an equilibrium"):
        pinlin.linearize_many(scene, [q_eq, q_eq + 0.3])
    ghost = MASSLESS_LINK_URDF
    massless = pinlin.Scene(pinlin.load_urdf_string(ghost))
    with pytest.raises(SingularMassError, match=r"joints \['ghost_joint'\].*lock them"):
        pinlin.linearize_many(massless, np.zeros((2, 2)))


def test_constrained_scene_is_linearized_point_by_point():
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    spring = pinlin.JointSpring("crank_joint", 40.0, rest=0.2)
    scene = pinlin.Scene(robot, [spring], constraints=[pinlin.PointConstraint("rocker_tip", (0.7, 0, 0), name="loop")])
    qs = np.array([pinlin.find_equilibrium(scene, pinlin.close_loops(scene, s).q).q for s in ([0.3, 0.2, -0.4], [0.5, 0.1, -0.6])])
    many = pinlin.linearize_many(scene, qs)
    for q, sys in zip(qs, many):
        _assert_same(sys, pinlin.linearize(scene, q))
        assert_array_equal(sys.basis, pinlin.linearize(scene, q).basis)


def test_paths_and_repeated_or_scattered_springs():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(4, radius=0.02))
    springs = [pinlin.JointSpring("joint1", 4.0, rest=0.1), pinlin.JointSpring("joint3", 2.0, rest=-0.2),
               pinlin.JointSpring("joint3", 1.5, rest=0.3), pinlin.JointSpring("joint4", [[3.0]], rest=0.05)]
    scattered = pinlin.Scene(robot, springs + [pinlin.JointDamper("joint2", 0.4), pinlin.JointDamper("joint2", 0.1)])
    rayleigh = pinlin.Scene(robot, springs + [pinlin.RayleighDamping(alpha=0.2, beta=0.01)])
    gaps = pinlin.Scene(robot, springs[:2] + springs[3:])  # unique joints, not consecutive: fancy indices
    assert batch_static.applies(scattered) and batch_static.applies(gaps) and not batch_static.applies(rayleigh)
    spring_group = gaps.groups[0]
    assert spring_group.unique and not spring_group.v_slice and spring_group.diagonal.span is None
    groups = {type(g).__name__: g for g in scattered.groups}
    assert not groups["SpringGroup"].unique and not groups["DamperGroup"].unique  # the np.add.at paths
    qs = np.random.default_rng(11).uniform(-0.6, 0.6, size=(5, robot.nq))
    for scene in (scattered, gaps, rayleigh):
        many = pinlin.linearize_many(scene, qs, balancing=True)
        for q, sys in zip(qs, many):
            _assert_same(sys, pinlin.linearize(scene, q, balancing=True))
    # the dampers' closed form: C = diag(0, 0.5, 0, 0) at every point
    assert_array_equal(pinlin.linearize_many(scattered, qs, balancing=True)[3].D, np.diag([0.0, 0.5, 0.0, 0.0]))


@pytest.mark.parametrize("size", [4, 36])  # math.hypot up to SMALL_NORM entries, a dot product beyond
def test_norms_closed_form_and_overflow(size):
    from pinlin.numerics.norms import SMALL_NORM, fro

    assert (size <= SMALL_NORM) == (size == 4)
    for scale in (1.0, 1e-100, 3e200):  # 3e200: the squares overflow, the norm does not
        a = np.zeros(size)
        a[:2] = [3.0 * scale, 4.0 * scale]  # norm 5 scale (a Pythagorean triple)
        assert fro(a.reshape(2, -1)) == pytest.approx(5.0 * scale, rel=4e-16)
        stack = np.stack([a, 2 * a, np.zeros(size)]).reshape(3, 2, -1)
        np.testing.assert_allclose(batch_common.norms(stack), [5.0 * scale, 10.0 * scale, 0.0], rtol=4e-16)
    bad = np.ones(size)
    bad[1] = np.inf
    assert fro(bad) == np.inf and np.isinf(batch_common.norms(bad.reshape(1, 2, -1))[0])
    bad[1] = np.nan
    assert not np.isfinite(fro(bad)) and not np.isfinite(batch_common.norms(bad.reshape(1, 2, -1))[0])


def test_bitwise_identical_from_eight_threads():
    from concurrent.futures import ThreadPoolExecutor

    turntable = _turntable([pinlin.JointDamper("slider", 0.4)])  # the steady-motion path
    turned = np.tile(turntable.neutral(), (6, 1))
    turned[:, 2:] = np.random.default_rng(4).uniform(-0.5, 0.5, size=(6, 2))
    for scene, qs in ((_pendulum_scene(), np.random.default_rng(4).uniform(-0.5, 0.5, size=(6, 2))), (turntable, turned)):
        reference = pinlin.linearize_many(scene, qs, balancing=True)
        with ThreadPoolExecutor(8) as pool:
            runs = list(pool.map(lambda _, scene=scene, qs=qs: pinlin.linearize_many(scene, qs, balancing=True), range(32)))
        for run in runs:
            for sys, ref in zip(run, reference):
                for name in ("M", "D", "G", "S", "N", "balancing"):
                    assert_array_equal(getattr(sys, name), getattr(ref, name))
                assert sys.residual == ref.residual and sys.dropped == ref.dropped


#: A body of 2 kg with a 1 kg bar on a revolute joint; with free_flyer=True a floating base (quaternion in q[3:7]).
FLOATING_ARM = """<robot name="floating_arm">
  <link name="body"><inertial><mass value="2.0"/><origin xyz="0 0 0"/>
    <inertia ixx="0.02" iyy="0.03" izz="0.04" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="bar"><inertial><mass value="1.0"/><origin xyz="0 0 -0.25"/>
    <inertia ixx="0.021" iyy="0.021" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="hinge" type="revolute"><parent link="body"/><child link="bar"/><axis xyz="0 1 0"/>
    <origin xyz="0.1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"""


def _floating_pendulum_scene():
    robot = pinlin.load_urdf_string(FLOATING_ARM, free_flyer=True)
    mount = robot.joint_names[0]
    elements = [pinlin.JointSpring(mount, np.diag([40.0, 50.0, 60.0, 7.0, 8.0, 9.0]), rest=robot.neutral()[:7])]
    elements += [pinlin.JointSpring(name, 3.0, rest=0.1) for name in robot.joint_names[1:]]
    elements += [pinlin.JointDamper(name, 0.2) for name in robot.joint_names]
    return pinlin.Scene(robot, elements)


def test_configurations_are_checked_and_normalized_on_the_stack_as_single_checks():
    from pinlin.linearization.batch import LENGTH_MARGIN, configurations
    from pinlin.model.scene import ANGLE_LIMIT, UNIT_NORM_MIN

    scene = _floating_pendulum_scene()
    qs = np.random.default_rng(7).uniform(-0.5, 0.5, size=(5, scene.robot.nq))
    qs[:, 3:7] *= [[1.0], [3.0], [0.2], [1.0], [1.0]]  # quaternions of lengths ~0.5 to ~3: normalized
    qs[3, 3:7] = [0.0, 0.0, 0.0, 2.0 * UNIT_NORM_MIN]  # short, accepted
    qs[4, 3:7] = [0.0, 0.0, UNIT_NORM_MIN * (1 + 1e-15), 0.0]  # within the margin: the single check decides
    assert UNIT_NORM_MIN * (1 + 1e-15) < UNIT_NORM_MIN * LENGTH_MARGIN
    given, rows = qs.copy(), configurations(scene, qs)
    assert_array_equal(qs, given)  # the caller's array: untouched, and not shared
    assert not np.shares_memory(rows, qs)
    for q, row in zip(qs, rows):
        assert_array_equal(row, scene.check_configuration(q))
    np.testing.assert_allclose(np.linalg.norm(rows[:, 3:7], axis=1), 1.0, rtol=4e-16)
    many = pinlin.linearize_many(scene, qs, balancing=True)
    for q, sys in zip(qs, many):
        _assert_same(sys, pinlin.linearize(scene, q, balancing=True))
    bad = qs.copy()
    bad[2, 3:7], bad[4, 3:7] = 0.0, [0.0, 0.0, 0.5 * UNIT_NORM_MIN, 0.0]
    with pytest.raises(ConfigurationError, match=r"qs\[2\]\[3:7\] = \[0.0, 0.0, 0.0, 0.0\] of joint .* not a rotation"):
        pinlin.linearize_many(scene, bad)
    bad = qs.copy()
    bad[1, 7] = 2.0 * ANGLE_LIMIT  # a revolute angle beyond the limit on row 1, a NaN on row 3
    bad[3, 0] = np.nan
    with pytest.raises(ConfigurationError, match=r"qs\[1\]\[7\] = .* rad on revolute joint .* beyond"):
        pinlin.linearize_many(scene, bad)
    bad[1, 7] = 0.0
    with pytest.raises(ConfigurationError, match=r"qs\[3\] has non-finite entries at \[0\]"):
        pinlin.linearize_many(scene, bad)


def test_systems_hold_the_single_calls_attributes():
    scene = _pendulum_scene()
    qs = np.array([[0.2, 0.1], [0.5, -0.3], [-0.1, 0.4]])
    many = pinlin.linearize_many(scene, qs, balancing=True)
    for q, sys in zip(qs, many):
        single = pinlin.linearize(scene, q, balancing=True)
        assert vars(sys).keys() == vars(single).keys()  # C and K not formed yet on either
        assert list(sys.dropped) == list(single.dropped)  # in the same order
        _assert_same(sys, single)
    assert many[0].D is many[2].D  # the scene's constant damping: one read-only view for the batch
    assert all(sys.N.any() for sys in many)  # the follower load is circulatory: N kept, a view of the batch's stack
    many[1].dropped["N"] = 1.0  # each system has a dictionary of its own
    assert "N" not in many[2].dropped and "N" not in many[0].dropped


def test_without_gravity_or_wrenches_and_with_an_upper_triangle_crba(monkeypatch):
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3, radius=0.02))
    springs = [pinlin.JointSpring(f"joint{i}", 2.0 * i, rest=(0.1, 0.2, 0.3)[i - 1]) for i in (1, 2, 3)]
    scene = pinlin.Scene(robot, springs + [pinlin.JointDamper("joint2", 0.3)], gravity=(0.0, 0.0, 0.0))
    qs = np.array([[0.1, 0.2, 0.3], [0.0, 0.4, 0.9]])
    many = pinlin.linearize_many(scene, qs, balancing=True)  # the first row is the springs' rest: r = 0
    assert many[0].residual == 0.0 and not many[0].balancing.any() and many[1].balancing.any()
    for q, sys in zip(qs, many):
        _assert_same(sys, pinlin.linearize(scene, q, balancing=True))
        assert sys.calls == ("crba",)
        assert_array_equal(sys.S, np.diag([2.0, 4.0, 6.0]))  # the springs alone, exactly
    # a Pinocchio whose crba fills only the upper triangle: the stack is mirrored, as linearize mirrors it
    monkeypatch.setattr(batch_static, "crba_is_symmetric", lambda: False)
    for q, sys in zip(qs, pinlin.linearize_many(scene, qs, balancing=True)):
        _assert_same(sys, pinlin.linearize(scene, q, balancing=True))


def test_decisions_at_the_tolerance_are_the_single_calls():
    """A tolerance equal to a point's own figure: the single call accepts (<=), one ulp below it refuses or keeps N."""
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(4, radius=0.02))
    scene = pinlin.Scene(robot, [pinlin.JointSpring(f"joint{i}", 30.0, rest=0.3) for i in (1, 2, 3, 4)])
    starts = [np.random.default_rng(seed).uniform(-0.5, 0.5, 4) for seed in range(3)]
    qs = np.array([pinlin.find_equilibrium(scene, start).q for start in starts])
    singles = [pinlin.linearize(scene, q) for q in qs]
    assert all(s.residual > 0 and s.dropped["N"] > 0 for s in singles)  # gravity's K: N at rounding level, dropped
    worst = max(s.residual for s in singles)
    many = pinlin.linearize_many(scene, qs, equilibrium_tol=worst)
    for sys, single in zip(many, singles):
        _assert_same(sys, single)
    assert max(sys.residual for sys in many) == worst  # the deciding figure taken as the single call takes it
    with pytest.raises(NotAnEquilibriumError, match="not an equilibrium"):
        pinlin.linearize_many(scene, qs, equilibrium_tol=float(np.nextafter(worst, 0.0)))
    for single, q in zip(singles, qs):
        size = single.dropped["N"]
        for tol in (size, float(np.nextafter(size, 0.0))):
            sys = pinlin.linearize_many(scene, q[None], structure_tol=tol)[0]
            _assert_same(sys, pinlin.linearize(scene, q, structure_tol=tol))
            assert sys.N.any() == (tol < size)  # kept one ulp below its size, dropped at it
            assert sys.dropped == ({"N": size} if tol == size else {})


def _turntable(elements=(), gravity=(0.0, 0.0, -9.81)):
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(0.5, 1.0))
    springs = [pinlin.JointSpring("slider", 10.0, rest=0.3), pinlin.JointSpring("arm", 4.0, rest=0.1)]
    return pinlin.Scene(robot, springs + list(elements), prescribed={"table": 2.0}, gravity=gravity)


def test_steady_motions_are_stacked_and_equal_single_calls():
    from pinlin.linearization import batch_moving

    dampers = [pinlin.JointDamper("slider", 0.4), pinlin.JointDamper("table", 0.7), pinlin.JointDamper("arm", 0.2)]
    follower = pinlin.FollowerWrench("particle", force=(0.0, 0.5, 0.0), torque=(0.0, 0.0, 0.3))
    damped, undamped = _turntable(dampers + [follower]), _turntable()
    tilted = _turntable(dampers, gravity=(1.0, 0.0, -9.81))  # gravity off the table's axis: time-periodic
    assert batch_moving.applies(damped, 1e-8) and batch_moving.applies(undamped, 1e-8)
    assert not batch_moving.applies(tilted, 1e-8) and not plan_of(damped).undamped
    qs = np.tile(damped.neutral(), (4, 1))
    qs[:, 2:] = np.random.default_rng(3).uniform(-0.8, 0.8, size=(4, 2))
    qs[1, :2] = [np.cos(0.7), np.sin(0.7)]  # the table turned: the proof makes it irrelevant
    with pytest.raises(TimePeriodicError, match="depend on the position of prescribed joint 'table'"):
        pinlin.linearize_many(tilted, qs, balancing=True)  # point by point: linearize's numerical check
    for scene in (damped, undamped):
        for tol in (None, 0.0, 1e-30, 1e-6):
            many = pinlin.linearize_many(scene, qs, balancing=True, structure_tol=tol)
            for q, sys in zip(qs, many):
                single = pinlin.linearize(scene, q, balancing=True, structure_tol=tol)
                _assert_same(sys, single)
                assert vars(sys).keys() == vars(single).keys() and list(sys.dropped) == list(single.dropped)
    # the table's damper holds the table against its prescribed speed: a force off the free rows, in the scale only
    sys = pinlin.linearize_many(damped, qs[:1], balancing=True)[0]
    assert sys.calls == ("computeRNEADerivatives",) and "by symmetry" in sys.notes[0]
    np.testing.assert_allclose(sys.D, np.diag([0.2, 0.4]), rtol=0, atol=1e-15)  # the dampers: Coriolis D dropped
    assert sys.G.any() and sys.N.any()  # Coriolis G kept; the follower's circulatory N kept


def test_steady_motion_errors_name_the_first_bad_point():
    scene = _turntable([pinlin.JointDamper("slider", 0.4)])
    q = pinlin.find_equilibrium(scene, scene.neutral()).q
    qs = np.array([q, q + [0.0, 0.0, 0.0, 0.2], q])
    first = pinlin.linearize_many(scene, qs[:1])[0]
    _assert_same(first, pinlin.linearize(scene, q))
    # the slider 0.2 m off: (k - m Omega^2) 0.2 = (10 - 4) 0.2 = 1.2 N unbalanced (theory: turntable)
    with pytest.raises(NotAnEquilibriumError, match=r"relative residual .*\(largest unbalanced force 1.2 on 'slider'\)"):
        pinlin.linearize_many(scene, qs)
    with pytest.raises(ConfigurationError, match=r"qs\[1\]\[0:2\] = \[0.0, 0.0\] of joint 'table' is not a rotation"):
        pinlin.linearize_many(scene, np.array([q, np.zeros(4)]))


def test_large_batches_are_taken_in_chunks(monkeypatch):
    from pinlin.linearization import batch

    scene = _pendulum_scene()
    monkeypatch.setattr(batch, "CHUNK_ENTRIES", 2 * 2**2)  # chunks of two points (nv = 2)
    qs = np.random.default_rng(5).uniform(-0.5, 0.5, size=(5, 2))
    many = pinlin.linearize_many(scene, qs, balancing=True)
    assert len(many) == 5
    for q, sys in zip(qs, many):
        _assert_same(sys, pinlin.linearize(scene, q, balancing=True))
    assert many[2].elapsed == many[3].elapsed  # a chunk's time per point
    q_eq = pinlin.find_equilibrium(scene, np.zeros(2)).q
    rows = np.array([q_eq, q_eq, q_eq, q_eq + [0.0, 0.3], q_eq])  # the fourth point, in the second chunk
    with pytest.raises(NotAnEquilibriumError, match="not an equilibrium"):
        pinlin.linearize_many(scene, rows)
    assert len(pinlin.linearize_many(scene, rows[:3])) == 3


def _stack_of_three(M):
    return LinearizedSystem.stack(M=M, D=np.zeros((2, 2)), G=np.zeros((2, 2)), S=np.eye(2), N=np.zeros((2, 2)),
                                  dof_names=("a", "b"), residual=[0.0] * 3, dropped=[{}, {}, {}],
                                  notes=[(), (), ()])  # fmt: skip


def test_nearly_singular_mass_matrices_are_decided_by_the_single_matrix_cholesky(monkeypatch):
    seen = []
    single_check = matrices._positive_definite
    monkeypatch.setattr(matrices, "_positive_definite", lambda M: seen.append(M.copy()) or single_check(M))
    delta = 1e-10  # [[1, 1 - delta], [1 - delta, 1]]: second pivot 2 delta - delta^2, below PIVOT_MARGIN
    near = np.array([[1.0, 1.0 - delta], [1.0 - delta, 1.0]])
    assert 2 * delta < matrices.PIVOT_MARGIN
    assert len(_stack_of_three(np.stack([np.eye(2), near, np.diag([2.0, 3.0])]))) == 3
    assert len(seen) == 1  # only the close one, and it passes (positive definite)
    assert_array_equal(seen[0], near)
    indefinite = np.array([[1.0, 2.0], [2.0, 1.0]])  # eigenvalues 3 and -1
    with pytest.raises(SingularMassError, match=r"smallest eigenvalue -1\).*coordinates \['a', 'b'\]"):
        _stack_of_three(np.stack([np.eye(2), indefinite, near]))
