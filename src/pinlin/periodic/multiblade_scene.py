"""Multi-blade coordinates of a scene's rotor: :func:`multiblade_transform` (theory: Floquet).

A scene with a rotor joint turning at a prescribed constant speed Omega and N >= 3 blades, each on a
1-DOF joint (a lag or flap hinge) of its own, has periodic coefficients in blade coordinates.  Along its
orbit (:func:`~pinlin.periodic.periodic_orbit`; usually constant: the blades at rest relative to the rotor)
the variational coefficients M(t), C(t), K(t) come from Pinocchio
(:func:`~pinlin.periodic.coefficients.variational_coefficients`), and the Coleman transform of the blade
coordinates (:func:`~pinlin.periodic.multiblade.multiblade_transform_matrices`) turns them into one
time-invariant system when the blades are identical and equally spaced, whatever the support.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..errors import ParameterError
from ..errors.deprecated import renamed_keywords
from ..model.scene import Scene
from .coefficients import variational_coefficients
from .multiblade import VARIATION_TOL, multiblade_transform_matrices
from .orbit_result import PeriodicOrbit

__all__ = ["multiblade_transform"]


@renamed_keywords(tolerance="variation_tol")
def multiblade_transform(scene: Scene, orbit: PeriodicOrbit, blades: Sequence[str], *, rotor: str,
                         psi0: float = 0.0, variation_tol: float = VARIATION_TOL):
    """The scene's linearized equations along ``orbit`` in multi-blade (Coleman) coordinates.

    .. math::  \\beta_k = \\beta_0 + \\sum_j (\\beta_{jc} \\cos j\\psi_k + \\beta_{js} \\sin j\\psi_k)
               + \\beta_{N/2} (-1)^k, \\qquad \\psi_k = \\Omega t + \\psi_0 + 2 \\pi (k - 1) / N

    Parameters
    ----------
    scene : Scene
        With ``rotor`` prescribed at a constant speed Omega [rad/s].
    orbit : PeriodicOrbit
        From :func:`pinlin.periodic_orbit` for this scene.
    blades : sequence of str
        The blade joints (1-DOF each, free), blade k at azimuth psi_k in this order.
    rotor : str
        The prescribed joint that turns the blades.
    psi0 : float
        Azimuth of the first blade at t = 0 [rad].
    variation_tol : float
        Largest relative change of the transformed matrices over a revolution (``tolerance`` is its
        deprecated spelling).

    Returns
    -------
    LinearizedSystem
        Time-invariant, coordinates named as the scene's with the blades' replaced by ``blade_collective``,
        ``blade_cos1``, ``blade_sin1``, ... (``blade_differential`` for even N); every analysis applies.

    Raises
    ------
    ParameterError
        ``rotor`` is not prescribed at a constant speed, a blade is not a free 1-DOF joint of the scene,
        or ``orbit`` belongs to another scene.
    MultibladeNotExactError
        The transform leaves time-dependent coefficients (N = 2, dissimilar or unequally spaced blades):
        analyse the scene with :func:`pinlin.floquet_analysis` instead.

    Examples
    --------
    Three lag-hinged blades on a hub that moves on springs in x and y, turning at 3 rad/s:

    >>> I = '<inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/>'
    >>> def body(name, m, x=0.0):
    ...     return f'<link name="{name}"><inertial><origin xyz="{x} 0 0"/><mass value="{m}"/>{I}</inertial></link>'
    >>> def joint(name, kind, parent, child, axis, xyz="0 0 0", yaw=0.0):
    ...     return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
    ...             f'<origin xyz="{xyz}" rpy="0 0 {yaw}"/><axis xyz="{axis}"/>'
    ...             f'<limit lower="-9" upper="9" effort="9" velocity="9"/></joint>')
    >>> parts = ['<robot name="rotor"><link name="world"/>', body("sx", 5.0), body("sy", 0.1), body("hub", 0.1),
    ...          joint("x", "prismatic", "world", "sx", "1 0 0"), joint("y", "prismatic", "sx", "sy", "0 1 0"),
    ...          joint("spin", "continuous", "sy", "hub", "0 0 1")]
    >>> for k, a in enumerate(2 * np.pi * np.arange(3) / 3):
    ...     parts += [body(f"b{k}", 1.0, 0.5),
    ...               joint(f"lag{k}", "revolute", "hub", f"b{k}", "0 0 1", f"{0.2 * np.cos(a)} {0.2 * np.sin(a)} 0", a)]
    >>> robot = pinlin.load_urdf_string("".join(parts) + "</robot>")
    >>> springs = [pinlin.JointSpring(j, 400.0 if j in "xy" else 20.0) for j in ("x", "y", "lag0", "lag1", "lag2")]
    >>> scene = pinlin.Scene(robot, springs, gravity=(0.0, 0.0, 0.0), prescribed={"spin": 3.0})
    >>> orbit = pinlin.periodic_orbit(scene, scene.neutral())
    >>> sys = pinlin.multiblade_transform(scene, orbit, ["lag0", "lag1", "lag2"], rotor="spin")
    >>> sys.dof_names
    ('x', 'y', 'blade_collective', 'blade_cos1', 'blade_sin1')
    """
    if rotor not in scene.prescribed:
        raise ParameterError("rotor", f"{rotor!r} is not a joint prescribed at a constant speed in this scene; "
                                      f"constant-speed joints: {sorted(scene.prescribed)}")
    omega = float(scene.prescribed[rotor])
    index = {name: i for i, name in enumerate(scene.dof_names)}
    rows = []
    for name in blades:
        if name not in index:
            raise ParameterError("blades", f"{name!r} is not a free 1-DOF coordinate of the scene; "
                                           f"free coordinates: {list(scene.dof_names)}")
        rows.append(index[name])
    co = variational_coefficients(scene, orbit)
    return multiblade_transform_matrices(co.M, co.C, co.K, rows, omega, psi0=psi0,
                                         dof_names=list(scene.dof_names), variation_tol=variation_tol)
