"""URDF generators for the reference cases of theory: worked examples.

The bundled files in ``pinlin/data/urdf`` are the output of these functions with
their default arguments (a test keeps them in sync), so every reference model
can also be rebuilt with other parameters.

Conventions: gravity along -z; pendulum bars hang along -z from their joint and
swing about +y, so a positive joint angle moves the tip towards -x.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import ParameterError

__all__ = [
    "pendulum_chain_urdf",
    "double_pendulum_urdf",
    "turntable_urdf",
    "rotating_ring_urdf",
    "branched_chain_urdf",
]


def _f(x: float) -> str:
    return repr(float(x))


def _per_link(name: str, value, n: int, total: bool) -> np.ndarray:
    """A scalar is a total split over n links (or a per-link value); a sequence is per link."""
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        arr = np.full(n, float(arr) / n if total else float(arr))
    if arr.shape != (n,):
        raise ParameterError(name, f"expected a number or {n} values (one per link), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ParameterError(name, f"values must be finite, got {arr}")
    return arr


def _inertial(mass: float, com_z: float, ixx: float, iyy: float, izz: float) -> str:
    return (
        f'    <inertial>\n      <origin xyz="0 0 {_f(com_z)}" rpy="0 0 0"/>\n'
        f'      <mass value="{_f(mass)}"/>\n'
        f'      <inertia ixx="{_f(ixx)}" ixy="0.0" ixz="0.0" iyy="{_f(iyy)}" iyz="0.0" izz="{_f(izz)}"/>\n'
        f"    </inertial>\n"
    )


def pendulum_chain_urdf(
    n: int,
    length: float | Sequence[float] = 1.0,
    mass: float | Sequence[float] = 1.0,
    *,
    radius: float | Sequence[float] = 0.0,
    damping: float | Sequence[float] = 0.0,
    joint_type: str = "revolute",
    name: str = "pendulum_chain",
    tip_frame: bool = True,
) -> str:
    """URDF text of an n-link pendulum chain of uniform bars (theory: pendulum chains).

    The chain hangs from a fixed ``base`` link; ``joint{i}`` (i = 1..n) joins
    ``link{i-1}`` to ``link{i}`` about +y, at the lower end of the previous bar.
    Each bar is a uniform solid cylinder along -z from its joint: centre of mass
    at -l/2, Ixx = Iyy = m (l^2/12 + r^2/4), Izz = m r^2/2 (r = 0 is the slender
    bar of the paper).  With ``tip_frame`` a massless fixed link ``tip`` sits at
    the free end.

    Parameters
    ----------
    n : int
        Number of links, at least 1.
    length, mass : float or sequence of n floats
        A number is the chain's *total* length [m] / mass [kg], split equally;
        a sequence gives each link's own value.
    radius : float or sequence of n floats
        Bar radius [m] (per link if a sequence), default 0 (slender bars).
    damping : float or sequence of n floats
        URDF ``<dynamics damping>`` per joint [N m s/rad] (the same number on
        every joint if scalar); pinlin adds it only with ``Scene(urdf_damping=True)``.
    joint_type : {"revolute", "continuous"}
        ``continuous`` joints have nq = 2, nv = 1 in Pinocchio.
    name : str
        The robot name.
    tip_frame : bool
        Add the ``tip`` frame at the end of the last bar.

    Examples
    --------
    >>> robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(3, length=0.5, mass=0.2))
    >>> robot.nv
    3
    """
    if not isinstance(n, (int, np.integer)) or isinstance(n, bool) or n < 1:
        raise ParameterError("n", f"number of links must be an integer >= 1, got {n!r}")
    if joint_type not in ("revolute", "continuous"):
        raise ParameterError("joint_type", f"expected 'revolute' or 'continuous', got {joint_type!r}")
    lengths = _per_link("length", length, n, total=True)
    masses = _per_link("mass", mass, n, total=True)
    radii = _per_link("radius", radius, n, total=False)
    dampings = _per_link("damping", damping, n, total=False)
    for label, arr in (("length", lengths), ("mass", masses)):
        if np.any(arr <= 0):
            raise ParameterError(label, f"must be positive, got {arr}")
    if np.any(radii < 0) or np.any(dampings < 0):
        raise ParameterError("radius/damping", "must be non-negative")

    parts = [f'<?xml version="1.0"?>\n<robot name="{name}">\n  <link name="base"/>\n']
    parent, drop = "base", 0.0
    limit = '    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>\n'
    for i, (l, m, r, c) in enumerate(zip(lengths, masses, radii, dampings), start=1):
        ixx = m * (l * l / 12.0 + r * r / 4.0)
        parts.append(f'  <link name="link{i}">\n{_inertial(m, -l / 2.0, ixx, ixx, m * r * r / 2.0)}  </link>\n')
        parts.append(
            f'  <joint name="joint{i}" type="{joint_type}">\n'
            f'    <parent link="{parent}"/>\n    <child link="link{i}"/>\n'
            f'    <origin xyz="0 0 {_f(drop)}" rpy="0 0 0"/>\n    <axis xyz="0 1 0"/>\n'
            + (limit if joint_type == "revolute" else "")
            + f'    <dynamics damping="{_f(c)}" friction="0.0"/>\n  </joint>\n'
        )
        parent, drop = f"link{i}", -l
    if tip_frame:
        parts.append(
            '  <link name="tip"/>\n  <joint name="tip_joint" type="fixed">\n'
            f'    <parent link="{parent}"/>\n    <child link="tip"/>\n'
            f'    <origin xyz="0 0 {_f(drop)}" rpy="0 0 0"/>\n  </joint>\n'
        )
    parts.append("</robot>\n")
    return "".join(parts)


def double_pendulum_urdf(
    m1: float = 1.3, l1: float = 0.7, m2: float = 0.9, l2: float = 0.5, *, damping: float = 0.0
) -> str:
    """The paper's double pendulum of uniform slender bars (theory: double pendulum, Example 6.2).

    Bars OA (m1 [kg], l1 [m]) and AB (m2, l2); joints ``joint1`` at O and
    ``joint2`` at A (relative angles theta1 = phi1, theta2 = phi2 - phi1); frame
    ``tip`` at B.  The follower load of the paper is
    ``FollowerWrench("tip", force=(0, 0, P))`` (from B towards A).

    Examples
    --------
    >>> text = pinlin.double_pendulum_urdf(m1=1.3, l1=0.7, m2=0.9, l2=0.5)
    >>> pinlin.load_urdf_string(text).joint_names
    ('joint1', 'joint2')
    """
    return pendulum_chain_urdf(
        2, [l1, l2], [m1, m2], damping=damping, name="double_pendulum"
    )


def turntable_urdf(a: float = 0.5, mass: float = 1.0, table_inertia: float = 1.0) -> str:
    """Particle on a turntable (theory: turntable, Example 6.1).

    ``table`` (continuous about z; give it a prescribed velocity) carries
    ``arm`` (revolute about z at distance ``a`` [m] from O; angle theta), which
    carries ``slider`` (prismatic along the arm's x; r = |AP|) holding a point
    mass ``mass`` [kg].  The spring of the paper is
    ``JointSpring("slider", k, rest=l0)``.

    Examples
    --------
    >>> robot = pinlin.load_urdf_string(pinlin.turntable_urdf(a=0.5))
    >>> robot.nv
    3
    """
    for label, val in (("a", a), ("mass", mass), ("table_inertia", table_inertia)):
        if not np.isfinite(val) or val <= 0:
            raise ParameterError(label, f"must be positive and finite, got {val!r}")
    i = table_inertia
    return f"""<?xml version="1.0"?>
<robot name="turntable">
  <link name="ground"/>
  <link name="table">
{_inertial(1.0, 0.0, i, i, i)}  </link>
  <joint name="table" type="continuous">
    <parent link="ground"/>
    <child link="table"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="arm"/>
  <joint name="arm" type="revolute">
    <parent link="table"/>
    <child link="arm"/>
    <origin xyz="{_f(a)} 0 0" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>
  </joint>
  <link name="particle">
{_inertial(mass, 0.0, 0.0, 0.0, 0.0)}  </link>
  <joint name="slider" type="prismatic">
    <parent link="arm"/>
    <child link="particle"/>
    <axis xyz="1 0 0"/>
    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>
  </joint>
</robot>
"""


def rotating_ring_urdf(mass: float = 1.0, ring_inertia: float = 1.0) -> str:
    """Particle in a rotating ring (theory: rotating ring, Example 11.1).

    ``ring`` (continuous about z; give it a prescribed velocity) carries the
    prismatic joints ``x`` and ``y`` (the particle's Cartesian coordinates in
    the ring frame) and a point mass ``mass`` [kg].  The springs and dampers of
    the paper are ``JointSpring("x", k)``, ``JointSpring("y", k)``,
    ``JointDamper("x", c)``, ``JointDamper("y", c)``.

    Examples
    --------
    >>> robot = pinlin.load_urdf_string(pinlin.rotating_ring_urdf(mass=1.0, ring_inertia=2.0))
    >>> robot.nv
    3
    """
    for label, val in (("mass", mass), ("ring_inertia", ring_inertia)):
        if not np.isfinite(val) or val <= 0:
            raise ParameterError(label, f"must be positive and finite, got {val!r}")
    i = ring_inertia
    lim = '    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>\n'
    return f"""<?xml version="1.0"?>
<robot name="rotating_ring">
  <link name="ground"/>
  <link name="ring">
{_inertial(1.0, 0.0, i, i, i)}  </link>
  <joint name="ring" type="continuous">
    <parent link="ground"/>
    <child link="ring"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="slide_x"/>
  <joint name="x" type="prismatic">
    <parent link="ring"/>
    <child link="slide_x"/>
    <axis xyz="1 0 0"/>
{lim}  </joint>
  <link name="particle">
{_inertial(mass, 0.0, 0.0, 0.0, 0.0)}  </link>
  <joint name="y" type="prismatic">
    <parent link="slide_x"/>
    <child link="particle"/>
    <axis xyz="0 1 0"/>
{lim}  </joint>
</robot>
"""


def _bar_link(name: str, mass: float, length: float) -> str:
    i = mass * length**2 / 12
    return (
        f'<link name="{name}"><inertial><origin xyz="0 0 {-length / 2}"/><mass value="{mass}"/>'
        f'<inertia ixx="{i}" iyy="{i}" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>'
    )


def _hinge(name: str, parent: str, child: str, z: float, axis: str) -> str:
    return (
        f'<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="0 0 {z}"/><axis xyz="{axis}"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>'
    )


def branched_chain_urdf(branches: int = 8) -> str:
    """URDF of a trunk (revolute about y) carrying ``branches`` identical two-link branches (about x, then y).

    Identical branches give clusters of equal eigenvalues (one per branch mode): the reference case of
    repeated eigenvalues whose Jordan structure is semisimple (benchmarks and tests of the multiplicities).
    """
    parts = ['<robot name="branched">', '<link name="base"/>', _bar_link("trunk", 2.0, 0.5),
             _hinge("trunk", "base", "trunk", 0.0, "0 1 0")]
    for b in range(branches):
        parts += [_bar_link(f"b{b}_1", 0.3, 0.2), _bar_link(f"b{b}_2", 0.2, 0.15),
                  _hinge(f"b{b}_j1", "trunk", f"b{b}_1", -0.5, "1 0 0"),
                  _hinge(f"b{b}_j2", f"b{b}_1", f"b{b}_2", -0.2, "0 1 0")]
    return "\n".join(parts + ["</robot>"])
