"""The lean constrained linearization: the planar proof of redundancy against the rank of J_c
and the probes, and the cheaper paths against the plain formulas they replace (bitwise where they are
the same arithmetic, to rounding where the factorization changed)."""

import dataclasses
import math

import numpy as np
import pinocchio as pin
import pytest
import scipy.linalg.lapack as lapack
from numpy.testing import assert_allclose

import pinlin
from constrained_cases import BUNDLED, PARALLELOGRAM
from pinlin.linearization.assembly import assemble
from pinlin.linearization.constrained_structure import structurally_redundant
from pinlin.linearization.constraint_set import (
    constrained_point,
    constraint_forces,
    contact_statuses,
    evaluate_constraints,
)
from pinlin.linearization.coordinates import PIVOTED_METHOD, coordinate_basis
from pinlin.linearization.singularity import check_regular
from pinlin.model.constraints import ConstraintForce, dead_wrench_stiffness

G = 9.81
#: dgels and dgelsy are both backward stable: on solo12's well-conditioned J_c (cond ~ 20)
#: the multipliers agree to a few eps.
MULTIPLIER_RTOL = 1e-13
#: a^T J_c of a planar constraint is a sum of products that cancel exactly in exact
#: arithmetic: a few eps of the Jacobian's size.
PLANAR_ZERO = 1e-14


@pytest.fixture(scope="module")
def four_bar_scene():
    robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    spring = pinlin.JointSpring("crank_joint", 50.0, rest=0.2)
    return pinlin.Scene(robot, [spring], constraints=[pinlin.PointConstraint("rocker_tip", (BUNDLED.ground, 0, 0))])


@pytest.fixture(scope="module")
def solo():
    robot = pinlin.load_example("solo12", free_flyer=True)
    q0 = robot.reference_configurations["standing"].copy()
    springs = [pinlin.JointSpring(j, 20.0, rest=q0[robot.joint(j).idx_q]) for j in robot.joint_names[1:]]
    feet = ("FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT")
    scene = pinlin.Scene(robot, springs, constraints=pinlin.ground_contacts(robot, q0, feet, friction=0.8))
    return scene, pinlin.find_equilibrium(scene, q0).q


def _chain(joints, frame_constraint=False):
    """A serial chain of the given Pinocchio joint models (0.3 m links along -z), a point or frame constraint at its tip."""
    model = pin.Model()
    parent = 0
    for k, joint in enumerate(joints):
        placement = pin.SE3(np.eye(3), np.array([0.0, 0.0, -0.3 if k else 0.0]))
        parent = model.addJoint(parent, joint, placement, f"j{k}")
        model.appendBodyToJoint(parent, pin.Inertia(1.0, np.array([0.0, 0.0, -0.15]), np.eye(3) * 0.01), pin.SE3.Identity())
    model.addFrame(pin.Frame("tip", parent, pin.SE3(np.eye(3), np.array([0.0, 0.0, -0.3])), pin.FrameType.OP_FRAME))
    robot = pinlin.Robot(model, "<chain>")
    if frame_constraint:
        constraint = pinlin.FrameConstraint("tip", np.eye(4))
    else:
        constraint = pinlin.PointConstraint("tip", (0.2, 0.0, -0.5))
    return pinlin.Scene(robot, [], constraints=[constraint])


# ----------------------------------------------------------------------------- the planar proof


def test_planar_four_bar_has_one_identically_redundant_equation(four_bar_scene):
    scene = four_bar_scene
    rng = np.random.default_rng(3)
    for _ in range(20):  # any configuration, assembled or not: the theorem holds on the whole space
        q = rng.uniform(-math.pi, math.pi, scene.model.nv)
        state = evaluate_constraints(scene, q)
        assert structurally_redundant(scene, state) == 1
        # the joints turn about y: the y row of J_c vanishes identically, so rank J_c <= 2
        assert np.abs(state.J[1]).max() <= PLANAR_ZERO * np.abs(state.J).max()
        assert np.linalg.matrix_rank(state.J) <= 2


@pytest.mark.parametrize(
    ("joints", "frame", "expected"),
    [
        ((pin.JointModelRY(), pin.JointModelRY(), pin.JointModelRY()), True, 3),  # planar weld: 3 of 6
        ((pin.JointModelRY(), pin.JointModelPX(), pin.JointModelRY()), False, 1),  # prismatic across the axis
        ((pin.JointModelRY(), pin.JointModelRX(), pin.JointModelRY()), False, 0),  # a crossed axis: spatial
        ((pin.JointModelRY(), pin.JointModelPY(), pin.JointModelRY()), False, 0),  # sliding along the axis
        ((pin.JointModelPX(), pin.JointModelPZ()), False, 0),  # no rotation: no normal to prove against
    ],
)
def test_planar_proof_only_where_the_theorem_applies(joints, frame, expected):
    scene = _chain(joints, frame)
    rng = np.random.default_rng(11)
    for _ in range(10):
        state = evaluate_constraints(scene, rng.uniform(-1.0, 1.0, scene.model.nv))
        s = structurally_redundant(scene, state)
        assert s == expected
        assert np.linalg.matrix_rank(state.J) <= state.m - s  # the bound the proof stands on


