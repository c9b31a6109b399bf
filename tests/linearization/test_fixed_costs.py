"""linearize's fixed costs paid once per scene: each cheaper route against the general one.

The mirror of Pinocchio's upper-triangular M by flat indices against ``np.where``,
the split of a block view against the split of its copy, and halving by the 0-d
``HALF`` against a Python float, each on inputs where the two could differ.
"""

import numpy as np
import pinocchio as pin
import pytest

import pinlin
from pinlin.linearization import batch_moving, batch_static
from pinlin.linearization.system import LinearizedSystem
from pinlin.linearization.split import split_stiffness
from pinlin.model.evaluation import live_view, symmetric_from_upper, workspace
from pinlin.numerics.arrays import HALF


def _turntable():
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(0.5, 1.0))
    return pinlin.Scene(robot, [pinlin.JointSpring("slider", 10.0, rest=0.3)], prescribed={"table": 2.0})


def test_mirror_by_flat_indices_is_np_where_on_a_lower_triangle_of_garbage():
    """The lower triangle Pinocchio leaves is arbitrary: only the upper one may reach the result."""
    scene = pinlin.Scene(pinlin.load_example("panda"), [])
    ws = workspace(scene)
    nv = scene.model.nv
    rng = np.random.default_rng(7)
    a = np.asfortranarray(rng.standard_normal((nv, nv)))  # Data's matrices are column-major
    before = a.copy()
    M = symmetric_from_upper(a, ws)
    assert np.array_equal(M, np.where(ws.lower, a.T, a))
    assert np.array_equal(M, M.T) and M.flags.c_contiguous and M.flags.owndata
    assert np.array_equal(a, before) and not np.array_equal(a, a.T)


def test_split_of_a_block_view_equals_the_split_of_its_copy():
    rng = np.random.default_rng(3)
    big = rng.standard_normal((5, 5))
    view = big[1:4, 1:4]
    assert not view.flags.c_contiguous
    for tol in (0.0, 1e3):  # the skew part kept, and dropped (reported)
        kept_view, kept_copy = {}, {}
        S1, N1 = split_stiffness(view, 1.0, tol, kept_view)
        S2, N2 = split_stiffness(view.copy(), 1.0, tol, kept_copy)
        assert np.array_equal(S1, S2) and np.array_equal(N1, N2) and kept_view == kept_copy
        assert np.array_equal(S1, (view + view.T) / 2)
    assert np.array_equal(big[1:4, 1:4], view)  # the input untouched


def test_halving_by_the_zero_dimensional_half_is_the_float_product():
    rng = np.random.default_rng(5)
    for a in (rng.standard_normal((3, 3)) * 1e300, np.array([[5e-324, -3.3e-320], [np.inf, 1.0]])):
        by_half, by_float = a.copy(), a.copy()
        by_half *= HALF
        by_float *= 0.5
        assert by_half.dtype == np.float64 and np.array_equal(by_half, by_float)
    assert not HALF.flags.writeable


def test_turntable_gyroscopic_part_from_a_strided_block_is_the_closed_form():
    """The turntable's C is a strided block of dtau/dv; G = 2 m Omega r0 [[0, 1], [-1, 0]], D = 0 (theory: turntable)."""
    a, m, k, l0, W = 0.5, 1.0, 10.0, 0.3, 2.0
    scene = _turntable()
    r0 = (k * l0 + m * W**2 * a) / (k - m * W**2)
    q = scene.neutral()
    q[3] = r0
    sys = pinlin.linearize(scene, q)
    np.testing.assert_allclose(sys.G, 2 * m * W * r0 * np.array([[0.0, 1.0], [-1.0, 0.0]]), rtol=1e-14, atol=1e-14)
    assert not sys.D.any() and np.array_equal(sys.G, -sys.G.T)
    np.testing.assert_allclose(sys.M, np.diag([m * r0**2, m]), rtol=1e-14, atol=1e-14)


