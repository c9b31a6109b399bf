"""The result of an equilibrium search, with or without constraints."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..results import Result

__all__ = ["EquilibriumResult"]


@dataclass(frozen=True, repr=False, eq=False)
class EquilibriumResult(Result):
    """An equilibrium (or steady motion) found by :func:`find_equilibrium`.

    Attributes
    ----------
    q : (nq,) ndarray
        The configuration (prescribed joints included, at their starting position).
    residual : float
        ||r(q)|| on the free coordinates [N, N m].
    relative_residual : float
        ||r|| / (||tau|| + ||Q_e|| + ||K||), see :class:`pinlin.linearization.assembly.Assembly`.
    iterations : int
        Newton steps taken.
    history : tuple of float
        ||r|| before each step and at the end.
    elapsed : float
        Seconds.
    method : str
        ``"newton"``, or ``"newton (least-squares steps at iterations [...])"`` when K
        was singular at some iterate and the minimum-norm step was taken instead.
    error : float
        The headline error figure: ``relative_residual``.
    notes : tuple of str
        Anything the solver wants the user to know (least-squares steps; for
        constraints: the loop-closure step, redundant equations, contacts whose force
        the ground cannot give).
    constraint_forces : tuple of ConstraintForce
        With constraints (theory: constraints): one entry per constraint, in scene
        order, the world-axes force (``.force`` [N]) and, for a frame constraint,
        torque (``.torque`` [N m]) that the constraint applies on its frame (at the
        frame origin; the target frame receives the opposite).  Minimum-norm when
        the constraints are redundant (``redundant`` > 0).  Empty without constraints.
    contacts : tuple of ContactStatus
        One entry per contact (``PointConstraint(..., contact=True)``): normal and
        tangential force, whether the ground must pull or friction exceeds mu.
    redundant : int
        Number of redundant constraint equations, m - rank J_c.
    constraint_gap : float
        Largest distance [m] left between a constrained frame and its target.
    closure : ClosureResult or None
        The loop-closure step that closed the constraints from q0 (None without constraints;
        ``assembly`` is its 0.2 name, kept for 0.3).

    For a scene with constraints, ``residual`` is ||r - J_c^T lambda|| and the
    relative residual divides it by ||tau|| + ||Q_e|| + ||J_c^T lambda|| + ||K - K_lambda||.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0)])
    >>> eq = pinlin.find_equilibrium(scene, np.array([0.1, 0.0]))
    >>> eq.method, np.round(eq.q, 6), bool(eq.error <= 1e-12), eq.constraint_forces
    ('newton', array([0., 0.]), True, ())
    """

    q: np.ndarray
    residual: float
    relative_residual: float
    iterations: int
    history: tuple[float, ...]
    elapsed: float
    method: str = "newton"
    notes: tuple[str, ...] = ()
    constraint_forces: tuple = ()
    contacts: tuple = ()
    redundant: int = 0
    constraint_gap: float = 0.0
    closure: Result | None = None

    @property
    def assembly(self) -> Result | None:
        """The 0.2 name of :attr:`closure` (kept for 0.3, removed in 0.4)."""
        return self.closure

    @property
    def error(self) -> float:
        """The relative residual ||r|| / (||tau|| + ||Q_e|| + ||K||)."""
        return self.relative_residual

    def __repr__(self) -> str:
        q = np.array2string(self.q, precision=6, threshold=12)
        return (
            f"EquilibriumResult(q={q}, residual={self.residual:.2e}, error={self.error:.1e}, "
            f"iterations={self.iterations}, method={self.method!r}, elapsed={self.elapsed * 1e3:.2f} ms)"
        )
