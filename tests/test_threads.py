"""One shared Scene, many threads: results bitwise equal to the serial run (thread-safety acceptance).

A :class:`pinlin.Scene` is an immutable description; every computation runs in
the Pinocchio ``Data`` of its own thread (:mod:`pinlin.model.evaluation`).
Before that split, all calls on one scene wrote into one ``scene.data``, and a
thread pool gave wrong stiffness matrices (the double pendulum with a dead
wrench), wrong balancing forces (a chain with gravity and Rayleigh damping) and
spurious ``TimePeriodicError`` (the turntable).

Each case runs the same list of calls twice, once in this thread and once from
a ``ThreadPoolExecutor(8)``, and compares every array with ``np.array_equal``:
the same inputs through the same code must give the same bits.  Python switches
threads every few milliseconds by default, longer than most of these calls; the
threaded runs shorten the switch interval to :data:`SWITCH_INTERVAL` so that
threads interleave inside each call, between its Pinocchio algorithms, where a
shared workspace would be overwritten.
"""

from __future__ import annotations

import contextlib
import sys
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pinocchio as pin
import pytest

import pinlin
from helpers import BOX_URDF

#: Workers of the thread pool (the thread-safety acceptance: 8).
WORKERS = 8
#: Calls of linearize and find_equilibrium per scene (the thread-safety acceptance: 400).
CALLS = 400
#: Calls of modal_analysis (of a fresh linearization) per scene: the 400 of the thread-safety acceptance.
MODAL_CALLS = 400
#: Calls of simulate per scene: each integrates a short span, far more work than a linearization.
SIM_CALLS = 16
#: Thread switch interval [s] during the threaded runs: about one Pinocchio algorithm on these
#: models, so that threads take turns inside each call rather than between calls.
SWITCH_INTERVAL = 1e-6


@contextlib.contextmanager
def _switch_often():
    old = sys.getswitchinterval()
    sys.setswitchinterval(SWITCH_INTERVAL)
    try:
        yield
    finally:
        sys.setswitchinterval(old)


# ----------------------------------------------------------------------------- scenes and inputs


def _double_pendulum():
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(
        robot,
        [
            pinlin.JointSpring("joint1", 3.0),
            pinlin.JointSpring("joint2", 2.0),
            pinlin.DeadWrench("tip", force=(4.0, 0.0, -2.0)),
        ],
    )
    rng = np.random.default_rng(1)
    return scene, [0.3 * rng.standard_normal(2) for _ in range(CALLS)], 0.2


def _chain():
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(30))
    elements = [pinlin.JointSpring(j, 5.0) for j in robot.joint_names]
    scene = pinlin.Scene(
        robot, elements + [pinlin.RayleighDamping(alpha=0.01, beta=0.002)], gravity=(0, 0, -9.81)
    )
    rng = np.random.default_rng(2)
    return scene, [0.1 * rng.standard_normal(30) for _ in range(CALLS)], 0.001


def _turntable():
    robot = pinlin.load_urdf_string(pinlin.turntable_urdf(0.5, 1.3))
    scene = pinlin.Scene(robot, [pinlin.JointSpring("slider", 10.0, rest=0.3)], prescribed={"table": 1.5})
    rng = np.random.default_rng(3)
    qs = []
    for _ in range(CALLS):
        q = scene.neutral()
        angle = rng.uniform(-np.pi, np.pi)
        q[0:2] = np.cos(angle), np.sin(angle)
        q[2] = 0.3 * rng.standard_normal()
        q[3] = 0.51 + 0.1 * rng.standard_normal()  # about r0 = 0.512 for these numbers (theory: turntable)
        qs.append(q)
    return scene, qs, 0.5


def _ur5():
    robot = pinlin.load_example("ur5")
    elements = [pinlin.JointSpring(j, 100.0, rest=0.1) for j in robot.joint_names]
    scene = pinlin.Scene(
        robot, elements + [pinlin.FollowerWrench("tool0", force=(0.0, 0.0, 5.0), torque=(0.2, 0, 0))]
    )
    rng = np.random.default_rng(4)
    return scene, [scene.neutral() + 0.1 * rng.standard_normal(robot.nq) for _ in range(CALLS)], 0.1


