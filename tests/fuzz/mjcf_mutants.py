"""Mutants of the bundled MJCF four-bar, and the pipeline each must pass or refuse.

:func:`mutate` changes the file as the URDF fuzzer does: an attribute set to a nasty value, an element
removed or duplicated, an entity trick or a cut.  Its choices come from a ``pick(options)`` callable, so
hypothesis (``draw(st.sampled_from(...))``) and a seeded ``random.Random`` (the subprocess runs) share it.
:func:`analyse` loads a mutant and, when it loads, builds a scene, closes the loop, linearizes and
computes the modes; every stage must give a PinlinError or an honest result, and a loaded model must
hold no NaN or infinite number.  Run as a script, it reads mutant files from stdin (one path a line) and
prints one verdict a line: a crash of the process is then seen by its parent.
"""

from __future__ import annotations

import copy
import random
import sys
import traceback
import xml.etree.ElementTree as ET

import numpy as np
from fuzz_strategies import outcome

import pinlin

BASE = pinlin.data_path("mjcf/four_bar.xml").read_text()

#: Attribute values that a parser may read wrongly (the URDF list, and MJCF's counted numbers).
VALUES = ["nan", "inf", "-inf", "1e999", "abc", "", " ", "-1", "0", "1e-300", "1e300", "-0", "1 2", "0 0 0",
          "1 1 1 1", "0x10", "1,5", "NaN", "a b c", "nan 0 0", "0 0 1", "1 0 0 0", "0 0 0 0", "1e-320", "5",
          "0.3 0 0", "hinge", "ball", "slide", "free", "world", "crank", "rocker", "loop", "false", "main",
          "1 0 0 0 1 0"]
ATTRIBUTES = ["name", "pos", "euler", "quat", "axis", "type", "mass", "diaginertia", "body1", "body2", "anchor",
              "site1", "site2", "relpose", "active", "range", "angle", "fullinertia", "class", "childclass",
              "size", "fromto", "xyaxes", "zaxis", "axisangle"]
ENTITIES = ['<!DOCTYPE mujoco [<!ENTITY v "0.5">]>', '<!DOCTYPE mujoco [<!ENTITY v SYSTEM "file:///etc/hostname">]>',
            '<!DOCTYPE mujoco [<!ENTITY a "1e300"><!ENTITY v "&a;&a;&a;&a;&a;&a;&a;&a;">]>']


def mutate(pick, base: str = BASE) -> str:
    """One mutant of ``base``; ``pick(options)`` returns one of the options (a list or a range)."""
    root = ET.fromstring(base)
    elements = list(root.iter())
    for _ in range(pick([1, 1, 1, 2, 3])):
        element = elements[pick(range(len(elements)))]
        parent = next((p for p in root.iter() if element in list(p)), None)
        op = pick(["attribute", "attribute", "new attribute", "remove", "duplicate"])
        if op == "attribute" and element.attrib:
            element.set(pick(sorted(element.attrib)), pick(VALUES))
        elif op == "new attribute":
            element.set(pick(ATTRIBUTES), pick(VALUES))
        elif op == "remove" and parent is not None:
            parent.remove(element)
        elif op == "duplicate" and parent is not None:
            parent.insert(list(parent).index(element) + 1, copy.deepcopy(element))
    out = ET.tostring(root, encoding="unicode")
    trick = pick(["none"] * 6 + ["entity", "truncate"])
    if trick == "entity":
        out = pick(ENTITIES) + out.replace('pos="', 'pos="&v; ', 1)
    elif trick == "truncate":
        out = out[: pick(range(len(out)))]
    return out


def random_mutant(rng: random.Random) -> str:
    return mutate(lambda options: rng.choice(list(options)))


def check_model(robot) -> None:
    """A loaded model holds only finite numbers: nothing uninitialized or NaN reached it."""
    model = robot.model
    numbers = [p.homogeneous for p in model.jointPlacements] + [f.placement.homogeneous for f in model.frames]
    numbers += [np.r_[i.mass, i.lever, i.inertia.ravel()] for i in model.inertias]
    numbers += [np.asarray(c.target, dtype=float) for c in robot.constraints if not isinstance(c.target, str)]
    for values in numbers:
        assert np.all(np.isfinite(values)), f"non-finite numbers in a loaded model: {values}"


def analyse(path: str) -> str:
    """The stages on one mutant file, each through :func:`fuzz_strategies.outcome`; the last stage reached."""
    robot = outcome(lambda: pinlin.load_mjcf(path), "load_mjcf")
    if robot is None:
        return "refused by load_mjcf"
    check_model(robot)
    springs = [pinlin.JointSpring(name, 10.0) for name in robot.joint_names if robot.joint(name).nv == 1]
    stages = [
        ("Scene", lambda _: pinlin.Scene(robot, springs)),
        ("find_equilibrium", lambda scene: (scene, pinlin.find_equilibrium(scene, scene.neutral(), max_iterations=30))),
        ("linearize", lambda se: pinlin.linearize(se[0], se[1].q, balancing=True)),
        ("modal_analysis", pinlin.modal_analysis),
    ]
    value = None
    for name, stage in stages:
        value = outcome(lambda stage=stage, value=value: stage(value), name)
        if value is None:
            return f"refused by {name}"
    return "analysed"


def main() -> None:
    for line in sys.stdin:
        path = line.strip()
        try:
            verdict = analyse(path)
        except Exception:  # noqa: BLE001 - the worker reports every other exception to its parent as a bug
            verdict = "BUG " + traceback.format_exc().replace("\n", " | ")
        print(f"{path}\t{verdict}", flush=True)


if __name__ == "__main__":
    main()
