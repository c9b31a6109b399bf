"""Timing worker of bench_workspace.py: one process, one version of pinlin (whatever ``import pinlin`` finds).

Run as a script with PYTHONPATH pointing at the ``src`` directory of the pinlin
to measure.  It reads one JSON command per line on stdin and answers one JSON
line on stdout:

- ``{"cmd": "info"}`` -> where pinlin was imported from;
- ``{"cmd": "result", "case": c}`` -> the matrices M, D, G, S, N of ``linearize`` (lists);
- ``{"cmd": "calibrate", "case": c, "variant": v, "min_time": s}`` -> a loop count making one sample last >= s;
- ``{"cmd": "sample", "case": c, "variant": v, "loops": k}`` -> seconds per call over k calls.

Variants: ``linearize`` (any version); with the per-thread workspaces
also ``fresh`` (linearize with an empty workspace cache for the call: a
new Pinocchio Data for every call; the reused workspace is put back after it), ``workspace`` (``Workspace(scene)``:
memory guard + createData), ``createData`` (``model.createData()`` alone) and
``lookup`` (``workspace(scene)``: the per-call cost of finding the thread's
workspace).  Only the public API of pinlin builds the scenes, so the code from
before the per-thread workspaces runs it too.
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np

import pinlin

#: Joint stiffness [N m/rad] and damping [N m s/rad] of the panda case (as in bench_linearize's arms).
PANDA_K, PANDA_C = 100.0, 0.5
#: Links of the chain case and its joint stiffness [N m/rad].
CHAIN_N, CHAIN_K = 100, 5.0


def panda():
    robot = pinlin.load_example("panda")
    q_ref = np.asarray(robot.reference_configurations["default"], dtype=float)
    elements = []
    for j, qj in zip(robot.joint_names, q_ref):
        elements += [pinlin.JointSpring(j, PANDA_K, rest=float(qj)), pinlin.JointDamper(j, PANDA_C)]
    elements.append(pinlin.FollowerWrench("panda_hand", force=(0.0, 0.0, 5.0)))
    scene = pinlin.Scene(robot, elements)
    return scene, pinlin.find_equilibrium(scene, q_ref).q, False


def chain(rayleigh: bool = True):
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(CHAIN_N))
    elements = [pinlin.JointSpring(j, CHAIN_K) for j in robot.joint_names]
    if rayleigh:
        elements.append(pinlin.RayleighDamping(alpha=0.01, beta=0.002))
    scene = pinlin.Scene(robot, elements, gravity=(0.0, 0.0, -9.81))
    q = 0.05 * np.sin(np.arange(CHAIN_N))  # a bent chain, held by balancing forces
    return scene, q, True


CASES = {"panda": panda, "chain100": chain, "chain100 without Rayleigh": lambda: chain(rayleigh=False)}
_built: dict = {}


def _case(name):
    if name not in _built:
        _built[name] = CASES[name]()
    return _built[name]


def _variant(name: str, variant: str):
    scene, q, balancing = _case(name)
    if variant == "linearize":
        return lambda: pinlin.linearize(scene, q, balancing=balancing)
    try:  # the per-thread workspaces: pinlin.model.evaluation now, pinlin.linearization.workspace in older code
        from pinlin.model import evaluation as ws_module
    except ImportError:
        from pinlin.linearization import workspace as ws_module

    if variant == "fresh":

        def fresh():
            # A new, empty cache for this call only: linearize creates (and drops) a workspace of its
            # own, while the thread's reused workspace stays cached for the other variants' samples.
            saved = ws_module._local.__dict__.pop("cache", None)
            try:
                return pinlin.linearize(scene, q, balancing=balancing)
            finally:
                ws_module._local.__dict__["cache"] = saved

        return fresh
    if variant == "workspace":
        return lambda: ws_module.Workspace(scene)
    if variant == "createData":
        return scene.model.createData
    if variant == "lookup":
        return lambda: ws_module.workspace(scene)
    raise ValueError(f"unknown variant {variant!r}")


def _answer(cmd: dict):
    if cmd["cmd"] == "info":
        return {"pinlin": pinlin.__file__}
    if cmd["cmd"] == "result":
        scene, q, balancing = _case(cmd["case"])
        sys_ = pinlin.linearize(scene, q, balancing=balancing)
        return {name: np.asarray(getattr(sys_, name)).tolist() for name in ("M", "D", "G", "S", "N")}
    fn = _variant(cmd["case"], cmd["variant"])
    if cmd["cmd"] == "calibrate":
        fn()
        loops = 1
        while True:
            t0 = time.perf_counter()
            for _ in range(loops):
                fn()
            if time.perf_counter() - t0 >= cmd["min_time"] or loops >= 1 << 20:
                return {"loops": loops}
            loops *= 2
    if cmd["cmd"] == "sample":
        t0 = time.perf_counter()
        for _ in range(cmd["loops"]):
            fn()
        return {"seconds": (time.perf_counter() - t0) / cmd["loops"]}
    raise ValueError(f"unknown command {cmd!r}")


def main() -> None:
    for line in sys.stdin:
        try:
            out = _answer(json.loads(line))
        except Exception as exc:  # noqa: BLE001 - reported to the driver, which raises
            out = {"failed": f"{type(exc).__name__}: {exc}"}
        sys.stdout.write(json.dumps(out) + "\n")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
