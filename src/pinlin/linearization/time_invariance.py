"""Do the linearized equations depend on the position of a prescribed joint? (theory: elements)

A prescribed joint moves at a constant velocity Omega, so its position grows with
time; the linearized equations are constant-coefficient only if they do not
depend on it.  Where the scene's structure settles the question, it is decided
once per scene (:func:`invariance_proofs`), from the model alone: the position
of the joint is then a symmetry of the whole scene, at every configuration.

1. **A root joint** (its parent is the world) turning about an axis along gravity
   (or without gravity), or sliding along any fixed axis: moving its whole subtree
   rigidly about (along) that world-fixed axis preserves the kinetic energy,
   gravity's potential up to a constant, and every element known to be invariant:
   joint-space elements (joint springs and dampers read their own joint's
   coordinates, Rayleigh damping M and the springs' K_e), body-fixed loads
   (follower wrenches: fixed in their body), dead loads outside the subtree or
   along the axis.
2. **A rotor**: a revolute joint whose subtree is one rigid body with its centre of
   mass on the axis and an inertia symmetric about it, no load on it and only
   joint-space elements and loads elsewhere: turning it changes neither the
   kinetic energy nor the weight's potential.
3. A joint held still (velocity 0) does not move.

What an element depends on is its class's own ``invariance`` declaration
(:func:`invariance_kind`; the rule is in :class:`~pinlin.Element`): an element
whose class declares nothing, a subclass of a built-in element included, is
"unknown" and stops cases 1 and 2.

Everything else (elements between frames, a tilted turntable, an unbalanced
rotor) is checked numerically at each linearization
(:func:`pinlin.linearization.periodicity.numeric_change`): the equations are assembled again
with the joint moved by a few offsets and compared against one system-wide scale, so an
exactly zero matrix (an undamped system's C) does not turn rounding into a huge
relative change.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..model.elements.invariance import (
    BODY_FIXED_LOAD,
    DEAD_LOAD,
    INVARIANCE_KINDS,
    JOINT_SPACE,
    UNKNOWN,
    declared_kind,
    invariance_kind,
)
from ..model.scene import Scene

__all__ = [
    "InvarianceProof",
    "invariance_kind",
    "invariance_proofs",
    "INVARIANCE_KINDS",
    "JOINT_SPACE",
    "BODY_FIXED_LOAD",
    "DEAD_LOAD",
    "UNKNOWN",
    "SYMMETRY_TOL",
]


#: Relative departure from an exact symmetry (gravity or a dead force across the axis, a
#: centre of mass off it, an inertia not symmetric about it) still taken as a symmetry by
#: a proof: a URDF's data are either exactly symmetric or far from it, and a departure of
#: 1e-12 changes the equations by about as much, far below the default periodic_tol.  The
#: proof records its departure; linearize uses it only when periodic_tol is not smaller.
SYMMETRY_TOL = 1e-12

_LOADS = (BODY_FIXED_LOAD, DEAD_LOAD)



@dataclass(frozen=True)
class InvarianceProof:
    """Why the equations do not depend on the position of one prescribed joint.

    Attributes
    ----------
    joint : str
    note : str
        The reason, for ``sys.notes``.
    departure : float
        Largest relative departure from the exact symmetry (0 when exact).
    """

    joint: str
    note: str
    departure: float


def _motion_axis(model: pin.Model, jid: int) -> tuple[str, np.ndarray] | None:
    """("rotation" or "translation", unit axis in the joint frame) of a 1-DOF joint, else None."""
    jm = model.joints[jid]
    data = jm.createData()
    jm.calc(data, np.asarray(jm.lieGroup().neutral, dtype=float))
    S = np.asarray(data.S, dtype=float).ravel()
    linear, angular = S[:3], S[3:]
    if not np.any(linear) and np.any(angular):
        return "rotation", angular / np.linalg.norm(angular)
    if np.any(linear) and not np.any(angular):
        return "translation", linear / np.linalg.norm(linear)
    return None  # helical or unknown: no proof


def _across(vector: np.ndarray, axis: np.ndarray) -> float:
    """Relative size of the part of ``vector`` across the unit ``axis`` (0 for a zero vector)."""
    size = float(np.linalg.norm(vector))
    return float(np.linalg.norm(np.cross(vector, axis))) / size if size else 0.0


def _subtree_joints(model: pin.Model, jid: int) -> set[int]:
    return {int(j) for j in model.subtrees[jid]}


def _root_proof(
    scene: Scene, kinds: tuple[str, ...], name: str, jid: int, kind: str, axis: np.ndarray
) -> InvarianceProof | None:
    """Case 1 of the module docstring, or None; ``kinds`` are the elements' :func:`invariance_kind`."""
    model = scene.model
    if model.parents[jid] != 0:
        return None
    world_axis = model.jointPlacements[jid].rotation @ axis
    departure = 0.0
    if kind == "rotation":
        departure = _across(scene.gravity, world_axis)
    inside = _subtree_joints(model, jid)
    for element, depends in zip(scene.elements, kinds):
        if depends in (JOINT_SPACE, BODY_FIXED_LOAD):
            continue
        if depends != DEAD_LOAD:
            return None  # an element the proof does not know (between frames, user-defined)
        frame_joint = model.frames[scene.robot.frame_id(element.frame)].parentJoint
        if kind == "rotation" and frame_joint in inside:
            departure = max(departure, _across(element.force, world_axis), _across(element.torque, world_axis))
    if departure > SYMMETRY_TOL:
        return None
    how = "turning about a fixed axis" + (" along gravity" if scene.has_gravity else " without gravity")
    if kind == "translation":
        how = "sliding along a fixed axis"
    return InvarianceProof(
        name,
        f"independent of the position of prescribed joint {name!r} by symmetry: a root joint {how}, "
        f"every element invariant (departure {departure:.1e})",
        departure,
    )


