"""What an equilibrium reports about each constraint: its force, and for a contact whether the ground can give it."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ConstraintForce", "ContactStatus"]


@dataclass(frozen=True)
class ConstraintForce:
    """The force (and torque) a constraint applies on its frame at an equilibrium.

    Attributes
    ----------
    constraint : str
        The constraint's label.
    frame : str
        The frame it acts on (at its origin).
    target : str or ndarray
        A frame name (which receives the opposite wrench) or a world point / placement.
    force : (3,) ndarray
        [N], world axes.
    torque : (3,) ndarray or None
        [N m], world axes; None for a point constraint.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/four_bar.urdf"))
    >>> loop = pinlin.PointConstraint("rocker_tip", (0.7, 0.0, 0.0), name="loop")
    >>> scene = pinlin.Scene(robot, [pinlin.JointSpring("crank_joint", 50.0, rest=0.2)], constraints=[loop])
    >>> (force,) = pinlin.find_equilibrium(scene, np.zeros(3)).constraint_forces
    >>> force.constraint, force.frame, np.round(force.force, 3), force.torque
    ('loop', 'rocker_tip', array([ 5.065,  0.   , 25.363]), None)
    """

    constraint: str
    frame: str
    target: str | np.ndarray
    force: np.ndarray
    torque: np.ndarray | None = None


@dataclass(frozen=True)
class ContactStatus:
    """Whether a contact's force is one the ground can give (theory: constraints).

    Attributes
    ----------
    constraint : str
        The contact's label.
    normal_force : float
        n . lambda [N]: positive when the ground pushes.
    tangential_force : float
        |lambda - (n . lambda) n| [N].
    friction_needed : float
        tangential / normal force (inf when the normal force is not positive).
    friction : float or None
        The friction coefficient mu the contact has (None: not checked).
    pulls : bool
        The ground must pull (normal force < 0).
    slips : bool
        More friction is needed than mu.

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> (foot,) = pinlin.ground_contacts(robot, np.zeros(2), ["tip"], friction=0.5)
    >>> status = foot.contact_status(np.array([0.1, 0.0, 1.0]))
    >>> status.normal_force, status.pulls, status.slips, status.feasible
    (1.0, False, False, True)
    """

    constraint: str
    normal_force: float
    tangential_force: float
    friction_needed: float
    friction: float | None
    pulls: bool
    slips: bool

    @property
    def feasible(self) -> bool:
        """True when the ground pushes and friction suffices."""
        return not (self.pulls or self.slips)

    def describe(self) -> str:
        """One sentence for notes and verdicts: what the contact needs.

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> (foot,) = pinlin.ground_contacts(robot, np.zeros(2), ["tip"], friction=0.5)
        >>> foot.contact_status(np.array([2.0, 0.0, 1.0])).describe()
        "contact 'tip': needs friction coefficient 2 > mu = 0.5 (tangential 2 N, normal 1 N)"
        """
        if self.pulls:
            return f"contact {self.constraint!r}: the ground must pull (normal force {self.normal_force:.4g} N)"
        if self.slips:
            return (
                f"contact {self.constraint!r}: needs friction coefficient {self.friction_needed:.3g} > "
                f"mu = {self.friction:g} (tangential {self.tangential_force:.4g} N, normal {self.normal_force:.4g} N)"
            )
        return f"contact {self.constraint!r}: normal force {self.normal_force:.4g} N, friction needed {self.friction_needed:.3g}"