def _floating_mount():
    """A free body on an anisotropic 6-DOF spring mount, near rest: the joint spring's own Lie-group log
    (kept per evaluation in ev.memo) and the simulator's chart rates on a free-flyer."""
    robot = pinlin.load_urdf_string(BOX_URDF, free_flyer=True)
    rng = np.random.default_rng(6)
    A = rng.normal(size=(6, 6))
    mount = pinlin.JointSpring("root_joint", 50.0 * (A @ A.T) + 100.0 * np.eye(6))
    scene = pinlin.Scene(robot, [mount, pinlin.JointDamper("root_joint", 0.5)])
    neutral = robot.neutral()
    qs = [pin.integrate(robot.model, neutral, 1e-3 * rng.standard_normal(6)) for _ in range(CALLS)]
    return scene, qs, 0.2


SCENES = {
    "floating_mount": _floating_mount,
    "double_pendulum_dead": _double_pendulum,
    "chain30_rayleigh": _chain,
    "turntable": _turntable,
    "ur5_follower": _ur5,
}
_built: dict[str, tuple] = {}


def _case(name):
    if name not in _built:
        _built[name] = SCENES[name]()
    return _built[name]


# ----------------------------------------------------------------------------- what each call returns


def _linearize(scene, q, span):
    sys_ = pinlin.linearize(scene, q, balancing=True)
    return [sys_.M, sys_.D, sys_.G, sys_.S, sys_.N, sys_.balancing, np.array(sys_.residual)]


def _equilibrium(scene, q, span):
    eq = pinlin.find_equilibrium(scene, q)
    return [eq.q, np.array(eq.residual), np.array(eq.iterations)]


def _modal(scene, q, span):
    modes = pinlin.modal_analysis(pinlin.linearize(scene, q, balancing=True))
    return [
        modes.eigenvalues,
        modes.right,
        modes.left,
        modes.backward_error,
        modes.condition,
        modes.stability.kind,
    ]


def _simulate(scene, q, span):
    sim = pinlin.simulate(scene, q, None, np.linspace(0.0, span, 3))
    return [sim.q, sim.v, np.array([sim.nfev, sim.reference_nfev]), np.array(sim.error)]


OPERATIONS = {
    "linearize": _linearize,
    "find_equilibrium": _equilibrium,
    "modal_analysis": _modal,
    "simulate": _simulate,
}


def _outcome(operation, scene, q, span):
    """The arrays a call returns, or the error it raised (so that a spurious error is a mismatch too)."""
    try:
        return operation(scene, q, span)
    except pinlin.PinlinError as exc:
        return [f"{type(exc).__name__}: {exc}"]


def _same(a, b) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    if a is None or b is None:
        return a is b
    return np.array_equal(
        a, b, equal_nan=True
    )  # a NaN figure (an undefined condition number) is a result too


def _mismatches(serial, threaded) -> list[str]:
    out = []
    for i, (s, t) in enumerate(zip(serial, threaded)):
        if len(s) != len(t) or not all(_same(a, b) for a, b in zip(s, t)):
            gap = max(
                (
                    float(np.max(np.abs(np.asarray(a) - np.asarray(b))))
                    for a, b in zip(s, t)
                    if isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.shape == b.shape
                ),
                default=float("nan"),
            )
            out.append(
                f"call {i}: largest difference {gap:.3g}; serial {str(s[0])[:60]!r}, threaded {str(t[0])[:60]!r}"
            )
    return out


def _serial_and_threaded(operation, scene, inputs, span):
    serial = [_outcome(operation, scene, q, span) for q in inputs]
    with _switch_often(), ThreadPoolExecutor(WORKERS) as pool:
        threaded = list(pool.map(lambda q: _outcome(operation, scene, q, span), inputs))
    return serial, threaded


# ----------------------------------------------------------------------------- tests


@pytest.mark.parametrize("operation", sorted(OPERATIONS))
@pytest.mark.parametrize("name", sorted(SCENES))
def test_shared_scene_threads_match_serial(name, operation):
    scene, inputs, span = _case(name)
    inputs = inputs[: {"simulate": SIM_CALLS, "modal_analysis": MODAL_CALLS}.get(operation, CALLS)]
    serial, threaded = _serial_and_threaded(OPERATIONS[operation], scene, inputs, span)
    assert len(threaded) == len(inputs)
    bad = _mismatches(serial, threaded)
    assert not bad, (
        f"{name} / {operation}: {len(bad)} of {len(inputs)} threaded calls differ from serial:\n"
        + "\n".join(bad[:10])
    )
    # the calls computed something: not every one of them failed
    assert sum(isinstance(s[0], np.ndarray) for s in serial) >= len(inputs) // 2


