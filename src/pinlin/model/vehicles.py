"""URDF generators for machines that roll and spin freely: the reference cases of steady motions.

Kinematics and inertia only (no meshes), like :mod:`.generators`.  Gravity along -z.

- :func:`whipple_bicycle_urdf` -- the benchmark bicycle of Meijaard, Papadopoulos, Ruina and
  Schwab (Proc. R. Soc. A 463, 2007), parameters :class:`WhippleParameters`; the bundled
  ``urdf/whipple_bicycle.urdf`` is its output with the default parameters;
- :func:`rolling_disk_urdf` -- a uniform disk (or a hoop) on massless slides and hinges;
- :func:`free_body_urdf` -- one rigid body with given principal moments (for a free flyer);
- :func:`top_urdf` -- a symmetric top on a fixed pivot with a free spin joint.

"Massless" intermediate links (slides, hinges, gimbals) have no ``<inertial>`` element, as
in :mod:`.generators`: Pinocchio gives them mass 0 and a zero tensor, and pinlin's inertia
check accepts them.  The mass matrix stays positive definite because the joints' motions
move the massive body at the chain's end independently (the disk's six, the top's three).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields
from numbers import Real

from ..errors import ParameterError
from .inertia import inertia_fault

__all__ = ["WhippleParameters", "whipple_bicycle_urdf", "rolling_disk_urdf", "free_body_urdf", "top_urdf"]

_LIMIT = '    <limit lower="-1e10" upper="1e10" effort="1e10" velocity="1e10"/>\n'


def _num(x: float) -> str:
    return repr(float(x))


def _finite(name: str, value) -> float:
    if not isinstance(value, Real) or isinstance(value, bool):
        raise ParameterError(name, f"expected a real number, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(name, f"must be finite, got {value!r}")
    return x


def _positive(name: str, value) -> float:
    x = _finite(name, value)
    if x <= 0:
        raise ParameterError(name, f"must be positive, got {value!r}")
    return x


def _check_moments(name: str, moments: tuple[float, float, float]) -> None:
    """Principal moments of a rigid body: each at most the sum of the other two (up to the loader's slack)."""
    fault = inertia_fault(sorted(moments))
    if fault is not None:
        raise ParameterError(name, f"principal moments {moments} {fault}")


def _link(name: str, mass: float, com=(0.0, 0.0, 0.0), ixx=0.0, iyy=0.0, izz=0.0, ixz=0.0) -> str:
    x, y, z = com
    return (
        f'  <link name="{name}">\n    <inertial>\n'
        f'      <origin xyz="{_num(x)} {_num(y)} {_num(z)}" rpy="0 0 0"/>\n'
        f'      <mass value="{_num(mass)}"/>\n'
        f'      <inertia ixx="{_num(ixx)}" ixy="0.0" ixz="{_num(ixz)}" iyy="{_num(iyy)}" iyz="0.0"'
        f' izz="{_num(izz)}"/>\n    </inertial>\n  </link>\n'
    )


def _joint(name: str, kind: str, parent: str, child: str, axis, xyz=(0.0, 0.0, 0.0)) -> str:
    return (
        f'  <joint name="{name}" type="{kind}">\n'
        f'    <parent link="{parent}"/>\n    <child link="{child}"/>\n'
        f'    <origin xyz="{" ".join(_num(t) for t in xyz)}" rpy="0 0 0"/>\n'
        f'    <axis xyz="{" ".join(_num(t) for t in axis)}"/>\n'
        + (_LIMIT if kind in ("revolute", "prismatic") else "")
        + "  </joint>\n"
    )


@dataclass(frozen=True, kw_only=True)
class WhippleParameters:
    """Parameters of the Whipple bicycle, named and valued as in the benchmark (Meijaard et al. 2007).

    Lengths [m], masses [kg], moments of inertia [kg m^2], ``lam`` [rad], ``g`` [m/s^2].
    Positions and products of inertia are in the benchmark's axes: x forward, y right,
    z down, from the rear contact point (so ``zB = -0.9`` is 0.9 m above the ground).
    Wheels: ``rR``, ``mR``, ``IRxx`` (= IRzz), ``IRyy`` (axial) and the front's ``rF``,
    ``mF``, ``IFxx``, ``IFyy``.  Rear frame with rider: ``xB``, ``zB``, ``mB``, ``IBxx``,
    ``IByy``, ``IBzz``, ``IBxz``; fork and handlebar: ``xH``, ``zH``, ``mH``, ``IHxx``,
    ``IHyy``, ``IHzz``, ``IHxz``.  Wheelbase ``w``, trail ``c``, steer axis tilt ``lam``.
    Keywords only; :func:`dataclasses.replace` gives a variant.

    Raises
    ------
    ParameterError
        A value that is not a finite number, a mass, radius, wheelbase or moment that is
        not positive, a tilt outside (-pi/2, pi/2), or body moments that are not physical.

    Examples
    --------
    >>> from pinlin.model.vehicles import WhippleParameters
    >>> p = WhippleParameters()
    >>> print(p.mR + p.mB + p.mH + p.mF, p.w, p.c)
    94.0 1.02 0.08
    >>> print(WhippleParameters(mB=60.0).mB)
    60.0
    >>> WhippleParameters(rF=0.0)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: rF: must be positive, got 0.0
    """

    w: float = 1.02
    c: float = 0.08
    lam: float = math.pi / 10
    g: float = 9.81
    rR: float = 0.3
    mR: float = 2.0
    IRxx: float = 0.0603
    IRyy: float = 0.12
    xB: float = 0.3
    zB: float = -0.9
    mB: float = 85.0
    IBxx: float = 9.2
    IByy: float = 11.0
    IBzz: float = 2.8
    IBxz: float = 2.4
    xH: float = 0.9
    zH: float = -0.7
    mH: float = 4.0
    IHxx: float = 0.05892
    IHyy: float = 0.06
    IHzz: float = 0.00708
    IHxz: float = -0.00756
    rF: float = 0.35
    mF: float = 3.0
    IFxx: float = 0.1405
    IFyy: float = 0.28

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, _finite(f.name, getattr(self, f.name)))
        for name in ("w", "rR", "rF", "mR", "mB", "mH", "mF", "IRxx", "IRyy", "IFxx", "IFyy",
                     "IBxx", "IByy", "IBzz", "IHxx", "IHyy", "IHzz"):
            _positive(name, getattr(self, name))
        if not abs(self.lam) < math.pi / 2:
            raise ParameterError("lam", f"steer axis tilt must lie in (-pi/2, pi/2), got {self.lam!r}")
        _check_moments("IRxx/IRyy", (self.IRxx, self.IRyy, self.IRxx))
        _check_moments("IFxx/IFyy", (self.IFxx, self.IFyy, self.IFxx))
        for body in ("B", "H"):
            xx, yy, zz, xz = (getattr(self, f"I{body}{k}") for k in ("xx", "yy", "zz", "xz"))
            # The xz block's principal moments with yy: a 2 x 2 eigenproblem in closed form.
            mean, half = (xx + zz) / 2, math.hypot((xx - zz) / 2, xz)
            if mean - half <= 0:
                raise ParameterError(f"I{body}xz", f"tensor of body {body} is not positive definite")
            _check_moments(f"I{body}", (mean - half, yy, mean + half))


