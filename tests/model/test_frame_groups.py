"""The vectorized spring-damper group against a straightforward per-element computation.

``SpringDamperGroup`` evaluates all the spring-dampers of a scene with gathered
arrays and a handful of products; here every spring is recomputed alone from
Pinocchio's own frame Jacobians (``getFrameJacobian``, LOCAL_WORLD_ALIGNED) and
placements, with the dead-force term of its end forces taken from Pinocchio's
``fext`` derivative (two ``DeadWrench`` elements), on a chain, ur5, solo12 (a
branched tree on a free-flyer) and a free-floating body: springs between
frames of one body, to the world frame, to world points, preloaded, zero-length.
At v != 0 (the q-derivative of the dashpot's ldot) K is checked against
Richardson-extrapolated central differences of the per-element force on the
manifold.  Evaluations from 8 threads are bitwise those of a serial run.
"""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pinocchio as pin
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.linearization.assembly import assemble
from pinlin.model.elements.spring_damper import SpringDamperGroup
from pinlin.model.evaluation import Evaluation

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED

#: Group against per-element sums: both are a few dozen rounded products of O(1) factors,
#: summed over up to 60 springs with preload (cancellation in T / l (I - u u^T)).
ROUNDING_RTOL = 1e-12
#: Richardson-extrapolated central differences (steps h, h/2; error O(h^4) + eps |Q| / h).
RICHARDSON_RTOL = 1e-8
#: Step of the differences [rad or m].
STEP = 1e-3

FREE_BODY = """<robot name="box"><link name="box"><inertial><origin xyz="0.1 -0.05 0.02"/><mass value="3.0"/>
  <inertia ixx="0.2" iyy="0.3" izz="0.4" ixy="0.01" ixz="0" iyz="-0.02"/></inertial></link>
  <link name="tip"/><joint name="fix" type="fixed"><parent link="box"/><child link="tip"/>
  <origin xyz="0.4 0.1 -0.2" rpy="0.3 0.2 0.1"/></joint></robot>"""


def _springs_chain(robot):
    links = [f"link{i}" for i in range(1, 7)]
    out = [pinlin.LinearSpringDamper(a, b, stiffness=30.0 + i, damping=0.4, rest_length=0.5 + 0.1 * i)
           for i, (a, b) in enumerate(zip(links, links[2:] + links[:2]))]
    out += [
        pinlin.LinearSpringDamper("link2", "link5", stiffness=7.0, damping=0.0, rest_length=0.0),
        pinlin.LinearSpringDamper("link4", (0.3, -0.2, 0.5), stiffness=11.0, damping=1.5, rest_length=0.8),
        pinlin.LinearSpringDamper("link6", "universe", stiffness=5.0, damping=0.3, rest_length=2.0),
    ]
    return out


def _springs_ur5(robot):
    return [
        pinlin.LinearSpringDamper("tool0", "upper_arm_link", stiffness=250.0, damping=3.0, rest_length=0.2),
        pinlin.LinearSpringDamper("wrist_3_link", "tool0", stiffness=40.0, damping=0.7, rest_length=0.05),  # one body
        pinlin.LinearSpringDamper("ee_link", "world", stiffness=15.0, damping=0.2, rest_length=0.6),
        pinlin.LinearSpringDamper("forearm_link", (0.2, 0.4, 0.9), stiffness=60.0, rest_length=0.0),
        pinlin.LinearSpringDamper("wrist_1_link", "shoulder_link", stiffness=80.0, damping=1.0, rest_length=0.9),
    ]


def _springs_solo(robot):
    legs = ("FL", "FR", "HL", "HR")
    out = [pinlin.LinearSpringDamper(f"{a}_FOOT", f"{b}_FOOT", stiffness=100.0, damping=2.0, rest_length=0.3)
           for a, b in zip(legs, legs[1:] + legs[:1])]
    out += [
        pinlin.LinearSpringDamper("FL_LOWER_LEG", "FL_FOOT", stiffness=30.0, damping=0.5, rest_length=0.1),
        pinlin.LinearSpringDamper("HR_UPPER_LEG", "base_link", stiffness=45.0, damping=0.0, rest_length=0.05),
        pinlin.LinearSpringDamper("FR_LOWER_LEG", (0.1, -0.3, -0.4), stiffness=20.0, damping=0.8, rest_length=0.2),
        pinlin.LinearSpringDamper("HL_FOOT", "universe", stiffness=12.0, damping=0.0, rest_length=0.0),
    ]
    return out


