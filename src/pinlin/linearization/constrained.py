"""Linearization of scenes with constraints in independent coordinates (theory: constraints).

At an equilibrium (q0, lambda0) (:mod:`.constrained_equilibrium`), v0 = 0, in
coordinates z with x = B z, B a basis of ker J_c (:mod:`.coordinates`):

.. math::
    M_z = B^T M B,\\quad C_z = B^T C B,\\quad K_z = B^T (K - K_\\lambda) B

K_lambda = d(J_c^T lambda)/dq at fixed lambda is the stiffness of the constraint
forces (the Hessian of -lambda^T Phi): without it the frequencies are wrong
wherever the constraints carry load.  J_c^T lambda is the generalized force of
world-fixed wrenches at the constrained frames, so K_lambda is their dead-wrench
stiffness, in closed form from the frame Jacobians the constraints already
computed (:func:`pinlin.model.constraints.dead_wrench_stiffness`): a constrained
scene runs the Pinocchio passes of the same scene without constraints, plus one
``computeJointJacobians`` + ``updateFramePlacements``.

A rank-deficient J_c is told apart from a singular configuration by
:mod:`.constrained_structure` when the redundancy is structural (a planar loop:
proved once per call from the Jacobians at hand) and otherwise by probing nearby
assembled configurations (:func:`~pinlin.linearization.singularity.check_regular`).
The default coordinates come from :func:`.coordinates.pivoted_basis`.

Contacts stay bilateral in the linearization (the standard stance
linearization): the equilibrium and the system's notes say when the ground
would have to pull or friction exceed mu.  Prescribed joint velocities are
refused with constraints (:class:`~pinlin.Scene`): their steady motion would
need the J_c-dot terms.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
import scipy.linalg.lapack as lapack

from ..errors import (
    AccuracyWarning,
    ComputationError,
    NotAnEquilibriumError,
    ParameterError,
    SingularMassError,
)
from ..model.scene import Scene
from ..numerics.norms import fro
from .constrained_structure import structurally_redundant
from .constraint_set import ConstrainedPoint, evaluate_constraints, linearization_point
from .coordinates import PIVOTED_METHOD, coordinate_basis, pivoted_basis
from .options import LinearizeOptions
from .plan import STRUCTURE_EPS_FACTOR
from .singularity import check_regular
from .state_form import null_motion
from .system import LinearizedSystem

__all__ = [
    "linearize_constrained",
    "constraint_stiffness",
    "BILATERAL_NOTE",
    "COORDINATE_CONDITION_WARN",
]

_TINY, _EPS = float(np.finfo(float).tiny), float(np.finfo(float).eps)

#: linearize warns when cond(J_d) of the chosen coordinates exceeds this: the basis entries
#: grow like cond(J_d), the projected matrices like its square, so their relative rounding
#: reaches eps cond^2 ~ 2e-8 at 1e4.
COORDINATE_CONDITION_WARN = 1e4

#: What sys.notes says about contacts (the linearization keeps them bilateral).
BILATERAL_NOTE = "contacts are treated as bilateral (the stance linearization): they neither lift off nor slide"

def linearize_constrained(scene: Scene, q: np.ndarray, coordinates, options: LinearizeOptions) -> LinearizedSystem:
    """The linearized equations of a scene with constraints in independent coordinates (theory: constraints).

    Called by :func:`pinlin.linearize` for scenes with constraints, with ``q``
    already checked (:meth:`Scene.check_configuration`); see there for the
    parameters (``options`` holds the checked tolerances), and the module docstring for the
    mathematics.

    Raises
    ------
    ConstraintViolationError
        q violates the constraints by more than ``constraint_tol`` (the gap [m] attached).
    OverconstrainedError
        No motion is left: rank J_c = nv.
    SingularConstraintError
        J_c loses rank at q (a toggle or change point), naming the constraints.
    NotAnEquilibriumError
        r - J_c^T lambda does not vanish at q and ``balancing`` is False.
    SingularMassError
        B^T M B is not positive definite.
    ParameterError, JointNotFoundError
        Bad ``coordinates`` (see :func:`~pinlin.linearization.coordinates.coordinate_basis`).

    Warns
    -----
    AccuracyWarning
        The coordinates are nearly singular: cond(J_d) > :data:`COORDINATE_CONDITION_WARN`.
    """
    t0 = time.perf_counter()
    point = linearization_point(scene, q, rank_tol=options.rank_tol, constraint_tol=options.constraint_tol)
    state, g, rel = point.state, point.g, point.relative_residual
    probes: list[str] = []
    if state.rank < state.m and state.rank != state.m - structurally_redundant(scene, state):
        check_regular(scene, q, state, probes)  # no structural proof of the redundancy: probe nearby
    if rel > options.equilibrium_tol and not options.balancing:
        worst_dof = int(np.argmax(np.abs(g)))
        raise NotAnEquilibriumError(
            f"q is not an equilibrium of the constrained scene: relative residual of r - J_c^T lambda {rel:.3e} "
            f"> equilibrium_tol {options.equilibrium_tol:g} (largest unbalanced force {g[worst_dof]:.4g} on "
            f"{scene.dof_names[worst_dof]!r}); use find_equilibrium, or balancing=True",
            residual=fro(g),
            relative_residual=rel,
        )
    if coordinates is None:  # the default: the same basis as coordinate_basis(state, names, None), leaner
        B, names, condition = pivoted_basis(state, scene.dof_names)
        method = PIVOTED_METHOD
    else:
        basis = coordinate_basis(state, scene.dof_names, coordinates)
        B, names, condition, method = basis.B, basis.dof_names, basis.condition, basis.method
    if condition > COORDINATE_CONDITION_WARN:
        warnings.warn(
            f"linearize: the coordinates {list(names)} are nearly singular here: the joints that follow "
            f"them have cond(J_d) = {condition:.2e} > {COORDINATE_CONDITION_WARN:g}, so M, C, K lose up to "
            f"about eps cond(J_d)^2 = {np.finfo(float).eps * condition**2:.1e} relative accuracy; choose "
            f"other joints, coordinates=None or coordinates='orthonormal'",
            AccuracyWarning,
            stacklevel=3,
        )
    calls = state.calls + probes + point.assembly.calls
    return _project_system(scene, q, point, (B, names, condition, method), options, calls, t0)


def _project_system(scene, q, point: ConstrainedPoint, basis, options: LinearizeOptions, calls, t0):
    """B^T M B, B^T C B and B^T (K - K_lambda) B split into the system's five matrices, with its notes."""
    B, names, condition, method = basis
    state, asm, rel, structure_tol = point.state, point.assembly, point.relative_residual, options.structure_tol
    # B^T A B of the three matrices in one batched product (each slice is the same gemm, bitwise),
    # and their symmetric parts in one sum: M, D = (C + C^T) / 2 and S = (K + K^T) / 2
    P = B.T @ np.array((asm.M, asm.C, point.Kt)) @ B
    H = P + P.transpose(0, 2, 1)
    H *= 0.5
    # one product: a NaN or inf anywhere makes it non-finite (inf * 0 is NaN); P finite if H is
    if not math.isfinite(np.vdot(H, H)) and not np.isfinite(H).all():
        raise ComputationError("linearize: non-finite entries in the projected M, C or K")
    M, D, S = H
    if lapack.dpotrf(M, lower=1, clean=0)[1] != 0:
        smallest, weak = null_motion(M, names)
        raise SingularMassError(
            f"the mass matrix B^T M B of the constrained system is not positive definite (smallest eigenvalue "
            f"{smallest:.3g}); the coordinates {weak} carry no inertia",
            weak,
        )
    dropped: dict[str, float] = {}
    K = P[2]
    N = K - K.T  # 2 N: halving is exact, so ||N|| = ||K - K^T|| / 2 bitwise (barring subnormals)
    # rounding in B^T (K - K_lambda) B: eps-relative to ||B||^2 (||K|| + ||K_lambda||) (||B||_2 <= ||B||_F)
    size = 0.5 * fro(N) / max(float(np.vdot(B, B)) * asm.rounding_scale_K, _TINY)
    if structure_tol is None:
        structure_tol = STRUCTURE_EPS_FACTOR * len(names) * _EPS
    G = np.zeros(K.shape)  # v0 = 0: C comes from the (symmetric) elements alone
    if size <= structure_tol:
        if size:
            dropped["N"] = size
        N = G  # both zero and read-only in the result: one array
    else:
        N *= 0.5
    notes = list(point.notes)
    if scene.contact_index:
        notes.append(BILATERAL_NOTE)
    notes.append(
        f"{len(names)} coordinate{'s' * (len(names) != 1)} z ({method}) for {len(scene.constraints)} "
        f"constraint{'s' * (len(scene.constraints) != 1)} "
        f"(rank J_c = {state.rank} of m = {state.m}); joint velocities = basis @ z; cond(J_d) = {condition:.3g}"
    )
    balance = None
    if options.balancing:
        balance = B.T @ point.g
        notes.append(
            f"held at q by constant actuator forces (relative residual {rel:.2e}): the minimum-norm joint forces "
            f"g = r - J_c^T lambda, orthogonal to the constraint forces; balancing = B^T g"
        )
    (system,) = LinearizedSystem.stack(
        M=M, D=D, G=G, S=S, N=N, dof_names=names, q=q[None], v=scene.v0, residual=[rel],
        balancing=None if balance is None else balance[None], elapsed=time.perf_counter() - t0, calls=calls,
        dropped=[dropped], notes=[tuple(notes)], basis=B, basis_names=scene.dof_names, basis_condition=condition,
        constraint_forces=point.forces,
    )  # fmt: skip
    return system


