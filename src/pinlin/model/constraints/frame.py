"""Frame constraints: a frame's whole placement held at another frame's or at a world placement."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pinocchio as pin

from ...errors import ParameterError
from .base import Constraint
from .forces import ConstraintForce

__all__ = ["FrameConstraint", "ROTATION_TOL"]

#: Largest deviation of R^T R from I (and of det R from 1) accepted in a target placement:
#: a rotation typed or computed in double precision is orthonormal to ~1e-15.
ROTATION_TOL = 1e-9


def _placement(value, label: str) -> np.ndarray:
    """A (4, 4) homogeneous matrix from a ``pin.SE3`` or a 4x4 array, checked, read-only."""
    if isinstance(value, pin.SE3):
        value = value.homogeneous
    try:
        H = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(label, f"expected a frame name, a pin.SE3 or a 4x4 placement, got {value!r}") from None
    if H.shape != (4, 4) or not np.all(np.isfinite(H)):
        raise ParameterError(label, f"expected a frame name or a finite 4x4 placement, got shape {H.shape}")
    R = H[:3, :3]
    if np.any(H[3] != (0.0, 0.0, 0.0, 1.0)) or (
        np.abs(R.T @ R - np.eye(3)).max() > ROTATION_TOL or abs(np.linalg.det(R) - 1) > ROTATION_TOL
    ):
        raise ParameterError(label, "not a placement: the last row must be (0, 0, 0, 1) and the 3x3 block a rotation")
    H.flags.writeable = False
    return H

@dataclass(frozen=True, eq=False)
class FrameConstraint(Constraint):
    """Keep the whole placement of ``frame`` equal to ``target`` (theory: constraints).

    .. math::
        \\Phi = \\begin{bmatrix} p_a - p_b \\\\ \\log_3(R_a R_b^T) \\end{bmatrix},\\qquad
        J_c = J_a - J_b \\ \\text{(LOCAL\\_WORLD\\_ALIGNED, 6 rows)}

    J_c is the relative velocity (origin velocity and angular velocity, world
    axes); it equals dPhi/dq on the manifold, so the multipliers lambda (6,) are
    the world-axes force and torque on ``frame`` at its origin.  Away from the
    manifold, loops are closed with the exact derivative
    dPhi_rot = Jlog3(E) (E^T J_wa - J_wb) dq, E = R_a R_b^T.

    Parameters
    ----------
    frame : str
        The constrained frame.
    target : str, pin.SE3 or (4, 4) array
        Another frame's name, or a fixed world placement.
    name : str, optional
        Label in reports.

    Raises
    ------
    ParameterError
        A target that is neither a frame name nor a placement (4x4 homogeneous
        matrix with a rotation block).

    Examples
    --------
    >>> weld = pinlin.FrameConstraint("tip", np.eye(4), name="weld")
    >>> weld.kind, weld.size, weld.label
    ('frame', 6, 'weld')
    """

    frame: str
    target: str | np.ndarray
    name: str | None = None

    kind: ClassVar[str] = "frame"
    size: ClassVar[int] = 6

    def __post_init__(self):
        if not isinstance(self.frame, str):
            raise ParameterError(f"FrameConstraint({self.frame!r}).frame", f"expected a frame name, got {self.frame!r}")
        if not isinstance(self.target, str):
            object.__setattr__(self, "target", _placement(self.target, f"FrameConstraint({self.frame!r}).target"))

    def _error_rotation(self, ev) -> tuple[np.ndarray, np.ndarray]:
        _, R_b, _ = self._target_placement(ev)
        R_a = ev.frame_rotation(ev.robot.frame_id(self.frame))
        E = R_a @ R_b.T
        return E, np.asarray(pin.log3(E), dtype=float)

    def residual(self, ev) -> np.ndarray:
        p_b, _, _ = self._target_placement(ev)
        _, theta = self._error_rotation(ev)
        return np.concatenate([ev.frame_position(ev.robot.frame_id(self.frame)) - p_b, theta])

    def jacobian(self, ev) -> np.ndarray:
        return self._relative_jacobian(ev)

    def closure_jacobian(self, ev) -> np.ndarray:
        J_a = ev.world_aligned_jacobian(ev.robot.frame_id(self.frame))
        J = self._relative_jacobian(ev).copy()
        E, _ = self._error_rotation(ev)
        Jlog = np.asarray(pin.Jlog3(E), dtype=float)
        J_wb = J_a[3:] - J[3:]  # the target's angular rows (zero for a world target)
        J[3:] = Jlog @ (E.T @ J_a[3:] - J_wb)
        return J

    def wrench_terms(self, ev, lam: np.ndarray) -> list[tuple]:
        lam = np.asarray(lam, dtype=float)
        return self._pair(ev, lam[:3], lam[3:])

    def force(self, lam: np.ndarray, copy: bool = True) -> ConstraintForce:
        lam = np.array(lam, dtype=float) if copy else lam
        return ConstraintForce(self.label, self.frame, self.target, lam[:3], lam[3:])