def test_standing_robot_gets_no_planar_proof(solo):
    scene, q = solo
    state = evaluate_constraints(scene, q)
    assert structurally_redundant(scene, state) == 0 and state.rank == state.m


@pytest.mark.parametrize("degrees", [0, 75, 150, 225, 300])
def test_planar_proof_agrees_with_the_probes(four_bar_scene, degrees):
    scene, q = four_bar_scene, BUNDLED.joints(math.radians(degrees))
    state = evaluate_constraints(scene, q)
    assert state.rank == state.m - structurally_redundant(scene, state) == 2
    calls = []
    check_regular(scene, q, state, calls)  # the probes find no higher rank nearby either
    assert calls.count("computeJointJacobians") >= 2
    sys = pinlin.linearize(scene, q, balancing=True)
    assert sys.calls.count("computeJointJacobians") == 1  # proved: no probe ran
    assert any("redundant" in note for note in sys.notes)


def test_toggle_position_is_still_probed_and_refused():
    """The parallelogram flat (tests/reference): planar, but its rank is below m - s, so the probes decide."""
    robot = pinlin.load_urdf_string(PARALLELOGRAM.urdf())
    scene = pinlin.Scene(robot, constraints=[pinlin.PointConstraint("rocker_tip", (0.8, 0, 0), name="loop")])
    r1, r2, r3 = PARALLELOGRAM.reference()
    q_flat = np.array([0.0 - r1, 0.0 - r2, math.pi - r3])
    state = evaluate_constraints(scene, q_flat)
    assert state.rank == 1 < state.m - structurally_redundant(scene, state) == 2
    with pytest.raises(pinlin.SingularConstraintError, match=r"rank 1 at q but rank 2.*\['loop'\]"):
        pinlin.linearize(scene, q_flat, balancing=True)


# ----------------------------------------------------------------------------- the cheaper paths


def test_full_rank_multipliers_match_least_squares(solo):
    scene, q = solo
    state = evaluate_constraints(scene, q)
    rng = np.random.default_rng(2)
    for r in (assemble(scene, q, stiffness=False).residual, rng.standard_normal(scene.model.nv)):
        lam, g = state.multipliers(r)
        reference = np.linalg.lstsq(state.J.T, r, rcond=None)[0]
        assert_allclose(lam, reference, rtol=MULTIPLIER_RTOL, atol=MULTIPLIER_RTOL * np.abs(reference).max())
        m = state.m  # the route it replaces: dgelsy with the same threshold
        b = r.reshape(-1, 1).copy()
        x = lapack.dgelsy(state.J.T, b, np.zeros(m, dtype=np.int32), state.rank_tol, 4 * m + 1)[1]
        assert_allclose(lam, x[:m, 0], rtol=MULTIPLIER_RTOL, atol=MULTIPLIER_RTOL * np.abs(reference).max())
        assert np.abs(state.J @ g).max() <= 1e-12 * np.abs(r).max()  # g is orthogonal to the constraint forces


@pytest.mark.parametrize("case", ["solo", "four_bar"])
def test_default_basis_against_the_given_coordinates_path(case, solo, four_bar_scene):
    """The default (pivoted-QR) basis: identity on its coordinates, J_c B = 0, and the same B as naming
    those coordinates explicitly (a different algorithm: the dependent joints follow by a QR of J_d)."""
    scene, q = solo if case == "solo" else (four_bar_scene, BUNDLED.joints(1.0))
    state = evaluate_constraints(scene, q)
    default = coordinate_basis(state, scene.dof_names, None)
    assert default.method == PIVOTED_METHOD
    assert set(default.dof_names).isdisjoint(default.dependent)
    assert len(default.dof_names) + len(default.dependent) == len(scene.dof_names)
    rows = [scene.dof_names.index(name) for name in default.dof_names]
    assert np.array_equal(default.B[rows], np.eye(len(rows)))
    assert np.abs(state.J @ default.B).max() <= 1e-14 * np.abs(state.J).max() * np.abs(default.B).max()
    given = coordinate_basis(state, scene.dof_names, list(default.dof_names))
    assert given.dependent == default.dependent
    assert_allclose(default.B, given.B, rtol=0, atol=1e-13 * np.abs(given.B).max())
    assert_allclose(default.condition, given.condition, rtol=0.5)  # two 1-norm estimates of one cond(J_d)


