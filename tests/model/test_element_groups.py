"""Joint spring and damper groups: data prepared once per scene against the elements' own methods.

The groups must give bitwise what the elements compute one by one (their
``generalized_force``, ``add_stiffness``, ``add_damping``), on every joint kind
(free-flyer, spherical, planar, continuous, revolute), at random configurations
and velocities, with repeated springs and dampers on one joint.
"""

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_array_equal

import pinlin
from pinlin.linearization.assembly import assemble
from pinlin.linearization.plan import plan_of
from pinlin.model.elements.base import DiagonalIndex, contiguous
from pinlin.model.elements.joint_damper import DamperGroup
from pinlin.model.elements.joint_spring import SpringGroup
from pinlin.model.evaluation import Evaluation
from pinlin.numerics.arrays import readonly


def _tree_robot() -> pinlin.Robot:
    """Free-flyer root, then a spherical, a planar, a continuous and two revolute joints (nv = 6+3+3+1+1+1)."""
    model = pin.Model()
    joints = [
        ("root", pin.JointModelFreeFlyer()),
        ("ball", pin.JointModelSpherical()),
        ("plane", pin.JointModelPlanar()),
        ("wheel", pin.JointModelRUBZ()),
        ("hinge", pin.JointModelRX()),
        ("elbow", pin.JointModelRY()),
    ]
    parent = 0
    for k, (name, joint) in enumerate(joints):
        placement = pin.SE3(np.eye(3), np.array([0.1, 0.0, -0.3 * (k > 0)]))
        parent = model.addJoint(parent, joint, placement, name)
        inertia = pin.Inertia(1.0 + k, np.array([0.0, 0.02, -0.1]), np.diag([0.02, 0.03, 0.01 + 0.01 * k]))
        model.appendBodyToJoint(parent, inertia, pin.SE3.Identity())
    return pinlin.Robot(model, "<tree>")


def _random_rest(robot: pinlin.Robot, name: str, rng: np.random.Generator):
    j = robot.joint(name)
    if j.nq == 1:
        return float(rng.uniform(-1, 1))
    lo, hi = -np.ones(robot.nq), np.ones(robot.nq)
    pin.seed(int(rng.integers(2**31 - 1)))  # numpy's rng does not seed Pinocchio
    return pin.randomConfiguration(robot.model, lo, hi)[j.q_slice]


def _psd(n: int, rng: np.random.Generator) -> np.ndarray:
    A = rng.normal(size=(n, n))
    return A @ A.T + n * np.eye(n)


def _elements(robot: pinlin.Robot, rng: np.random.Generator) -> list:
    """Springs with scalar, diagonal and full stiffness, dampers likewise; repeated on 'ball' and 'hinge'."""
    out = []
    for name in robot.joint_names:
        nv = robot.joint(name).nv
        rest = _random_rest(robot, name, rng)
        out.append(pinlin.JointSpring(name, _psd(nv, rng), rest=rest))
        out.append(pinlin.JointDamper(name, rng.uniform(0.1, 1.0, size=nv) if nv > 1 else 0.3))
    out.append(pinlin.JointSpring("ball", 7.0, rest=_random_rest(robot, "ball", rng)))
    out.append(pinlin.JointSpring("hinge", 3.0, rest=0.2))  # a second 1-DOF spring on one joint
    out.append(pinlin.JointSpring("hinge", 5.0))
    out.append(pinlin.JointSpring("elbow", [[4.0]], rest=-0.3))  # 1 x 1 matrix: the prepared path
    out.append(pinlin.JointDamper("hinge", 0.7))  # repeated damper
    out.append(pinlin.JointDamper("ball", _psd(3, rng)))
    return out


def _one_by_one(elements, ev: Evaluation, nv: int):
    """(Q, K, C, K_e) from the elements' own methods, element by element in scene order."""
    Q, K, C, Ke = np.zeros(nv), np.zeros((nv, nv)), np.zeros((nv, nv)), np.zeros((nv, nv))
    for e in elements:
        Q += e.generalized_force(ev)
        e.add_stiffness(ev, K)
        e.add_damping(ev, C)
        e.add_elastic_stiffness(ev, Ke)
    return Q, K, C, Ke