def whipple_bicycle_urdf(params: WhippleParameters | None = None) -> str:
    """URDF text of the Whipple bicycle benchmark (Meijaard, Papadopoulos, Ruina and Schwab 2007).

    Four bodies: ``rear_frame`` (rear frame with rider; the root, to be loaded with a
    free flyer), ``rear_wheel_body``, ``fork`` (fork and handlebar) and
    ``front_wheel_body``.  Axes x forward, y left, z up (the benchmark's are x forward,
    y right, z down: positions and products of inertia are mapped by diag(1, -1, -1),
    which flips the sign of I_xz).  The rear frame's origin is the rear wheel centre,
    so the upright bicycle stands on z = 0 with the root at height ``rR``.

    Joints: ``rear_wheel`` (continuous about the rear frame's y), ``steer`` (revolute
    about the steer axis, tilted back by ``lam`` from the vertical and passing through
    the ground ``w + c`` ahead of the rear contact, so the trail is ``c``; its axis points
    *down*, so a positive angle steers to the right as in the benchmark) and
    ``front_wheel`` (continuous about the fork's y through the front wheel centre).  The
    fork frame's origin is the point of the steer axis at the front wheel centre's
    height; each wheel body's origin is its centre, with its axle along its y.  A
    positive wheel rate rolls the bicycle forward.  The benchmark's roll (to the right
    positive) is a positive rotation of the rear frame about its forward x axis.

    Parameters
    ----------
    params : WhippleParameters, optional
        Default: the benchmark's values.

    Examples
    --------
    >>> from pinlin.model.vehicles import whipple_bicycle_urdf
    >>> robot = pinlin.load_urdf_string(whipple_bicycle_urdf(), free_flyer=True)
    >>> print(robot.model.nq, robot.model.nv, round(sum(i.mass for i in robot.model.inertias), 12))
    12 9 94.0
    """
    p = WhippleParameters() if params is None else params
    if not isinstance(p, WhippleParameters):
        raise ParameterError("params", f"expected WhippleParameters, got {type(p).__name__}")
    s, k = math.sin(p.lam), math.cos(p.lam)
    steer_x = p.w + p.c - p.rF * math.tan(p.lam)  # steer axis at the front wheel centre's height
    parts = [
        f'<?xml version="1.0"?>\n<robot name="whipple_bicycle">\n'
        f"  <!-- {_describe(p)} -->\n",
        _link("rear_frame", p.mB, (p.xB, 0.0, -p.zB - p.rR), p.IBxx, p.IByy, p.IBzz, -p.IBxz),
        _link("rear_wheel_body", p.mR, ixx=p.IRxx, iyy=p.IRyy, izz=p.IRxx),
        _joint("rear_wheel", "continuous", "rear_frame", "rear_wheel_body", (0, 1, 0)),
        _link("fork", p.mH, (p.xH - steer_x, 0.0, -p.zH - p.rF), p.IHxx, p.IHyy, p.IHzz, -p.IHxz),
        _joint("steer", "revolute", "rear_frame", "fork", (s, 0, -k), (steer_x, 0.0, p.rF - p.rR)),
        _link("front_wheel_body", p.mF, ixx=p.IFxx, iyy=p.IFyy, izz=p.IFxx),
        _joint("front_wheel", "continuous", "fork", "front_wheel_body", (0, 1, 0), (p.w - steer_x, 0.0, 0.0)),
        "</robot>\n",
    ]
    return "".join(parts)