def _springs_free(robot):
    return [
        pinlin.LinearSpringDamper("tip", (0.5, 0.2, 1.0), stiffness=80.0, damping=1.2, rest_length=0.4),
        pinlin.LinearSpringDamper("box", (-0.3, 0.1, 0.7), stiffness=50.0, damping=0.6, rest_length=0.9),
        pinlin.LinearSpringDamper("box", "tip", stiffness=9.0, damping=0.1, rest_length=0.2),  # one body
        pinlin.LinearSpringDamper("tip", "universe", stiffness=25.0, rest_length=0.0),
    ]


def _robot(name):
    if name == "chain":
        return pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(6, length=0.7, mass=1.5))
    if name == "free body":
        return pinlin.load_urdf_string(FREE_BODY, free_flyer=True)
    return pinlin.load_example(name)


CASES = {"chain": _springs_chain, "ur5": _springs_ur5, "solo12": _springs_solo, "free body": _springs_free}


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    robot = _robot(request.param)
    springs = CASES[request.param](robot)
    return robot, springs, np.random.default_rng(len(request.param))


def _configuration(robot, rng):
    return pin.integrate(robot.model, pin.neutral(robot.model), rng.uniform(-1.0, 1.0, robot.nv))


def _kinematics(model, q):
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    return data


def _end(robot, model, data, target):
    """Position and linear Jacobian (world axes) of a spring end: a frame's origin or a fixed world point."""
    if isinstance(target, str):
        fid = robot.frame_id(target)
        return data.oMf[fid].translation.copy(), pin.getFrameJacobian(model, data, fid, LWA)[:3]
    return np.asarray(target, dtype=float), np.zeros((3, model.nv))


def _per_element(robot, springs, q, v):
    """Q, C, K_e and the material + geometric part of K, spring by spring; the end forces for the dead term."""
    model = robot.model
    data = _kinematics(model, q)
    nv = model.nv
    Q, C, Ke, K = np.zeros(nv), np.zeros((nv, nv)), np.zeros((nv, nv)), np.zeros((nv, nv))
    loads = []
    for s in springs:
        p_a, J_a = _end(robot, model, data, s.frame)
        p_b, J_b = _end(robot, model, data, s.target)
        d, J_rel = p_b - p_a, J_b - J_a
        l = np.linalg.norm(d)
        if l == 0.0:  # zero-length spring: force k d = 0, isotropic stiffness k
            K += s.stiffness * J_rel.T @ J_rel
            Ke += s.stiffness * J_rel.T @ J_rel
            continue
        u = d / l
        T = s.stiffness * (l - s.rest_length) + s.damping * (u @ J_rel @ v)
        Q -= J_rel.T @ (T * u)
        uu = np.outer(u, u)
        C += s.damping * J_rel.T @ uu @ J_rel
        Ke += s.stiffness * J_rel.T @ uu @ J_rel
        K += J_rel.T @ (s.stiffness * uu + T / l * (np.eye(3) - uu)) @ J_rel
        loads.append(pinlin.DeadWrench(s.frame, force=T * u))
        if isinstance(s.target, str):
            loads.append(pinlin.DeadWrench(s.target, force=-T * u))
    return Q, C, Ke, K, loads


def _group(robot, springs, q, v, shared=None):
    """Q, K, C, K_e of the group at (q, v); ``shared`` = (scene, group) evaluates a given scene's group."""
    scene, group = shared or (pinlin.Scene(robot, springs, gravity=(0, 0, 0)), SpringDamperGroup(tuple(springs), robot))
    ev = Evaluation(scene, q, v)
    nv = robot.nv
    Q, K, C, Ke = np.zeros(nv), np.zeros((nv, nv)), np.zeros((nv, nv)), np.zeros((nv, nv))
    group.add_force(ev, Q)
    group.add_stiffness(ev, K)
    group.add_damping(ev, C)
    group.add_elastic_stiffness(ev, Ke)
    return Q, K, C, Ke


def _close(actual, desired, rtol):
    assert_allclose(actual, desired, rtol=0, atol=rtol * max(np.abs(desired).max(), 1.0))


