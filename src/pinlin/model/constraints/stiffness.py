"""The stiffness of world-fixed wrenches at frame origins, in closed form (theory: elements, constraints).

:func:`dead_wrench_stiffness` is d(J^T w)/dq at fixed w from the frames' Jacobians
alone (no kinematic Hessian, no Pinocchio pass): the constraint stiffness
K_lambda of every constraint, whose forces are such wrenches.
"""

from __future__ import annotations

import numpy as np

__all__ = ["dead_wrench_stiffness", "stack_wrenches", "CONSTANT_SUBSPACE_JOINTS"]

#: Multi-DOF joints whose motion subspace is constant in the joint frame and whose
#: configuration moves by right multiplication (``pin.integrate``), besides every 1-DOF
#: joint: the closed form of :func:`dead_wrench_stiffness` holds for chains of these.
CONSTANT_SUBSPACE_JOINTS = frozenset(
    {"JointModelFreeFlyer", "JointModelSpherical", "JointModelPlanar", "JointModelTranslation"}
)

def dead_wrench_stiffness(
    J: np.ndarray,
    forces: np.ndarray,
    torques: np.ndarray | None,
    before: np.ndarray,
    linear: np.ndarray | None = None,
) -> np.ndarray:
    """d(sum_k J_k^T w_k)/dq (nv x nv, tangent space) of world-fixed wrenches w_k = (F_k, T_k) at frame origins.

    With J the frame Jacobian in LOCAL_WORLD_ALIGNED axes, u_i its linear and
    w_i its angular columns: moving along degree of freedom j turns column i with
    the joints that support it and moves the point with every joint, so

    .. math::
        \\frac{\\partial u_i}{\\partial q_j} =
            \\begin{cases} \\omega_j \\times u_i & j \\preceq i \\\\
                           \\omega_i \\times u_j & \\text{otherwise} \\end{cases},\\qquad
        \\frac{\\partial \\omega_i}{\\partial q_j} = [j \\preceq i]\\, \\omega_j \\times \\omega_i

    where j <= i means that j's joint supports i's (its own included: every pair of a
    multi-DOF joint).  Hence K[i, j] = A[i, j] for j <= i and A[j, i] otherwise, with
    A = sum_k U_k^T [F_k]x W_k (A[i, j] = F . (w_j x u_i)), plus sum_k W_k^T [T_k]x W_k
    for j <= i: the dead-wrench stiffness of :class:`~pinlin.DeadWrench` (theory: elements) in world axes, without a kinematic Hessian.  Exact for 1-DOF joints and
    :data:`CONSTANT_SUBSPACE_JOINTS`; checked against central differences through
    ``pin.integrate`` in the tests.  The mask is the same for every wrench, so the
    wrenches are summed first (one product for all of them) and masked once.

    It does not call :func:`pinlin.model.elements.frame_pairs.fixed_wrench_stiffness` (the
    same derivative from the world Jacobian and each degree of freedom's accumulated
    spatial wrench) because the constraints already hold the LOCAL_WORLD_ALIGNED frame
    Jacobians J_c is built from, while that form first needs the accumulated wrenches
    (p x F and a support mask per frame, one more product) and a copy of the world
    Jacobian: more numpy calls for the same nv^2 product, rounded unlike the J_c it
    differentiates.

    Parameters
    ----------
    J : (k, 6, nv) ndarray
        The frames' Jacobians, LOCAL_WORLD_ALIGNED (linear rows first).
    forces : (k, 3) ndarray
        [N], world axes, at each frame's origin.
    torques : (k, 3) ndarray or None
        [N m], world axes; None when there are none.
    before : (nv, nv) bool ndarray
        before[i, j]: the joint of degree of freedom j supports (or is) that of i
        (:attr:`pinlin.Robot.dof_supports`); only the degrees of freedom that move
        a frame matter, and those lie on one chain.
    linear : (3k, nv) ndarray, optional
        ``J[:, :3].reshape(-1, nv)`` when the caller has it already (a point
        constraint set's J_c): the same numbers, one copy fewer.
    """
    if not len(J):
        return np.zeros(before.shape)
    nv = J.shape[2]
    W = J[:, 3:]
    FxW = (forces @ _GENERATORS).reshape(-1, 3, 3) @ W  # [F_k]x W_k
    U = J[:, :3].reshape(-1, nv) if linear is None else linear
    A = U.T @ FxW.reshape(-1, nv)
    K = np.where(before, A, A.T)
    if torques is not None:
        TxW = (torques @ _GENERATORS).reshape(-1, 3, 3) @ W
        K += np.where(before, W.reshape(-1, nv).T @ TxW.reshape(-1, nv), 0.0)
    return K


def stack_wrenches(terms) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """(J, forces, torques) arrays of :func:`dead_wrench_stiffness` from (J, force, torque or None) terms."""
    J = np.array([t[0] for t in terms]).reshape(len(terms), 6, -1)
    forces = np.array([t[1] for t in terms]).reshape(-1, 3)
    torques = None
    if any(t[2] is not None for t in terms):
        torques = np.array([_ZERO3 if t[2] is None else t[2] for t in terms])
    return J, forces, torques


def _skew(a) -> np.ndarray:
    """[a]x: [a]x b = a x b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


#: [a]x = a @ _GENERATORS reshaped (3, 3): the three generators [e_b]x, flattened (3 x 9).
_GENERATORS = np.array([_skew(e) for e in np.eye(3)]).reshape(3, 9)
_ZERO3 = np.zeros(3)