@pytest.mark.parametrize("seed", range(6))
def test_prepared_groups_equal_the_elements_bitwise(seed):
    rng = np.random.default_rng(seed)
    robot = _tree_robot()
    elements = _elements(robot, rng)
    scene = pinlin.Scene(robot, elements, gravity=(0, 0, 0))
    assert {type(g) for g in scene.groups} == {SpringGroup, DamperGroup}
    pin.seed(1000 + seed)  # numpy's rng does not seed Pinocchio
    q = pin.randomConfiguration(robot.model, -np.ones(robot.nq), np.ones(robot.nq))
    v = rng.normal(size=robot.nv)
    ev = Evaluation(scene, q, v)
    nv = robot.nv
    Q, K, C, Ke = np.zeros(nv), np.zeros((nv, nv)), np.zeros((nv, nv)), np.zeros((nv, nv))
    springs = [e for e in elements if isinstance(e, pinlin.JointSpring)]
    dampers = [e for e in elements if isinstance(e, pinlin.JointDamper)]
    for group in scene.groups:
        group.add_force(ev, Q)
        group.add_stiffness(ev, K)
        group.add_damping(ev, C)
        group.add_elastic_stiffness(ev, Ke)
    # the groups add the vectorized 1-DOF part first, then the prepared elements: same order per entry
    # as the elements grouped likewise (the sums of one entry are in scene order within each part)
    simple_s = [e for e in springs if robot.joint(e.joint).nq == 1 and e.stiffness.ndim < 2]
    simple_d = [e for e in dampers if robot.joint(e.joint).nv == 1 and e.damping.ndim < 2]
    ordered = simple_s + [e for e in springs if e not in simple_s] + simple_d + [e for e in dampers if e not in simple_d]
    Q1, K1, C1, Ke1 = _one_by_one(ordered, ev, nv)
    assert_array_equal(Q, Q1)
    assert_array_equal(K, K1)
    assert_array_equal(C, C1)
    assert_array_equal(Ke, Ke1)
    # and the multi-DOF springs really are off rest with a non-identity de/dq (not a trivial case)
    ball = next(e for e in springs if e.joint == "ball")
    e, jac = ball.deflection(ev)
    assert np.linalg.norm(e) > 0.1 and np.linalg.norm(jac - np.eye(3)) > 1e-3


def test_prepared_data_are_read_only_and_match_the_element_methods():
    rng = np.random.default_rng(7)
    robot = _tree_robot()
    scene = pinlin.Scene(robot, _elements(robot, rng), gravity=(0, 0, 0))
    springs = next(g for g in scene.groups if isinstance(g, SpringGroup))
    prepared = {robot.joint(e.joint).name: p for e, p in zip(springs.elements, springs.prepared)}
    for e, (qs, vs, rest, group, Ks, derivative) in zip(springs.elements, springs.prepared):
        j = robot.joint(e.joint)
        assert (qs, vs) == (j.q_slice, j.v_slice)
        assert_array_equal(rest, e.rest_configuration(robot))
        assert_array_equal(Ks, e.matrix(j))
        assert derivative == (j.nv > 1)
        assert not rest.flags.writeable and not Ks.flags.writeable
        if j.nq > 1:
            assert group.name == robot.model.joints[j.id].lieGroup().name
    assert set(prepared) == {"root", "ball", "plane", "wheel", "hinge", "elbow"}
    assert not springs.k.flags.writeable and not springs.iv.flags.writeable