def test_linearized_system_equals_the_validating_constructor_on_its_fields():
    """linearize builds its result through LinearizedSystem.stack, the constructor's own path: the same attributes,
    key for key, in the same order, all arrays read-only."""
    scene = _turntable()
    q = scene.neutral()
    q[3] = 0.5
    sys = pinlin.linearize(scene, q, balancing=True)
    reference = LinearizedSystem(**{name: getattr(sys, name) for name in vars(sys) if name not in ("C", "K")})
    ours, theirs = vars(sys), vars(reference)
    assert list(ours)[:19] == list(theirs)[:19]
    for key, value in theirs.items():
        if isinstance(value, np.ndarray):
            assert np.array_equal(ours[key], value) and not ours[key].flags.writeable, key
        else:
            assert type(ours[key]) is type(value) and ours[key] == value, key
    assert sys.balancing is not None and sys.notes[-1].startswith("held at q")


def test_stack_refuses_a_non_symmetric_damping_at_one_point():
    """The batch check names the matrix and the defect, as the constructor does for one system."""
    M = np.stack([np.eye(2), np.eye(2)])
    D = np.stack([np.zeros((2, 2)), np.array([[0.0, 1.0], [0.0, 0.0]])])
    with pytest.raises(pinlin.ParameterError, match="D.*must be symmetric; relative defect 1.41e"):
        LinearizedSystem.stack(M=M, D=D, G=np.zeros((2, 2)), S=np.eye(2), N=np.zeros((2, 2)), dof_names=("a", "b"),
                               residual=[0.0, 0.0], dropped=[{}, {}], notes=[(), ()])  # fmt: skip
    M = np.stack([np.eye(2), np.diag([1.0, 0.0])])
    with pytest.raises(pinlin.SingularMassError, match=r"carry no inertia"):
        LinearizedSystem.stack(M=M, D=np.zeros((2, 2)), G=np.zeros((2, 2)), S=np.eye(2), N=np.zeros((2, 2)),
                               dof_names=("a", "b"), residual=[0.0, 0.0], dropped=[{}, {}], notes=[(), ()])  # fmt: skip


def test_live_view_of_data_follows_each_pass():
    scene = pinlin.Scene(pinlin.load_example("ur5"), [])
    model, data = scene.model, workspace(scene).data
    view, live = live_view(data, "g")
    assert live
    for q in (np.full(model.nq, 0.3), np.full(model.nq, -0.7)):
        g = pin.computeGeneralizedGravity(model, data, q).copy()
        assert np.array_equal(view, g)


@pytest.mark.parametrize("moving", [False, True])
def test_batch_reads_data_after_each_pass_when_the_binding_copies(monkeypatch, moving):
    """The fallback of live_view (a binding that copies Data's vectors): the same systems as the live view's."""
    if moving:
        scene = _turntable()
        qs = np.tile(scene.neutral(), (3, 1))
        qs[:, 3] = (0.5, 0.7, 0.9)
        module = batch_moving
    else:
        scene = pinlin.Scene(pinlin.load_example("ur5"), [pinlin.FollowerWrench("tool0", force=(0.0, 0.0, 5.0))])
        qs = np.array([np.full(6, 0.1 * k) for k in range(1, 4)])
        module = batch_static
    live = pinlin.linearize_many(scene, qs, balancing=True)

    def copying(data, name):  # a stale copy: used at any point, it would give the first point's forces to all
        return getattr(data, name).copy(), False

    monkeypatch.setattr(module, "live_view", copying)
    copied = pinlin.linearize_many(scene, qs, balancing=True)
    for a, b, q in zip(live, copied, qs):
        assert np.array_equal(a.balancing, b.balancing) and np.array_equal(a.K, b.K)
        assert np.array_equal(b.balancing, pinlin.linearize(scene, q, balancing=True).balancing)
    assert not np.array_equal(copied[0].balancing, copied[2].balancing)


PLANAR_URDF = """<robot name="sled"><link name="base"/>
  <link name="sled"><inertial><mass value="2"/><origin xyz="0.1 0 0"/>
    <inertia ixx="0.1" iyy="0.2" izz="0.3" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><mass value="1"/><origin xyz="0 0 -0.4"/>
    <inertia ixx="0.05" iyy="0.05" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="slide" type="planar"><parent link="base"/><child link="sled"/><axis xyz="0 0 1"/></joint>
  <joint name="hinge" type="revolute"><parent link="sled"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint></robot>"""


