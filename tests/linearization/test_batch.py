"""linearize_many: one scene at many configurations equals linearize point by point, bitwise (issue 14)."""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_array_equal

import pinlin
from helpers import MASSLESS_LINK_URDF
from pinlin.errors import ConfigurationError, NotAnEquilibriumError, ParameterError, SingularMassError
from pinlin.linearization import batch_static

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
    # SPEC 7.2 closed form on (arm, slider), at every table angle
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
    from pinlin.linearization.assembly import SMALL_NORM, fro

    assert (size <= SMALL_NORM) == (size == 4)
    for scale in (1.0, 1e-100, 3e200):  # 3e200: the squares overflow, the norm does not
        a = np.zeros(size)
        a[:2] = [3.0 * scale, 4.0 * scale]  # norm 5 scale (a Pythagorean triple)
        assert fro(a.reshape(2, -1)) == pytest.approx(5.0 * scale, rel=4e-16)
        stack = np.stack([a, 2 * a, np.zeros(size)]).reshape(3, 2, -1)
        np.testing.assert_allclose(batch_static._norms(stack), [5.0 * scale, 10.0 * scale, 0.0], rtol=4e-16)
    bad = np.ones(size)
    bad[1] = np.inf
    assert fro(bad) == np.inf and np.isinf(batch_static._norms(bad.reshape(1, 2, -1))[0])
    bad[1] = np.nan
    assert not np.isfinite(fro(bad)) and not np.isfinite(batch_static._norms(bad.reshape(1, 2, -1))[0])


def test_bitwise_identical_from_eight_threads():
    from concurrent.futures import ThreadPoolExecutor

    scene = _pendulum_scene()
    qs = np.random.default_rng(4).uniform(-0.5, 0.5, size=(6, 2))
    reference = pinlin.linearize_many(scene, qs, balancing=True)
    with ThreadPoolExecutor(8) as pool:
        runs = list(pool.map(lambda _: pinlin.linearize_many(scene, qs, balancing=True), range(32)))
    for run in runs:
        for sys, ref in zip(run, reference):
            for name in ("M", "D", "G", "S", "N", "balancing"):
                assert_array_equal(getattr(sys, name), getattr(ref, name))
            assert sys.residual == ref.residual and sys.dropped == ref.dropped