def _with_zero_length(robot, springs, q):
    """A zero-length spring (rest 0, no damping) whose world point is the frame's origin at q, exactly."""
    data = _kinematics(robot.model, q)
    frame = springs[0].frame
    point = data.oMf[robot.frame_id(frame)].translation.copy()
    return springs + [pinlin.LinearSpringDamper(frame, point, stiffness=13.0)]


def test_group_at_rest_matches_per_element_reference(case):
    """v = 0: Q, C, K_e and K (material, geometric and dead-force terms) equal the per-spring sums to rounding."""
    robot, springs, rng = case
    for _ in range(3):
        q = _configuration(robot, rng)
        springs_q = _with_zero_length(robot, springs, q)
        v = np.zeros(robot.nv)
        Q, K, C, Ke = _group(robot, springs_q, q, v)
        Q_ref, C_ref, Ke_ref, K_ref, loads = _per_element(robot, springs_q, q, v)
        dead = assemble(pinlin.Scene(robot, loads, gravity=(0, 0, 0)), q, stiffness=True).K
        _close(Q, Q_ref, ROUNDING_RTOL)
        _close(C, C_ref, ROUNDING_RTOL)
        _close(Ke, Ke_ref, ROUNDING_RTOL)
        _close(K, K_ref + dead, ROUNDING_RTOL)


def _richardson_stiffness(robot, springs, q, v):
    """-dQ/dq on the manifold (pin.integrate steps) from the per-element force, Richardson-extrapolated."""

    def diff(h):
        cols = []
        for k in range(robot.nv):
            e = np.zeros(robot.nv)
            e[k] = h
            plus = _per_element(robot, springs, pin.integrate(robot.model, q, e), v)[0]
            minus = _per_element(robot, springs, pin.integrate(robot.model, q, -e), v)[0]
            cols.append(-(plus - minus) / (2 * h))
        return np.array(cols).T

    return (4 * diff(STEP / 2) - diff(STEP)) / 3


def test_group_in_motion_against_differences(case):
    """v != 0: Q and C equal the per-spring sums to rounding; K (with d(ldot)/dq) matches differences."""
    robot, springs, rng = case
    q = _configuration(robot, rng)
    v = rng.standard_normal(robot.nv)
    Q, K, C, _ = _group(robot, springs, q, v)
    Q_ref, C_ref, _, _, _ = _per_element(robot, springs, q, v)
    _close(Q, Q_ref, ROUNDING_RTOL)
    _close(C, C_ref, ROUNDING_RTOL)
    _close(K, _richardson_stiffness(robot, springs, q, v), RICHARDSON_RTOL)


def test_group_arrays_are_read_only(case):
    """The group is shared by the threads that share its scene: nothing in it can be written."""
    robot, springs, _ = case
    group = SpringDamperGroup(tuple(springs), robot)
    arrays = {name: value for name, value in vars(group).items() if isinstance(value, np.ndarray)}
    assert {"ia", "ib", "m_f", "T", "k", "c", "l0", "B"} <= set(arrays)
    assert not [name for name, value in arrays.items() if value.flags.writeable]


def test_threads_give_bitwise_the_serial_results():
    """8 threads evaluating one scene's group at their own (q, v) points reproduce the serial run bitwise."""
    robot = _robot("solo12")
    springs = _springs_solo(robot)
    rng = np.random.default_rng(8)
    points = [(_configuration(robot, rng), rng.standard_normal(robot.nv) * (i % 2)) for i in range(16)]
    scene = pinlin.Scene(robot, springs)
    (group,) = [g for g in scene.groups if isinstance(g, SpringDamperGroup)]

    def run(point):
        Q, K, C, Ke = _group(robot, springs, *point, shared=(scene, group))
        return b"".join(a.tobytes() for a in (Q, K, C, Ke))

    serial = [run(p) for p in points]
    with ThreadPoolExecutor(8) as pool:
        for _ in range(5):
            assert list(pool.map(run, points)) == serial
    q = points[0][0]

    def lin(_):
        sys = pinlin.linearize(scene, q, balancing=True)
        return b"".join(np.asarray(a).tobytes() for a in (sys.M, sys.C, sys.K))

    reference = lin(None)
    with ThreadPoolExecutor(8) as pool:
        assert set(pool.map(lin, range(64))) == {reference}