def _rotor_proof(
    scene: Scene, kinds: tuple[str, ...], name: str, jid: int, kind: str, axis: np.ndarray
) -> InvarianceProof | None:
    """Case 2 of the module docstring, or None; ``kinds`` are the elements' :func:`invariance_kind`."""
    model = scene.model
    if kind != "rotation" or _subtree_joints(model, jid) != {jid}:
        return None
    for element, depends in zip(scene.elements, kinds):
        if depends == JOINT_SPACE:
            continue
        if depends not in _LOADS or model.frames[scene.robot.frame_id(element.frame)].parentJoint == jid:
            return None  # a load on the rotor turns with it; unknown elements are not proved
    body = model.inertias[jid]
    I = np.asarray(body.inertia, dtype=float)
    c = np.asarray(body.lever, dtype=float)
    size = float(np.linalg.norm(I))
    gyration = math.sqrt(size / body.mass) if body.mass > 0 else 0.0
    P = np.eye(3) - np.outer(axis, axis)
    plane = P @ I @ P
    departure = max(
        float(np.linalg.norm(np.cross(c, axis))) / max(float(np.linalg.norm(c)) + gyration, np.finfo(float).tiny),
        float(np.linalg.norm(np.cross(I @ axis, axis))) / max(size, np.finfo(float).tiny),
        float(np.linalg.norm(plane - np.trace(plane) / 2 * P)) / max(size, np.finfo(float).tiny),
    )
    if body.mass == 0 and size == 0:
        departure = 0.0  # a massless rotor carries nothing that could turn
    if departure > SYMMETRY_TOL:
        return None
    return InvarianceProof(
        name,
        f"independent of the position of prescribed joint {name!r} by symmetry: an axisymmetric rigid rotor "
        f"(centre of mass on the axis, inertia symmetric about it) with no load on it (departure {departure:.1e})",
        departure,
    )


def invariance_proofs(scene: Scene) -> dict[str, InvarianceProof]:
    """The prescribed joints whose position provably does not enter the equations, and why.

    Decided from the model and the elements alone (module docstring); a joint
    missing from the result is checked numerically by :func:`numeric_change`.

    Raises
    ------
    ParameterError
        An element's class declares an ``invariance`` not in :data:`INVARIANCE_KINDS`
        (checked for every scene, with or without prescribed joints).
    """
    classes = dict.fromkeys(type(element) for element in scene.elements)  # in order: the first bad one raises
    declared = {cls: declared_kind(cls) for cls in classes}
    kinds = tuple(declared[type(element)] for element in scene.elements)
    out: dict[str, InvarianceProof] = {}
    for name, omega in scene.prescribed.items():
        if omega == 0:
            out[name] = InvarianceProof(
                name, f"prescribed joint {name!r} is held still (velocity 0): its position does not change", 0.0
            )
            continue
        jid = scene.robot.joint(name).id
        motion = _motion_axis(scene.model, jid)
        if motion is None:
            continue
        proof = _root_proof(scene, kinds, name, jid, *motion)
        proof = proof or _rotor_proof(scene, kinds, name, jid, *motion)
        if proof is not None:
            out[name] = proof
    return out