@pytest.mark.parametrize("root", ["free_flyer", "planar"])
def test_batched_logs_of_multi_dof_springs_equal_single_calls(root):
    """linearize_many evaluates a multi-DOF spring's log on all rows at once: each system is linearize's, bitwise,
    at deflections across the log's branches (the series buckets of beta and gamma, the closed form, rest itself)."""
    if root == "planar":
        robot = pinlin.load_urdf_string(PLANAR_URDF)
        joint, deflections = "slide", [0.0, 1e-5, 0.2, 2.5]
    else:
        robot = pinlin.load_example("solo12", free_flyer=True)
        joint, deflections = "root_joint", [0.0, 1e-5, 0.2, 1.2, 2.5]
    info = robot.joint(joint)
    rng = np.random.default_rng(23)
    A = rng.normal(size=(info.nv, info.nv))
    rest = pin.neutral(robot.model)
    scene = pinlin.Scene(robot, [pinlin.JointSpring(joint, A @ A.T + np.eye(info.nv), rest=rest[info.q_slice])])
    qs = []
    for angle in deflections:
        xi = np.zeros(robot.model.nv)
        xi[info.v_slice] = rng.normal(size=info.nv)
        rotation = info.v_slice.start + (2 if root == "planar" else 3)
        turn = np.linalg.norm(xi[rotation : info.v_slice.stop])
        xi[rotation : info.v_slice.stop] *= angle / turn
        qs.append(pin.integrate(robot.model, rest, xi))
    assert batch_static.applies(scene)  # the stacked path, whose springs take the batched log
    many = pinlin.linearize_many(scene, np.array(qs), balancing=True)
    for q, sys in zip(qs, many):
        single = pinlin.linearize(scene, q, balancing=True)
        for name in ("M", "D", "G", "S", "N"):
            assert np.array_equal(getattr(sys, name), getattr(single, name)), name
        assert np.array_equal(sys.balancing, single.balancing)


def test_chunks_share_the_batched_log_each_reading_its_own_rows(monkeypatch):
    """With several chunks the log is evaluated once for the call: every point still gets its own (bitwise)."""
    from pinlin.linearization import batch

    robot = pinlin.load_example("solo12", free_flyer=True)
    info = robot.joint("root_joint")
    rest = pin.neutral(robot.model)
    scene = pinlin.Scene(robot, [pinlin.JointSpring("root_joint", 50.0, rest=rest[info.q_slice])])
    rng = np.random.default_rng(29)
    qs = []
    for _ in range(7):
        xi = np.zeros(robot.model.nv)
        xi[info.v_slice] = 0.3 * rng.normal(size=6)
        qs.append(pin.integrate(robot.model, rest, xi))
    monkeypatch.setattr(batch, "CHUNK_ENTRIES", 3 * robot.model.nv**2)  # chunks of 3, 3 and 1 points
    calls = []
    evaluate_many = type(scene.groups[0].prepared[0][3]).evaluate_many
    monkeypatch.setattr(type(scene.groups[0].prepared[0][3]), "evaluate_many",
                        lambda log, rows: calls.append(len(rows)) or evaluate_many(log, rows))  # fmt: skip
    many = pinlin.linearize_many(scene, np.array(qs), balancing=True)
    assert calls == [7]  # once for the call, all rows
    for q, sys in zip(qs, many):
        single = pinlin.linearize(scene, q, balancing=True)
        assert np.array_equal(sys.K, single.K) and np.array_equal(sys.balancing, single.balancing)


@pytest.mark.parametrize("n", [3, 6])
def test_stacked_products_are_the_single_calls_dot_row_by_row(n):
    """linearize_many's spring products (np.matmul on stacks) against np.dot per row, bitwise, with entries
    spread over many decades (where a different summation order would show)."""
    rng = np.random.default_rng(31 + n)
    for _ in range(20):
        Ks = rng.normal(size=(n, n)) * 10.0 ** rng.uniform(-3, 3, size=(n, n))
        P = int(rng.integers(1, 60))
        E = rng.normal(size=(P, n)) * 10.0 ** rng.uniform(-8, 2, size=(P, n))
        J = rng.normal(size=(P, n, n)) * 10.0 ** rng.uniform(-4, 4, size=(P, n, n))
        forces, stiffnesses = np.matmul(Ks, E[:, :, None])[:, :, 0], np.matmul(Ks, J)
        for p in range(P):
            assert np.array_equal(forces[p], np.dot(Ks, E[p])) and np.array_equal(stiffnesses[p], np.dot(Ks, J[p]))