def _sweep_point(scene, qs, i):
    sys_ = pinlin.linearize(scene, qs[i], balancing=True)
    return np.concatenate([sys_.M.ravel(), sys_.G.ravel(), sys_.S.ravel(), sys_.N.ravel(), sys_.balancing])


@pytest.mark.parametrize("name", ["double_pendulum_dead", "turntable"])
def test_sweep_with_thread_pool_matches_serial(name):
    scene, qs, _ = _case(name)

    def point(i):
        return _sweep_point(scene, qs, i)

    grid = {"i": list(range(CALLS))}
    serial = pinlin.sweep(point, grid, on_error="record", progress=False)
    with _switch_often(), ThreadPoolExecutor(WORKERS) as pool:
        threaded = pinlin.sweep(point, grid, executor=pool, on_error="record", progress=False)
    failures = [p for p, v in zip(grid["i"], threaded.values) if isinstance(v, pinlin.SweepFailure)]
    assert not failures and not [v for v in serial.values if isinstance(v, pinlin.SweepFailure)], (
        f"{len(failures)} threaded points failed, first: {threaded.values[failures[0]] if failures else None}"
    )
    differ = [
        i
        for i, (s, t) in enumerate(zip(serial.values, threaded.values))
        if not np.array_equal(s, t, equal_nan=True)
    ]
    assert not differ, (
        f"{len(differ)} of {CALLS} sweep points differ from the serial sweep (first: {differ[:5]})"
    )


def test_each_thread_computes_in_its_own_workspace():
    from pinlin.model.evaluation import workspace

    scene, _, _ = _case("double_pendulum_dead")
    mine = workspace(scene)
    assert workspace(scene) is mine  # reused within a thread
    with ThreadPoolExecutor(2) as pool:
        theirs = pool.submit(lambda: (threading.get_ident(), workspace(scene))).result()
    assert theirs[0] != threading.get_ident()
    assert theirs[1] is not mine and theirs[1].data is not mine.data
    assert not hasattr(scene, "data")  # the description holds no Pinocchio workspace


def test_scenes_of_one_robot_share_the_threads_data():
    """One Data per robot and thread (createData dominates loading): a sweep's scenes reuse it.

    Scenes of one robot differ in gravity and elements, not in the model's structure;
    interleaving them in one workspace gives bitwise the results of each alone.
    """
    from pinlin.model.evaluation import workspace

    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(4))
    weak = pinlin.Scene(robot, [pinlin.JointSpring(j, 5.0) for j in robot.joint_names])
    strong = weak.replace(gravity=(0.0, 0.0, -20.0), elements=[pinlin.JointSpring(j, 50.0) for j in robot.joint_names])
    q = np.array([0.1, -0.2, 0.3, 0.05])
    alone = [pinlin.linearize(s, q, balancing=True) for s in (weak, strong)]
    assert workspace(weak) is workspace(strong)
    mixed = [pinlin.linearize(s, q, balancing=True) for s in (weak, strong, weak, strong)]
    for got, expected in zip(mixed, alone + alone):
        for name in ("M", "S", "balancing"):
            assert np.array_equal(getattr(got, name), getattr(expected, name))
    assert not np.array_equal(alone[0].S, alone[1].S)  # the two scenes do differ


def test_shared_descriptions_are_immutable():
    """Robot, Scene and elements are shared by threads: none can be changed after construction, and an
    element does not alias the caller's arrays."""
    robot = pinlin.load_example("talos_reduced")
    with pytest.raises(AttributeError, match="Robot is immutable"):
        robot.source = "elsewhere"
    assert not robot.reference_configurations["half_sitting"].flags.writeable
    with pytest.raises(TypeError):
        robot.reference_configurations["other"] = robot.neutral()
    force = np.array([0.0, 0.0, 4.0])
    wrench = pinlin.FollowerWrench("tip", force=force)
    force[2] = 99.0
    assert wrench.force[2] == 4.0 and not wrench.force.flags.writeable
    spring = pinlin.JointSpring("joint1", stiffness=np.array([[3.0]]))
    assert not spring.stiffness.flags.writeable
    scene = pinlin.Scene(pinlin.load_urdf_string(pinlin.double_pendulum_urdf()), [wrench])
    with pytest.raises(AttributeError, match="Scene is immutable"):
        scene.gravity = np.zeros(3)
    assert not scene.gravity.flags.writeable and not scene.free_dofs.flags.writeable