def constraint_stiffness(scene: Scene, q, lam) -> np.ndarray:
    """K_lambda = d(J_c(q)^T lambda)/dq at fixed lambda (nv x nv, tangent space; theory: constraints).

    The stiffness of the constraint forces alone: the dead-wrench stiffness of
    lambda at each constrained frame's origin and -lambda at its target frame's
    (:func:`pinlin.model.constraints.dead_wrench_stiffness`), what
    :func:`pinlin.linearize` subtracts from K.

    Parameters
    ----------
    scene : Scene
        A scene with constraints.
    q : (nq,) array
    lam : (m,) array
        Multipliers in scene order (3 per point constraint: force [N]; 6 per frame
        constraint: force [N], torque [N m]), world axes.

    Raises
    ------
    ParameterError
        No constraints, or lam of the wrong size.
    ConfigurationError
        q has the wrong size or is not finite.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    >>> loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0), name="loop")
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", 50.0, rest=0.2)], constraints=[loop])
    >>> eq = pinlin.find_equilibrium(scene, np.zeros(3))
    >>> K_lambda = pinlin.constraint_stiffness(scene, eq.q, eq.constraint_forces[0].force)
    >>> K_lambda.shape, bool(np.allclose(K_lambda, K_lambda.T))
    ((3, 3), True)
    """
    if not scene.constraints:
        raise ParameterError("scene", "has no constraints")
    lam = np.asarray(lam, dtype=float)
    if lam.shape != (scene.constraint_size,) or not np.all(np.isfinite(lam)):
        raise ParameterError("lam", f"expected {scene.constraint_size} finite multipliers, got shape {lam.shape}")
    return evaluate_constraints(scene, scene.check_configuration(q)).force_stiffness(lam)