def test_flat_index_diagonal_update_equals_the_element_by_element_sum():
    rng = np.random.default_rng(3)
    nv = 7
    cases = [[0, 1, 2, 3], [2, 3, 4], [5, 1, 3], [1, 4, 1, 1, 6], [6]]
    for iv in cases:
        index = DiagonalIndex(iv, nv)
        values = rng.normal(size=len(iv)) * 10.0 ** rng.integers(-8, 8, size=len(iv))
        start = rng.normal(size=(nv, nv))
        for layout in ("C", "F", "view"):
            A = np.array(start, order="F") if layout == "F" else start.copy()
            if layout == "view":  # a non-contiguous view into a larger matrix
                big = np.zeros((nv + 2, nv + 2))
                big[1:-1, 1:-1] = start
                A = big[1:-1, 1:-1]
            expected = start.copy()
            for i, x in zip(iv, values):
                expected[i, i] += x  # one element at a time, in order
            index.add(A, values)
            assert_array_equal(A, expected)
            if layout == "view":
                assert_array_equal(big[1:-1, 1:-1], expected)
                assert not big[0].any() and not big[-1].any()
    assert DiagonalIndex([1, 4, 1], nv).unique is False
    assert DiagonalIndex([2, 3, 4], nv).span == slice(16, 40, 8)
    assert DiagonalIndex([5, 1, 3], nv).span is None
    with pytest.raises(AttributeError, match="immutable"):
        DiagonalIndex([1], nv).flat = np.array([0])
    frozen = readonly(np.zeros((nv, nv)))
    for iv in ([1, 2], [3, 1]):  # the strided-slice and the flat-index paths refuse a read-only matrix
        with pytest.raises(ValueError, match="read-only"):
            DiagonalIndex(iv, nv).add(frozen, np.ones(2))


def test_contiguous_indices_become_slices():
    assert contiguous(np.array([3, 4, 5])) == slice(3, 6)
    assert contiguous(np.array([0])) == slice(0, 1)
    for idx in (np.array([3, 5]), np.array([4, 3]), np.array([2, 2]), np.array([], dtype=int)):
        assert contiguous(idx) is idx


def test_damper_group_at_rest_adds_no_force_and_its_damping_is_constant():
    robot = _tree_robot()
    scene = pinlin.Scene(robot, _elements(robot, np.random.default_rng(1)), gravity=(0, 0, 0))
    dampers = next(g for g in scene.groups if isinstance(g, DamperGroup))
    q = robot.neutral()
    Q = np.full(robot.nv, 0.25)
    dampers.add_force(Evaluation(scene, q, np.zeros(robot.nv)), Q)
    assert_array_equal(Q, np.full(robot.nv, 0.25))
    assert dampers.constant_damping
    C_none, C_ev = np.zeros((robot.nv, robot.nv)), np.zeros((robot.nv, robot.nv))
    dampers.add_damping(None, C_none)
    dampers.add_damping(Evaluation(scene, q, np.ones(robot.nv)), C_ev)
    assert_array_equal(C_none, C_ev)


def test_plan_rest_damping_is_the_per_call_sum_and_read_only():
    robot = _tree_robot()
    scene = pinlin.Scene(robot, _elements(robot, np.random.default_rng(2)), gravity=(0, 0, 0))
    rest = plan_of(scene).rest_damping
    C = np.zeros((robot.nv, robot.nv))
    ev = Evaluation(scene, robot.neutral(), np.zeros(robot.nv))
    for group in scene.groups:
        group.add_damping(ev, C)
    assert_array_equal(rest.C, C)
    asm = assemble(scene, robot.neutral(), damping=True)
    assert_array_equal(asm.C, C)
    with pytest.raises(ValueError, match="read-only"):
        asm.C[0, 0] = 1.0
    D, G = rest.split(1e-12, {})
    assert_array_equal(D, (C + C.T) / 2) and not G.any()
    with pytest.raises(ValueError, match="WRITEABLE|writeable"):
        D.setflags(write=True)  # a view of the plan's read-only array cannot be made writable
    # Rayleigh damping depends on M(q): no constant damping, assembled per call
    with_rayleigh = pinlin.Scene(robot, [pinlin.RayleighDamping(alpha=0.1)], gravity=(0, 0, 0))
    assert plan_of(with_rayleigh).rest_damping is None