@pytest.mark.parametrize("balancing", [False, True])
def test_projection_is_the_plain_formulas_bitwise(solo, balancing):
    scene, q = solo
    if balancing:
        q = q.copy()
        q[7] += 1e-3  # a leg joint moved: the contacts stay closed to ~1e-4 m only, so loosen them
    kwargs = {"constraint_tol": 1e-2} if balancing else {}
    sys = pinlin.linearize(scene, q, balancing=balancing, **kwargs)
    state = evaluate_constraints(scene, q)
    lam, g, asm, Kt = constrained_point(scene, q, state, stiffness=True, damping=True, mass=True)
    B = sys.basis
    M, C, K = B.T @ asm.M @ B, B.T @ asm.C @ B, B.T @ Kt @ B
    M = M + M.T
    M *= 0.5
    assert np.array_equal(sys.M, M)
    assert np.array_equal(sys.D, (C + C.T) * 0.5)
    assert np.array_equal(sys.S, (K + K.T) * 0.5)
    assert not sys.G.any()
    if balancing:  # off the equilibrium K_lambda is not symmetric: N is kept, halved exactly
        assert sys.N.any() and np.array_equal(sys.N, (K - K.T) * 0.5)
    else:
        assert not sys.N.any()
    assert np.array_equal(np.concatenate([f.force for f in sys.constraint_forces]), lam)
    if balancing:
        assert np.array_equal(sys.balancing, B.T @ g)


def test_contact_check_matches_the_statuses(solo):
    scene, q = solo
    state = evaluate_constraints(scene, q)
    rng = np.random.default_rng(7)
    samples = [rng.normal(size=(4, 3)) * [1, 1, 3] + [0, 0, 2] for _ in range(200)]
    samples += [np.tile([0.8, 0.0, 1.0], (4, 1)), np.tile([0.0, 0.0, -1.0], (4, 1)), np.tile([0.0, 0.0, 0.0], (4, 1)),
                np.tile([0.1, 0.0, 0.0], (4, 1))]
    for L in samples:
        lam = L.ravel()
        assert state.contacts_violated(lam) == any(not s.feasible for s in contact_statuses(scene, lam))
        # and the vectorized formula it replaces, term by term
        n = scene.contact_normals
        fn = np.add.reduce(L * n, axis=1)
        t = L - fn[:, None] * n
        mu_fn = scene.contact_friction * fn
        old = bool(np.count_nonzero(fn < 0) or np.count_nonzero(np.add.reduce(t * t, axis=1) > mu_fn * mu_fn))
        assert state.contacts_violated(lam) == old


def test_gaps_are_the_largest_distance(solo):
    scene, q = solo
    state = evaluate_constraints(scene, q)
    rng = np.random.default_rng(4)
    for _ in range(20):
        phi = rng.normal(size=state.m)
        gap, rot, worst = dataclasses.replace(state, phi=phi).gaps()
        distances = np.linalg.norm(phi.reshape(-1, 3), axis=1)
        assert gap == pytest.approx(distances.max(), rel=1e-15) and rot == 0.0
        assert worst == scene.constraints[int(distances.argmax())].label
    phi = np.zeros(state.m)
    phi[4] = math.nan  # as numpy's argmax: the first NaN is the largest
    gap, _, worst = dataclasses.replace(state, phi=phi).gaps()
    assert math.isnan(gap) and worst == scene.constraints[1].label


def test_rank_counts_the_pivots_above_the_threshold(solo, four_bar_scene):
    for scene, q in (solo, (four_bar_scene, BUNDLED.joints(1.0))):
        for tol in (1e-9, 1e-3, 0.5):
            state = evaluate_constraints(scene, q, rank_tol=tol)
            d = np.abs(np.diagonal(lapack.dgeqp3(state.J)[0]))
            assert state.rank == int(np.count_nonzero(d > tol * d[0]))


def test_constraint_forces_are_values_of_their_own(solo):
    scene, q = solo
    lam = np.arange(12.0)
    forces = constraint_forces(scene, lam)
    lam[:] = -1.0  # the caller's array is not shared
    for k, (f, c) in enumerate(zip(forces, scene.constraints)):
        built = ConstraintForce(c.label, c.frame, c.target, np.arange(3.0 * k, 3.0 * k + 3))
        assert repr(f) == repr(built) and (f.constraint, f.frame) == (built.constraint, built.frame)
        assert np.array_equal(f.target, built.target)
        assert np.array_equal(f.force, built.force) and f.torque is None
        with pytest.raises(dataclasses.FrozenInstanceError):
            f.force = None
        with pytest.raises(ValueError, match="read-only"):  # a frozen result: its arrays too
            f.force[0] = 1.0


def test_dead_wrench_stiffness_with_the_linear_rows_given(solo):
    scene, q = solo
    state = evaluate_constraints(scene, q)
    forces = np.random.default_rng(1).normal(size=(4, 3))
    before = scene.robot.dof_supports
    plain = dead_wrench_stiffness(state.frames, forces, None, before)
    assert np.array_equal(dead_wrench_stiffness(state.frames, forces, None, before, linear=state.J), plain)


def test_contact_status_without_normal_force():
    """A contact carrying no force needs no friction; one with only a tangential force slips (any mu)."""
    c = pinlin.PointConstraint("foot", target=(0.0, 0.0, 0.0), contact=True, friction=0.5)
    idle = c.contact_status(np.zeros(3))
    assert idle.friction_needed == 0.0 and idle.feasible
    sliding = c.contact_status(np.array([0.2, 0.0, 0.0]))
    assert sliding.friction_needed == math.inf and sliding.slips and not sliding.feasible
