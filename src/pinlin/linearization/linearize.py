"""Linearization of a scene at an equilibrium or steady motion (SPEC section 1)."""

from __future__ import annotations

import math
import time

import numpy as np
import pinocchio as pin
import scipy.linalg

from .assembly import assemble, fro
from ..model.elements import WrenchElement
from ..errors import (
    ComputationError,
    NotAnEquilibriumError,
    ParameterError,
    SingularMassError,
    TimePeriodicError,
)
from ..model.scene import Scene
from .constraint_set import CONSTRAINT_TOL, RANK_TOL
from .system import LinearizedSystem, null_motion
from .workspace import Evaluation

__all__ = ["linearize", "generalized_force", "PERIODIC_TEST_ANGLES", "STRUCTURE_EPS_FACTOR"]

#: Offsets [rad or m] of a prescribed joint at which the equations are
#: evaluated again to check that they do not depend on its position.
PERIODIC_TEST_ANGLES = (1.0, 2.5)


#: Default structure_tol is STRUCTURE_EPS_FACTOR n eps: Pinocchio's recursive algorithms
#: accumulate a few rounding errors per joint, so an exactly (skew-)symmetric part that
#: should vanish comes out at a small multiple of n eps of the computed part's norm.
STRUCTURE_EPS_FACTOR = 100.0


def _structure_tol(n: int) -> float:
    return STRUCTURE_EPS_FACTOR * n * np.finfo(float).eps


def _massless_joints(scene: Scene) -> list[str]:
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


def _check_mass(scene: Scene, M: np.ndarray) -> None:
    if scipy.linalg.lapack.dpotrf(M, lower=1, clean=0)[1] == 0:  # Cholesky succeeded: positive definite
        return
    joints = _massless_joints(scene)
    if not joints:
        smallest, coords = null_motion(M, scene.dof_names)
        joints = sorted({name.split("[")[0] for name in coords})
        why = f"the mass matrix is singular or indefinite (smallest eigenvalue {smallest:.3g}); its null motion moves"
    else:
        why = "the mass matrix is singular: no mass or inertia moves with"
    raise SingularMassError(
        f"{why} joints {joints}; give their links inertia or lock them (locked=[...])", joints
    )


def _time_invariance(scene: Scene, q: np.ndarray, base, tol: float) -> tuple[float, list[str]]:
    """Largest relative change of M, C, K and the residual when a prescribed joint moves,
    and the Pinocchio calls this check made."""
    f = scene.free_dofs
    ref = {
        "M": base.M[np.ix_(f, f)],
        "C": base.C[np.ix_(f, f)],
        "K": base.K[np.ix_(f, f)],
    }
    worst = 0.0
    calls: list[str] = []
    for name in scene.prescribed:
        j = scene.robot.joint(name)
        for offset in PERIODIC_TEST_ANGLES:
            dq = np.zeros(scene.model.nv)
            dq[j.idx_v] = offset
            other = assemble(scene, pin.integrate(scene.model, q, dq), stiffness=True, damping=True, mass=True)
            calls.extend(other.calls)
            change = max(
                fro(getattr(other, key)[np.ix_(f, f)] - val) / max(fro(val), np.finfo(float).tiny)
                for key, val in ref.items()
            )
            change = max(
                change,
                fro(other.residual[f] - base.residual[f]) / max(base.force_scale, np.finfo(float).tiny),
            )
            worst = max(worst, change)
            if change > tol:
                raise TimePeriodicError(
                    f"the linearized equations depend on the position of prescribed joint {name!r} "
                    f"(relative change {change:.2e} after {offset} rad): with its prescribed velocity "
                    f"they are time-periodic, not constant-coefficient, and cannot be analysed as "
                    f"M x'' + C x' + K x = f",
                    joint=name,
                    variation=change,
                )
    return worst, calls


