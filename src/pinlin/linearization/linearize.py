"""Linearization of a scene at an equilibrium or steady motion (theory: equations).

:func:`linearize` runs the scene's Pinocchio passes once (:mod:`.assembly`),
with everything that does not depend on q decided beforehand in the scene's
:class:`~pinlin.linearization.plan.LinearizationPlan`; then the checks
(equilibrium, finite entries, positive definite mass, time invariance) and the
split of C and K into their symmetric and skew parts, rounding-level parts set
to exactly zero and reported.
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import (
    ParameterError,
)
from ..model.elements import WrenchElement
from ..model.evaluation import Evaluation
from ..model.scene import Scene
from .assembly import Assembly, assemble
from .checks import check_equilibrium, check_finite_and_mass
from .constrained import linearize_constrained
from .options import CONSTRAINT_TOL, EQUILIBRIUM_TOL, PERIODIC_TOL, RANK_TOL, LinearizeOptions
from .periodicity import PERIODIC_TEST_ANGLES, numeric_change, refuse_motions
from .plan import STRUCTURE_EPS_FACTOR, LinearizationPlan, plan_of
from .split import split_damping as _split_damping
from .split import split_stiffness as _split_stiffness
from .system import LinearizedSystem

__all__ = ["linearize", "generalized_force", "PERIODIC_TEST_ANGLES", "STRUCTURE_EPS_FACTOR"]













def linearize(
    scene: Scene,
    q,
    *,
    coordinates=None,
    balancing: bool = False,
    equilibrium_tol: float = EQUILIBRIUM_TOL,
    structure_tol: float | None = None,
    periodic_tol: float = PERIODIC_TOL,
    constraint_tol: float = CONSTRAINT_TOL,
    rank_tol: float = RANK_TOL,
) -> LinearizedSystem:
    """The linearized equations of ``scene`` around configuration ``q`` (theory: equations, constraints).

    .. math::
        M = \\partial\\tau/\\partial a,\\quad
        C = \\partial\\tau/\\partial v - \\partial Q_e/\\partial v,\\quad
        K = \\partial\\tau/\\partial q - \\partial Q_e/\\partial q

    on the free coordinates, at velocity v0 (zero except on prescribed joints)
    and a = 0, with the derivatives in the tangent space; then D, G, S, N are
    the symmetric and skew parts of C and K.  Only the Pinocchio algorithms the
    scene needs are run (see :mod:`pinlin.linearization.assembly`); they are listed in
    ``sys.calls``.

    With constraints (closed loops, contacts; theory: constraints) the system has
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
        100 n eps (:data:`STRUCTURE_EPS_FACTOR`).  What was dropped is reported in
        ``sys.dropped``.  Must be a finite number >= 0.
    periodic_tol : float
        Largest relative change of M, C, K, r allowed when a prescribed joint is
        moved by :data:`PERIODIC_TEST_ANGLES`, each against the system-wide scale
        of :func:`~pinlin.linearization.periodicity.numeric_change`.  Joints
        whose position provably does not enter the equations (a root turntable
        about an axis along gravity, an axisymmetric rotor, a joint held still:
        :mod:`pinlin.linearization.time_invariance`) are not moved; ``sys.notes``
        says which were proved and which were checked.
    constraint_tol : float
        With constraints: largest gap [m] (and rotation [rad]) accepted at q.
    rank_tol : float
        With constraints: a singular value of J_c counts as zero at or below
        rank_tol times the largest (:data:`~pinlin.linearization.constraint_set.RANK_TOL`).

    Raises
    ------
    ParameterError
        A tolerance is not a finite positive number (``structure_tol``: >= 0;
        ``rank_tol``: below 1), or ``coordinates`` is given without constraints.
    ConfigurationError
        q has the wrong size, is not finite, has a revolute angle beyond
        :data:`~pinlin.model.scene.ANGLE_LIMIT` or a zero quaternion.
    ComputationError
        M, C, K or the residual overflow (non-finite entries).
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

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0)])
    >>> sys = pinlin.linearize(scene, np.zeros(2))
    >>> sys.n, sys.nonzero, sys.calls
    (2, ('M', 'S'), ('computeGeneralizedGravityDerivatives', 'crba'))
    >>> np.round(sys.K, 4)
    array([[15.8511,  2.2073],
           [ 2.2073,  2.2073]])
    """
    t0 = time.perf_counter()
    q = scene.check_configuration(q)
    options = LinearizeOptions(balancing, equilibrium_tol, structure_tol, periodic_tol, constraint_tol, rank_tol)
    if scene.constraints:
        return linearize_constrained(scene, q, coordinates, options)
    if coordinates is not None:
        raise ParameterError("coordinates", "applies to scenes with constraints only; this scene has none")
    if scene.motions:
        refuse_motions(scene)
    plan = plan_of(scene)
    base = assemble(scene, q, stiffness=True, damping=True, mass=True)
    r, rel = check_equilibrium(scene, plan, base, equilibrium_tol, balancing)
    M, C, K = (base.M, base.C, base.K) if plan.everything else (a[plan.block] for a in (base.M, base.C, base.K))
    check_finite_and_mass(scene, M, C, base)
    calls, notes = base.calls, []
    if scene.prescribed:
        notes, more = _prescribed_notes(scene, plan, q, base, periodic_tol)
        calls = calls + more
    tol = plan.structure_tol if structure_tol is None else float(structure_tol)
    dropped: dict[str, float] = {}
    S, N = _split_stiffness(K, base.rounding_scale_K, tol, dropped)
    D, G = _split_damping(C, base, plan, tol, dropped)
    if balancing:
        notes.append(f"held at q by constant actuator forces (relative residual {rel:.2e})")
    (system,) = LinearizedSystem.stack(
        M=M, D=D, G=G, S=S, N=N, dof_names=scene.dof_names, q=q[None], v=scene.v0, residual=[rel],
        balancing=r[None].copy() if balancing else None, elapsed=time.perf_counter() - t0, calls=calls,
        dropped=[dropped], notes=[tuple(notes)],
    )  # fmt: skip
    return system






def _prescribed_notes(
    scene: Scene, plan: LinearizationPlan, q: np.ndarray, base: Assembly, tol: float
) -> tuple[list[str], list[str]]:
    """Notes on the time invariance of the prescribed joints, and the Pinocchio calls of the checks.

    Proved joints (``plan.proofs``, whose departure from symmetry is within ``tol``)
    cost nothing; the others are moved and assembled again (:func:`numeric_change`).
    """
    if tol >= plan.largest_departure:  # the usual case: every proof applies
        notes, checked = list(plan.proof_notes), plan.unproved
    else:
        proved = [p for p in plan.proofs.values() if p.departure <= tol]
        notes = [p.note for p in proved]
        checked = tuple(name for name in scene.prescribed if name not in {p.joint for p in proved})
    calls: list[str] = []
    if checked:
        change, calls = numeric_change(scene, q, base, checked, tol)
        notes.append(
            f"independent of the position of prescribed joint(s) {list(checked)}: relative change {change:.1e} "
            f"after moving them by {list(PERIODIC_TEST_ANGLES)} (checked numerically)"
        )
    return notes, calls


def generalized_force(scene: Scene, q, wrench: WrenchElement) -> np.ndarray:
    """Generalized force of a wrench on the free coordinates at q (theory: equations).

    Use it to build the input vector of f(t) in M x'' + C x' + K x = f(t): for a
    follower couple of unit size, ``generalized_force(scene, q,
    FollowerWrench("tip", torque=(0, 1, 0)))``.  With constraints the system's
    coordinates are z (theory: constraints): its input vector is
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

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0)])
    >>> wrench = pinlin.FollowerWrench("tip", force=(1.0, 0.0, 0.0))
    >>> pinlin.generalized_force(scene, np.zeros(2), wrench)  # [N m]: the tip is 1.2 m and 0.5 m out
    array([-1.2, -0.5])
    """
    if not isinstance(wrench, WrenchElement):
        raise ParameterError("wrench", f"expected a FollowerWrench or DeadWrench, got {wrench!r}")
    wrench.check(scene.robot)
    q = scene.check_configuration(q)
    ev = Evaluation(scene, q, np.asarray(scene.v0))
    return wrench.generalized_force(ev)[scene.free_dofs]
