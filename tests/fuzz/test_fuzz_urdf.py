"""Fuzzed URDFs through loading, a scene, linearization and modal analysis.

Valid URDFs are mutated: an attribute set to a nasty value (``nan``, ``1e999``,
``abc``, empty, negative), an element removed or duplicated, an entity trick
(an internal entity, an external one pointing at a local file, nested
expansions), or the text cut short.  Every stage must give a PinlinError or a
result whose error figures are finite; never another exception or a hang.

A link that is the child of two joints (a joint duplicated under another name) was
the one bug this fuzzer found in loading; the loader now refuses it (model/loading.py).
"""

from __future__ import annotations

import copy
import xml.etree.ElementTree as ET

from fuzz_strategies import outcome, urdf_values
from hypothesis import event, given
from hypothesis import strategies as st

import pinlin

BASES = {
    "double_pendulum": pinlin.data_path("urdf/double_pendulum.urdf").read_text(),
    "chain3": pinlin.pendulum_chain_urdf(3, tip_frame=True),
    "turntable": pinlin.data_path("urdf/turntable.urdf").read_text(),
}

ENTITIES = [
    '<!DOCTYPE robot [<!ENTITY v "0.5">]>',
    '<!DOCTYPE robot [<!ENTITY v SYSTEM "file:///etc/hostname">]>',
    '<!DOCTYPE robot [<!ENTITY a "1e300"><!ENTITY v "&a;&a;&a;&a;&a;&a;&a;&a;">]>',
    '<!DOCTYPE robot [<!ENTITY v "&v;">]>',
]


@st.composite
def mutated_urdfs(draw) -> str:
    text = BASES[draw(st.sampled_from(sorted(BASES)))]
    root = ET.fromstring(text)
    elements = list(root.iter())
    for _ in range(draw(st.sampled_from([1, 1, 1, 2, 3]))):  # mostly one change: most models then still load
        element = elements[draw(st.integers(0, len(elements) - 1))]
        op = draw(st.sampled_from(["attribute", "attribute", "remove", "duplicate"]))
        parent = next((p for p in root.iter() if element in list(p)), None)
        if op == "attribute" and element.attrib:
            key = draw(st.sampled_from(sorted(element.attrib)))
            element.set(key, draw(urdf_values()))
        elif op == "remove" and parent is not None:
            parent.remove(element)
        elif op == "duplicate" and parent is not None:
            parent.insert(list(parent).index(element) + 1, copy.deepcopy(element))
    out = ET.tostring(root, encoding="unicode")
    trick = draw(st.sampled_from(["none"] * 4 + ["entity", "truncate"]))
    if trick == "entity":
        out = draw(st.sampled_from(ENTITIES)) + out.replace('value="', 'value="&v;', 1)
    elif trick == "truncate":
        out = out[: draw(st.integers(0, len(out)))]
    return out


def _elements(robot: pinlin.Robot) -> list:
    springs = [pinlin.JointSpring(name, 10.0) for name in robot.joint_names if robot.joint(name).nv == 1]
    wrench = [pinlin.FollowerWrench("tip", force=(0.0, 0.0, 1.0))] if "tip" in robot.frame_names else []
    return springs + wrench


@given(text=mutated_urdfs())
def test_fuzzed_urdf_loads_and_analyses_or_says_why(text):
    stages = [
        ("load_urdf_string", lambda _: pinlin.load_urdf_string(text)),
        ("Scene", lambda robot: pinlin.Scene(robot, _elements(robot))),
        ("linearize", lambda scene: pinlin.linearize(scene, scene.neutral(), balancing=True)),
        ("modal_analysis", pinlin.modal_analysis),
    ]
    value = None
    for name, stage in stages:
        value = outcome(lambda stage=stage, value=value: stage(value), name)
        if value is None:
            event(f"refused by {name}")
            return
    event("analysed")
