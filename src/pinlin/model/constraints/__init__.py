"""Kinematic constraints: closed loops and contacts (theory: constraints).

A constraint is a small frozen value, like an element: it names a frame and a
target and, at a configuration q, gives

- its residual Phi(q) (m equations, zero when satisfied) and the exact dPhi/dq
  used to close loops (:meth:`Constraint.closure_jacobian`);
- its Jacobian J_c (m x nv, tangent space) in velocity form: the relative velocity
  of the frame with respect to its target in world axes, so that the multipliers
  lambda are the world-axes force (and torque) that the constraint applies ON the
  frame, at its origin, and -lambda on the target;
- the stiffness of the constraint forces at fixed lambda,
  K_lambda = d(J_c^T lambda)/dq (:meth:`Constraint.force_stiffness`).  J_c^T lambda
  is the generalized force of world-fixed (dead) wrenches, lambda at the frame's
  origin and -lambda at the target frame's, so K_lambda is their dead-wrench
  stiffness, computed in closed form from the frame Jacobians the constraint
  already has (:func:`dead_wrench_stiffness`): no kinematic Hessian, no extra
  Pinocchio pass.

On the constraint manifold the velocity form is dPhi/dq; away from it the two
differ by terms that vanish on the manifold, which changes neither the
equilibrium nor the projected stiffness B^T (K - K_lambda) B (theory: constraints).

Contacts are point constraints on the ground (``contact=True``): the linearization
treats them as bilateral, and :meth:`PointConstraint.contact_status` says whether
the equilibrium needs the ground to pull or more friction than ``friction``.

One concept per module:

- :mod:`.base` -- :class:`Constraint`, the interface;
- :mod:`.point` -- :class:`PointConstraint` (loops closed at a point, ground
  contacts) and :func:`ground_contacts`;
- :mod:`.frame` -- :class:`FrameConstraint` (welds);
- :mod:`.forces` -- :class:`ConstraintForce` and :class:`ContactStatus`, what an
  equilibrium reports;
- :mod:`.stiffness` -- :func:`dead_wrench_stiffness`, K_lambda in closed form.
"""

from .base import Constraint
from .forces import ConstraintForce, ContactStatus
from .frame import ROTATION_TOL, FrameConstraint
from .point import PointConstraint, ground_contacts
from .stiffness import CONSTANT_SUBSPACE_JOINTS, dead_wrench_stiffness, stack_wrenches

__all__ = [
    "Constraint",
    "PointConstraint",
    "FrameConstraint",
    "ConstraintForce",
    "ContactStatus",
    "ground_contacts",
    "dead_wrench_stiffness",
    "stack_wrenches",
    "ROTATION_TOL",
    "CONSTANT_SUBSPACE_JOINTS",
]