def _describe(p: WhippleParameters) -> str:
    return "Whipple bicycle, benchmark axes (x fwd, y right, z down): " + ", ".join(
        f"{name}={value!r}" for name, value in asdict(p).items()
    )


def rolling_disk_urdf(radius: float, mass: float, hoop: bool = False) -> str:
    """URDF of a thin disk (or a hoop) on massless slides and hinges, for rolling on z = 0.

    Joints in order: prismatic ``x``, ``y``, ``z`` (the centre's position), revolute
    ``heading`` (about z) and ``lean`` (about the heading frame's forward x, through
    the centre), then continuous ``spin`` about the disk's axle, its body y.  Every
    speed of the straight upright rolling motion is then a constant joint rate.  The
    body ``disk`` has its origin at the centre; the intermediate links are massless
    (mass 0, no ``<inertial>``).  Uniform disk: C = m r^2 / 2 (axial), A = m r^2 / 4
    (diametral); hoop: C = m r^2, A = m r^2 / 2.

    Parameters
    ----------
    radius : float
        r [m], positive.
    mass : float
        m [kg], positive.
    hoop : bool
        A thin ring instead of a uniform disk.

    Examples
    --------
    >>> from pinlin.model.vehicles import rolling_disk_urdf
    >>> robot = pinlin.load_urdf_string(rolling_disk_urdf(0.5, 2.0))
    >>> print(robot.model.nq, robot.model.nv, np.round(np.diag(robot.model.inertias[-1].inertia), 6))
    7 6 [0.125 0.25  0.125]
    """
    r, m = _positive("radius", radius), _positive("mass", mass)
    axial = m * r * r if hoop else m * r * r / 2
    parts = ['<?xml version="1.0"?>\n<robot name="rolling_hoop">\n' if hoop
             else '<?xml version="1.0"?>\n<robot name="rolling_disk">\n', '  <link name="ground"/>\n']
    chain = [("x", "prismatic", (1, 0, 0)), ("y", "prismatic", (0, 1, 0)), ("z", "prismatic", (0, 0, 1)),
             ("heading", "revolute", (0, 0, 1)), ("lean", "revolute", (1, 0, 0))]
    parent = "ground"
    for name, kind, axis in chain:
        parts += [f'  <link name="{name}_link"/>\n', _joint(name, kind, parent, f"{name}_link", axis)]
        parent = f"{name}_link"
    parts += [_link("disk", m, ixx=axial / 2, iyy=axial, izz=axial / 2),
              _joint("spin", "continuous", parent, "disk", (0, 1, 0)), "</robot>\n"]
    return "".join(parts)