def linearize(
    scene: Scene,
    q,
    *,
    coordinates=None,
    balancing: bool = False,
    equilibrium_tol: float = 1e-8,
    structure_tol: float | None = None,
    periodic_tol: float = 1e-8,
    constraint_tol: float = CONSTRAINT_TOL,
    rank_tol: float = RANK_TOL,
) -> LinearizedSystem:
    """The linearized equations of ``scene`` around configuration ``q`` (SPEC sections 1, 10).

    .. math::
        M = \\partial\\tau/\\partial a,\\quad
        C = \\partial\\tau/\\partial v - \\partial Q_e/\\partial v,\\quad
        K = \\partial\\tau/\\partial q - \\partial Q_e/\\partial q

    on the free coordinates, at velocity v0 (zero except on prescribed joints)
    and a = 0, with the derivatives in the tangent space; then D, G, S, N are
    the symmetric and skew parts of C and K.  Only the Pinocchio algorithms the
    scene needs are run (see :mod:`pinlin.assembly`); they are listed in
    ``sys.calls``.

    With constraints (closed loops, contacts; SPEC section 10) the system has
    n = nv - rank J_c coordinates z, joint velocities = ``sys.basis @ z``:

    .. math::
        M_z = B^T M B,\\quad C_z = B^T C B,\\quad K_z = B^T (K - K_\\lambda) B

    with lambda the constraint forces at q (minimum-norm when redundant, in
    ``sys.constraint_forces``) and K_lambda their stiffness
    (:mod:`pinlin.linearization.constrained`).  Contacts are linearized as
    bilateral (the stance linearization); ``sys.notes`` says when the ground
    would have to pull or friction exceed mu.

    Parameters
    ----------
    scene : Scene
    q : (nq,) array
        Full configuration (prescribed joints included) at which to linearize.
    coordinates : None, "orthonormal" or sequence of str
        Scenes with constraints only: the coordinates z.  None picks joints by a
        column-pivoted QR of J_c (``sys.dof_names`` names them); a list names the
        joints (or degrees of freedom) to use; ``"orthonormal"`` takes an
        orthonormal basis of ker J_c (names ``z1``, ...).  The eigenvalues do not
        depend on the choice; ``sys.basis_condition`` reports cond(J_d).
    balancing : bool
        Accept a q that is not an equilibrium by holding it with constant
        generalized forces (actuators); they are returned in ``sys.balancing``
        and do not change K.  Never applied unless asked.
    equilibrium_tol : float
        Largest relative residual ||r|| / (||tau|| + ||Q_e|| + ||K||) accepted as
        equilibrium (the K term: a unit displacement's force).
    structure_tol : float, optional
        Relative size below which the skew part of K (the symmetric part of the
        Coriolis C) that Pinocchio's rounding leaves is set to exactly zero; the
        reference scale is the norm of the Pinocchio-computed part.  Default
        100 n eps.  What was dropped is reported in ``sys.dropped``.
    periodic_tol : float
        Largest relative change of M, C, K, r allowed when a prescribed joint is
        moved by :data:`PERIODIC_TEST_ANGLES`.
    constraint_tol : float
        With constraints: largest gap [m] (and rotation [rad]) accepted at q.
    rank_tol : float
        With constraints: a singular value of J_c counts as zero at or below
        rank_tol times the largest (:data:`~pinlin.linearization.constraint_set.RANK_TOL`).

    Raises
    ------
    ConfigurationError
        q has the wrong size or is not finite.
    NotAnEquilibriumError
        q is not an equilibrium and ``balancing`` is False.
    SingularMassError
        The mass matrix of the free coordinates is not positive definite.
    TimePeriodicError
        The equations depend on a prescribed joint's position.
    ConstraintViolationError
        q violates the scene's constraints (``gap`` [m] attached).
    OverconstrainedError
        The constraints leave no motion (rank J_c = nv).
    SingularConstraintError
        J_c loses rank at q (a linkage at a toggle or change point), naming the constraints.
    """
    t0 = time.perf_counter()
    q = scene.check_configuration(q)
    if not (equilibrium_tol > 0 and math.isfinite(equilibrium_tol)):
        raise ParameterError("equilibrium_tol", f"must be a positive number, got {equilibrium_tol!r}")
    if not (periodic_tol > 0 and math.isfinite(periodic_tol)):
        raise ParameterError("periodic_tol", f"must be a positive number, got {periodic_tol!r}")
    if scene.constraints:
        from .constrained import linearize_constrained

        return linearize_constrained(
            scene, q, coordinates=coordinates, balancing=balancing, equilibrium_tol=equilibrium_tol,
            structure_tol=structure_tol, constraint_tol=constraint_tol, rank_tol=rank_tol,
        )  # fmt: skip
    if coordinates is not None:
        raise ParameterError("coordinates", "applies to scenes with constraints only; this scene has none")
    f = scene.free_dofs
    n = len(f)
    everything = n == scene.model.nv
    base = assemble(scene, q, stiffness=True, damping=True, mass=True)
    r = base.residual if everything else base.residual[f]
    rel = fro(r) / base.force_scale if base.force_scale > 0 else 0.0
    if rel > equilibrium_tol and not balancing:
        worst = int(np.argmax(np.abs(r)))
        raise NotAnEquilibriumError(
            f"q is not an equilibrium of the scene: relative residual {rel:.3e} > equilibrium_tol "
            f"{equilibrium_tol:g} (largest unbalanced force {r[worst]:.4g} on {scene.dof_names[worst]!r}); "
            f"use find_equilibrium, or balancing=True to hold q with actuator forces",
            residual=fro(r),
            relative_residual=rel,
        )

    def restrict(a):
        return a if everything else a[np.ix_(f, f)]

    M, C, K = restrict(base.M), restrict(base.C), restrict(base.K)
    if not math.isfinite(base.force_scale + fro(C) + fro(M)):
        raise ComputationError(
            "linearize: non-finite entries in M, C, K or the residual (overflow from extreme parameters?)"
        )
    _check_mass(scene, M)
    notes = []
    calls = list(base.calls)
    if scene.prescribed:
        change, more = _time_invariance(scene, q, base, periodic_tol)
        notes.append(f"independent of the prescribed joint positions (relative change {change:.1e})")
        calls.extend(more)

    tol = _structure_tol(n) if structure_tol is None else float(structure_tol)
    tiny = np.finfo(float).tiny
    dropped: dict[str, float] = {}
    S = (K + K.T) * 0.5
    N = (K - K.T) * 0.5
    size = fro(N) / max(base.rounding_scale_K, tiny)
    if size <= tol:
        if size:
            dropped["N"] = size
        N = np.zeros_like(K)
    if base.coriolis_D is None:  # C comes from the elements alone: exactly symmetric
        D, G = C, np.zeros_like(C)
    else:
        D = (C + C.T) * 0.5
        G = (C - C.T) * 0.5
        D_rnea = restrict(base.coriolis_D)
        size = fro(D_rnea) / max(base.rounding_scale_C, tiny)
        if size <= tol:  # the Coriolis part of C is skew in exact arithmetic
            D = D - D_rnea
            if size:
                dropped["D (Coriolis rounding)"] = size
        size = fro(G) / max(base.rounding_scale_C, tiny)
        if size <= tol:
            if size:
                dropped["G"] = size
            G = np.zeros_like(C)
    if balancing:
        notes.append(f"held at q by constant actuator forces (relative residual {rel:.2e})")
    return LinearizedSystem.trusted(
        M,
        D,
        G,
        S,
        N,
        dof_names=scene.dof_names,
        q=q,
        v=scene.v0,
        residual=rel,
        balancing=r.copy() if balancing else None,
        elapsed=time.perf_counter() - t0,
        calls=tuple(calls),
        dropped=dropped,
        notes=tuple(notes),
        method="analytic",
    )


def generalized_force(scene: Scene, q, wrench: WrenchElement) -> np.ndarray:
    """Generalized force of a wrench on the free coordinates at q (SPEC section 1).

    Use it to build the input vector of f(t) in M x'' + C x' + K x = f(t): for a
    follower couple of unit size, ``generalized_force(scene, q,
    FollowerWrench("tip", torque=(0, 1, 0)))``.  With constraints the system's
    coordinates are z (SPEC section 10): its input vector is
    ``sys.basis.T @ generalized_force(scene, q, wrench)``.

    Returns
    -------
    (n,) ndarray
        Q = J^T w on the free coordinates [N or N m].

    Raises
    ------
    ParameterError
        ``wrench`` is not a FollowerWrench or DeadWrench.
    FrameNotFoundError
        Its frame is not in the robot.
    ConfigurationError
        q has the wrong size or is not finite.
    """
    if not isinstance(wrench, WrenchElement):
        raise ParameterError("wrench", f"expected a FollowerWrench or DeadWrench, got {wrench!r}")
    wrench.check(scene.robot)
    q = scene.check_configuration(q)
    ev = Evaluation(scene, q, np.asarray(scene.v0))
    return wrench.generalized_force(ev)[scene.free_dofs]
