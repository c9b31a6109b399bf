"""Redundant constraint equations proved from the mechanism's structure: planar constraints (theory: constraints).

A rank-deficient J_c is either redundant (the same rank at every assembled
configuration nearby) or singular (a toggle); :func:`~.singularity.check_regular`
tells them apart by probing nearby configurations, which costs two loop closures.
For a planar constraint a theorem decides it without probing.

**Planar constraints.**  Let every degree of freedom that moves a constraint's
frame (and its target frame) have a world twist (v_j, omega_j) with omega_j
parallel to one unit vector a and a . v_j = 0 (revolute joints about parallel
axes, prismatic joints across them, planar joints).  Such twists span the Lie
algebra of the planar motions normal to a, and moving along them changes each
twist by the adjoint of a planar motion, which keeps that property; the joints
the constraints accept (:meth:`~pinlin.model.constraints.Constraint.check`) have a
motion subspace constant in the joint frame.  So it holds at every configuration,
and then a . (v_j + omega_j x p) = 0 for every point p and omega_j x a = 0: the
frame's origin velocity has no component along a and its angular velocity none
across a.  A point constraint has one equation that is identically redundant
(a^T J_c = 0 on its rows), a frame constraint three (its linear row along a,
its angular rows across a).  These left null vectors of J_c live on disjoint
rows, so rank J_c <= m - s everywhere, s their number.  If rank J_c(q) = m - s,
the rank cannot rise nearby (it is at most m - s) nor fall (the rank is lower
semicontinuous): it is locally constant, q is regular, and the probes, which
look for a higher rank nearby, would find none.  Otherwise (a lower rank, or
constraints that are not planar) the probes still run.

In LOCAL_WORLD_ALIGNED axes a frame's Jacobian column j is (v_j + omega_j x p,
omega_j): the test reads the Jacobians J_c was built from, no Pinocchio pass.
"""

from __future__ import annotations

import math

import numpy as np

from ..model.scene import Scene
from .constraint_set import ConstraintState

__all__ = ["structurally_redundant", "PLANAR_TOL", "PLANAR_REDUNDANT"]

#: A frame's Jacobian is planar about a when its angular columns deviate from a, and its
#: linear columns have a component along a, by at most PLANAR_TOL times the largest such
#: column: parallel joint axes typed or read from a file agree to ~1e-16, and a tilt below
#: RANK_TOL (1e-9) could not change the rank decision the proof stands in for anyway.
PLANAR_TOL = 1e-12

#: Identically redundant equations of a planar constraint, by kind (module docstring).
PLANAR_REDUNDANT = {"point": 1, "frame": 3}


def _planar(jacobians: list[np.ndarray]) -> bool:
    """True when the frames' (6 x nv, LOCAL_WORLD_ALIGNED) Jacobians are planar about one normal a.

    On Python floats, column by column (a loop's few degrees of freedom: cheaper than
    numpy's fixed costs); every test is written so that a NaN fails it.
    """
    columns = [c for J in jacobians for c in J.T.tolist()]  # (v_x, v_y, v_z, w_x, w_y, w_z) each
    largest, normal = 0.0, None
    for c in columns:
        w2 = c[3] * c[3] + c[4] * c[4] + c[5] * c[5]
        if w2 > largest:
            largest, normal = w2, c
    if normal is None:  # no rotation at all: no normal to test against
        return False
    size = math.sqrt(largest)
    ax, ay, az = normal[3] / size, normal[4] / size, normal[5] / size
    across_tol = PLANAR_TOL * size
    along_tol = PLANAR_TOL * max(abs(x) for c in columns for x in c[:3])
    for vx, vy, vz, wx, wy, wz in columns:
        across = (abs(ay * wz - az * wy), abs(az * wx - ax * wz), abs(ax * wy - ay * wx))  # |a x w_j|
        if not (across[0] <= across_tol and across[1] <= across_tol and across[2] <= across_tol):
            return False
        if not abs(ax * vx + ay * vy + az * vz) <= along_tol:  # a . (v_j + w_j x p)
            return False
    return True


def structurally_redundant(scene: Scene, state: ConstraintState) -> int:
    """s: the number of constraint equations proved redundant at every configuration (module docstring).

    Counts the planar constraints' identically redundant equations; 0 when none is
    planar.  Reads the constraints' frame Jacobians from ``state.ev`` (computed for
    J_c already).
    """
    ev, s = state.ev, 0
    for c in scene.constraints:
        frames = (c.frame,) if c.target_frame is None else (c.frame, c.target_frame)
        if _planar([ev.world_aligned_jacobian(ev.robot.frame_id(f)) for f in frames]):
            s += PLANAR_REDUNDANT[c.kind]
    return s
