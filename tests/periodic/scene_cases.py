"""URDF scenes of the periodic-motion tests: a point-mass pendulum on a pivot that slides along x and z.

The pivot carriage hangs on two prismatic joints ``pivot_x`` and ``pivot_z`` (world x, z); the pendulum
joint ``swing`` turns about y and carries a bob of mass ``mass`` at distance ``length`` along -z (inertia
``inertia`` about its centre, all axes).  The bob sits at (-l sin theta, 0, -l cos theta) from the pivot,
so about the hanging position theta = 0 (gravity -z)

    J theta'' + m l (g + z_p'') sin theta = m l x_p'' cos theta,     J = m l^2 + I.
"""

from __future__ import annotations

import pinlin


def pivot_pendulum_urdf(length=0.5, mass=1.3, inertia=0.0, links=1, limit=None) -> str:
    """URDF text; ``links`` > 1 appends more point-mass links ``swing2``.. below the bob; ``limit``:
    (lower, upper) of ``swing`` [rad] (default: practically none)."""
    lo, hi = limit if limit is not None else (-1e10, 1e10)

    def inertial(m, z):
        I = inertia
        return (f'<inertial><origin xyz="0 0 {z}"/><mass value="{m}"/>'
                f'<inertia ixx="{I}" iyy="{I}" izz="{I}" ixy="0" ixz="0" iyz="0"/></inertial>')

    parts = ['<robot name="pivot_pendulum"><link name="world"/>',
             f'<link name="slider">{inertial(0.7, 0)}</link>',
             f'<link name="carriage">{inertial(0.9, 0)}</link>',
             '<joint name="pivot_x" type="prismatic"><parent link="world"/><child link="slider"/>'
             '<axis xyz="1 0 0"/><limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/></joint>',
             '<joint name="pivot_z" type="prismatic"><parent link="slider"/><child link="carriage"/>'
             '<axis xyz="0 0 1"/><limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/></joint>']
    parent = "carriage"
    for i in range(1, links + 1):
        name = "swing" if i == 1 else f"swing{i}"
        z = 0.0 if i == 1 else -length
        parts.append(f'<link name="bob{i}">{inertial(mass, -length)}</link>')
        parts.append(f'<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="bob{i}"/>'
                     f'<origin xyz="0 0 {z}"/><axis xyz="0 1 0"/>'
                     f'<limit lower="{lo}" upper="{hi}" effort="1e10" velocity="1e10"/></joint>')
        parent = f"bob{i}"
    parts.append("</robot>")
    return "".join(parts)


def pivot_scene(prescribed, *, length=0.5, mass=1.3, inertia=0.0, links=1, limit=None, g=9.81, elements=()):
    """The pivot pendulum with both pivot joints prescribed (a joint not named is held: velocity 0)."""
    robot = pinlin.load_urdf_string(pivot_pendulum_urdf(length, mass, inertia, links, limit))
    pres = {"pivot_x": 0.0, "pivot_z": 0.0, **prescribed}
    return pinlin.Scene(robot, elements, gravity=(0.0, 0.0, -g), prescribed=pres)
