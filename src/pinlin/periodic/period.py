"""The period of a scene's motion (theory: Floquet): :func:`scene_period`.

Everything that moves periodically sets a period: each periodic prescribed motion (:class:`~pinlin.Harmonic`
etc.) its own T_j, and each joint turning at a constant speed Omega whose position the equations depend on
the period 2 pi / |Omega|.  Whether they depend on it is decided as :func:`pinlin.linearize` decides it: a
proof of :mod:`pinlin.linearization.time_invariance` (then the joint sets no period), else the numerical
check :func:`pinlin.linearization.periodicity.numeric_change` at a configuration.  The common period is the
least common multiple (:func:`pinlin.model.motions.common_period`: period ratios p / r with r <= 12 within
1e-12), and incommensurate periods are refused as quasi-periodic.
"""

from __future__ import annotations

import math

from ..errors import InputError, TimePeriodicError
from ..linearization.assembly import assemble
from ..linearization.options import PERIODIC_TOL
from ..linearization.periodicity import numeric_change
from ..linearization.plan import plan_of
from ..model.motions import common_period
from ..model.scene import Scene

__all__ = ["scene_period", "period_sources"]


def period_sources(scene: Scene, q=None, *, periodic_tol: float = PERIODIC_TOL) -> dict[str, float]:
    """Joint name -> the period [s] it sets: every periodic motion, and every constant-speed joint whose
    position the equations depend on (at ``q``; without ``q``, every one no proof covers).

    Raises
    ------
    InputError
        A prismatic joint sliding at constant speed changes the equations: they depend on time without
        repeating.

    Examples
    --------
    >>> from pinlin.periodic.period import period_sources
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> {name: round(T, 6) for name, T in period_sources(spec.scene).items()}
    {...: 0.031416}
    """
    periods = {name: m.period for name, m in scene.motions.items()}
    plan = plan_of(scene)
    moving = [name for name in plan.unproved if scene.prescribed[name] != 0]
    if moving and q is not None:
        q = scene.check_configuration(q)
        base = assemble(scene, q, stiffness=True, damping=True, mass=True)
        depends = []
        for name in moving:
            try:
                numeric_change(scene, q, base, (name,), periodic_tol)
            except TimePeriodicError:
                depends.append(name)
        moving = depends
    for name in moving:
        j = scene.robot.joint(name)
        if j.kind.removeprefix("JointModel").startswith("P"):
            raise InputError(
                f"prescribed joint {name!r} slides at {scene.prescribed[name]:g} m/s and the equations depend "
                f"on its position: they change with time without repeating, so there is no period"
            )
        periods[name] = 2.0 * math.pi / abs(scene.prescribed[name])
    return periods


def scene_period(scene: Scene, q=None, *, periodic_tol: float = PERIODIC_TOL) -> float | None:
    """The common period T [s] of everything that moves in ``scene``, or None when nothing does.

    Parameters
    ----------
    scene : Scene
    q : (nq,) array, optional
        The configuration at which constant-speed joints without a time-invariance proof are checked
        numerically; without it each such joint is taken to set the period 2 pi / |Omega|.
    periodic_tol : float
        Tolerance of that check (as :func:`pinlin.linearize`'s).

    Raises
    ------
    QuasiPeriodicError
        Incommensurate periods (names the joints and periods).
    InputError
        A prismatic joint at constant speed on which the equations depend.

    Examples
    --------
    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> print(f"{pinlin.scene_period(spec.scene):.6f}")          # the pivot's period 2 pi / 200 rad/s
    0.031416
    """
    return common_period(period_sources(scene, q, periodic_tol=periodic_tol))