def free_body_urdf(I1: float, I2: float, I3: float, mass: float) -> str:
    """URDF of one rigid body ``body`` with principal moments (I1, I2, I3) [kg m^2] along its x, y, z.

    Load it with ``free_flyer=True``; the body's origin is its centre of mass.

    Raises
    ------
    ParameterError
        A mass or moment that is not positive, or moments that break the triangle
        inequality (no rigid body has them).

    Examples
    --------
    >>> from pinlin.model.vehicles import free_body_urdf
    >>> robot = pinlin.load_urdf_string(free_body_urdf(1.0, 2.0, 3.0, 5.0), free_flyer=True)
    >>> print(robot.model.nv, robot.model.inertias[1].mass)
    6 5.0
    """
    moments = tuple(_positive(n, v) for n, v in (("I1", I1), ("I2", I2), ("I3", I3)))
    _check_moments("I1/I2/I3", moments)
    m = _positive("mass", mass)
    return ('<?xml version="1.0"?>\n<robot name="free_body">\n'
            + _link("body", m, ixx=moments[0], iyy=moments[1], izz=moments[2]) + "</robot>\n")


def top_urdf(mass: float, l: float, A: float, C: float) -> str:  # noqa: E741 (the top's l)
    """URDF of a symmetric top on a fixed pivot at the origin, with a free spin joint.

    The pivot is a gimbal of two massless hinges, ``tilt_x`` (about x) then ``tilt_y``
    (about the tilted y); then ``spin`` (continuous about the top's symmetry axis, the
    body z).  The gimbal is regular at the upright (sleeping) top, where the tilt rates
    are the transverse angular velocities.  A spherical joint followed by a spin joint
    would repeat the rotation about the axis and make the mass matrix singular.  The
    body ``top`` has its centre of mass at height ``l`` above the pivot on its axis.

    Parameters
    ----------
    mass : float
        m [kg], positive.
    l : float
        Pivot-to-centre distance [m], positive.
    A : float
        Transverse moment of inertia about the pivot [kg m^2]; A - m l^2 is the one about
        the centre of mass and must be positive.
    C : float
        Axial moment [kg m^2], positive, at most 2 (A - m l^2).

    Examples
    --------
    >>> from pinlin.model.vehicles import top_urdf
    >>> robot = pinlin.load_urdf_string(top_urdf(1.0, 0.1, 0.02, 0.015))
    >>> print(robot.model.nq, robot.model.nv, robot.joint_names)
    4 3 ('tilt_x', 'tilt_y', 'spin')
    """
    m, length = _positive("mass", mass), _positive("l", l)
    transverse = _positive("A", A) - m * length**2
    if transverse <= 0:
        raise ParameterError("A", f"the moment about the pivot must exceed m l^2 = {m * length**2!r}, "
                                  f"got {A!r}")
    axial = _positive("C", C)
    _check_moments("A/C", (transverse, transverse, axial))
    return ('<?xml version="1.0"?>\n<robot name="top">\n  <link name="ground"/>\n'
            '  <link name="gimbal_x"/>\n' + _joint("tilt_x", "revolute", "ground", "gimbal_x", (1, 0, 0))
            + '  <link name="gimbal_y"/>\n' + _joint("tilt_y", "revolute", "gimbal_x", "gimbal_y", (0, 1, 0))
            + _link("top", m, (0.0, 0.0, length), transverse, transverse, axial)
            + _joint("spin", "continuous", "gimbal_y", "top", (0, 0, 1)) + "</robot>\n")
