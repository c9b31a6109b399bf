"""The checks every linearization makes of what it assembled, in one place for the single and batched paths.

- :func:`check_equilibrium` -- the relative residual on the free coordinates, refused above
  ``equilibrium_tol`` unless the point is held by actuator forces (``balancing``);
- :func:`check_finite_and_mass` -- no overflow reached M, C, K or the residual, and M is positive
  definite (:func:`check_mass`, naming the joints that carry no mass).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg.lapack as lapack

from ..errors import ComputationError, NotAnEquilibriumError, SingularMassError
from ..model.scene import Scene
from ..numerics.norms import fro
from .assembly import Assembly
from .plan import LinearizationPlan
from .state_form import null_motion

__all__ = ["check_equilibrium", "check_finite_and_mass", "check_mass", "massless_joints"]


def massless_joints(scene: Scene) -> list[str]:
    """Free joints whose whole subtree has neither mass nor rotational inertia."""
    model = scene.model
    mass = np.zeros(model.njoints)
    inertia = np.zeros(model.njoints)
    for jid in range(model.njoints - 1, 0, -1):
        mass[jid] += model.inertias[jid].mass
        inertia[jid] += np.abs(model.inertias[jid].inertia).sum()
        parent = model.parents[jid]
        mass[parent] += mass[jid]
        inertia[parent] += inertia[jid]
    free = set(scene.free_dofs.tolist())
    names = []
    for jid in range(1, model.njoints):
        j = scene.robot.joint(model.names[jid])
        if mass[jid] == 0 and inertia[jid] == 0 and any(i in free for i in range(j.idx_v, j.idx_v + j.nv)):
            names.append(j.name)
    return names


def check_mass(scene: Scene, M: np.ndarray) -> None:
    """Raise SingularMassError, naming the joints, unless M is positive definite (one Cholesky)."""
    if lapack.dpotrf(M, lower=True, clean=False)[1] == 0:  # the Cholesky factorization succeeded: PD
        return
    joints = massless_joints(scene)
    if not joints:
        smallest, coords = null_motion(M, scene.dof_names)
        joints = sorted({name.split("[")[0] for name in coords})
        why = f"the mass matrix is singular or indefinite (smallest eigenvalue {smallest:.3g}); its null motion moves"
    else:
        why = "the mass matrix is singular: no mass or inertia moves with"
    raise SingularMassError(
        f"{why} joints {joints}; give their links inertia or lock them (locked=[...])", joints
    )


def check_equilibrium(
    scene: Scene, plan: LinearizationPlan, base: Assembly, tol: float, balancing: bool
) -> tuple[np.ndarray, float]:
    """The residual on the free coordinates and its relative size; raise unless q is an equilibrium."""
    r = base.residual if plan.everything else base.residual[plan.rows]
    norm = fro(r)
    rel = norm / base.force_scale if base.force_scale > 0 else 0.0
    if rel > tol and not balancing:
        worst = int(np.argmax(np.abs(r)))
        raise NotAnEquilibriumError(
            f"q is not an equilibrium of the scene: relative residual {rel:.3e} > equilibrium_tol "
            f"{tol:g} (largest unbalanced force {r[worst]:.4g} on {scene.dof_names[worst]!r}); "
            f"use find_equilibrium, or balancing=True to hold q with actuator forces",
            residual=norm,
            relative_residual=rel,
        )
    return r, rel


def check_finite_and_mass(scene: Scene, M: np.ndarray, C: np.ndarray, base: Assembly) -> None:
    """Raise ComputationError for non-finite entries, SingularMassError for M not positive definite.

    ``force_scale`` covers tau, Q_e and K; one product covers M and C (a NaN or
    inf in either makes it non-finite), checked entry by entry only when it is.
    """
    if not (math.isfinite(base.force_scale) and math.isfinite(np.vdot(M, C))):
        if not (math.isfinite(base.force_scale) and np.isfinite(M).all() and np.isfinite(C).all()):
            raise ComputationError(
                "linearize: non-finite entries in M, C, K or the residual (overflow from extreme parameters?)"
            )
    check_mass(scene, M)
