"""Units of coordinates, matrix entries and sweep parameters in the reports (docs/conventions.md, "Units").

A coordinate is an angle [rad] or a length [m] as its joint says; a matrix
entry has the unit of its row's force (N m for an angle, N for a length) over
its column's coordinate, rate or acceleration.  The text report prints one
unit per matrix when all coordinates agree and the four combinations otherwise.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..model.robot import Robot

__all__ = ["coordinate_units", "matrix_unit", "UNKNOWN_UNIT", "MATRIX_ORDERS"]

#: The unit printed for a coordinate of a joint kind pinlin does not know (composite, mimic joints).
UNKNOWN_UNIT = "?"

#: Tangent-space units of each Pinocchio joint kind whose coordinates are not all of one unit.
_MIXED_JOINTS = {
    "JointModelFreeFlyer": ("m", "m", "m", "rad", "rad", "rad"),
    "JointModelPlanar": ("m", "m", "rad"),
}
#: Joint kinds (prefixes of ``JointModel...`` names) whose coordinates are lengths [m] or angles [rad].
_LENGTH_JOINTS = ("JointModelP", "JointModelTranslation")
_ANGLE_JOINTS = ("JointModelR", "JointModelH", "JointModelSpherical", "JointModelUniversal", "JointModelEllipsoid")

#: The time derivative each matrix multiplies: M x'' (2), D, G, C x' (1), S, N, K x (0).
MATRIX_ORDERS = {"M": 2, "D": 1, "G": 1, "C": 1, "S": 0, "N": 0, "K": 0}

#: Entry units by (row unit, column unit) for each order: the row's force (N m or N) over the
#: column's coordinate (0), rate (1) or acceleration (2).
_ENTRY_UNITS = {
    0: {("rad", "rad"): "N m/rad", ("rad", "m"): "N", ("m", "rad"): "N/rad", ("m", "m"): "N/m"},
    1: {("rad", "rad"): "N m s/rad", ("rad", "m"): "N s", ("m", "rad"): "N s/rad", ("m", "m"): "N s/m"},
    2: {("rad", "rad"): "kg m^2", ("rad", "m"): "kg m", ("m", "rad"): "kg m", ("m", "m"): "kg"},
}


def _joint_units(kind: str, nv: int) -> tuple[str, ...]:
    if kind in _MIXED_JOINTS:
        return _MIXED_JOINTS[kind]
    if kind.startswith(_LENGTH_JOINTS):
        return ("m",) * nv
    if kind.startswith(_ANGLE_JOINTS):
        return ("rad",) * nv
    return (UNKNOWN_UNIT,) * nv


def coordinate_units(robot: Robot, dofs: Sequence[int] | None = None) -> tuple[str, ...]:
    """The unit ("rad", "m" or :data:`UNKNOWN_UNIT`) of each velocity coordinate of ``robot``.

    Parameters
    ----------
    robot : Robot
    dofs : sequence of int, optional
        Velocity indices to keep (a scene's ``free_dofs``); default all nv.

    Examples
    --------
    >>> from pinlin.report.units import coordinate_units
    >>> coordinate_units(pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf")))
    ('rad', 'rad')
    """
    units: list[str] = []
    for name in robot.joint_names:
        joint = robot.joint(name)
        units.extend(_joint_units(joint.kind, joint.nv))
    return tuple(units) if dofs is None else tuple(units[i] for i in dofs)


def matrix_unit(name: str, units: Sequence[str]) -> str:
    """The unit of the entries of matrix ``name`` (M, D, G, C, S, N or K) for coordinates of ``units``.

    One unit when every coordinate has the same; otherwise each combination that
    occurs, labelled by the (row, column) coordinate units, so that every entry's
    unit can be read off.

    Examples
    --------
    >>> from pinlin.report.units import matrix_unit
    >>> matrix_unit("S", ["rad"]), matrix_unit("D", ["m"])
    ('N m/rad', 'N s/m')
    >>> matrix_unit("M", ["rad", "m"])
    'kg m^2 (rad, rad), kg m (rad, m), kg m (m, rad), kg (m, m) for (row, column) units'
    """
    order = MATRIX_ORDERS[name]
    kinds = sorted(set(units))
    if UNKNOWN_UNIT in kinds:
        what = ("coordinate", "rate", "acceleration")[order]
        return f"row's force / column's {what}"
    if len(kinds) == 1:
        return _ENTRY_UNITS[order][(kinds[0], kinds[0])]
    pairs = [(r, c) for r in ("rad", "m") for c in ("rad", "m")]
    return ", ".join(f"{_ENTRY_UNITS[order][p]} ({p[0]}, {p[1]})" for p in pairs) + " for (row, column) units"
