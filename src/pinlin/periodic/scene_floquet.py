"""Floquet analysis of a scene along its periodic orbit (theory: Floquet): :func:`floquet_analysis`."""

from __future__ import annotations

import time

import numpy as np

from ..errors import ParameterError
from ..model.scene import Scene
from .analysis import floquet_second_order
from .coefficients import variational_coefficients
from .inputs import coefficient
from .orbit_result import PeriodicOrbit
from .result import FloquetAnalysis

__all__ = ["floquet_analysis"]


def floquet_analysis(scene: Scene, orbit: PeriodicOrbit, **options) -> FloquetAnalysis:
    """Floquet multipliers of the variational equation of ``scene`` along ``orbit``.

    .. math::  M(t)\\, \\ddot x + C(t)\\, \\dot x + K(t)\\, x = 0

    with M, C, K from :func:`~pinlin.periodic.coefficients.variational_coefficients` (Pinocchio's RNEA
    derivatives at the orbit's actual acceleration, elements included, on the free coordinates), handed
    to :func:`~pinlin.periodic.analysis.floquet_analysis_matrices` with the orbit's period.  An autonomous
    orbit is analysed with ``autonomous=True`` (its multiplier 1, with the Jordan partner of a conservative
    family, set apart from the verdict).  A ``constant`` orbit is the equilibrium itself, with the
    prescribed joints moving.

    Parameters
    ----------
    scene : Scene
    orbit : PeriodicOrbit
        From :func:`pinlin.periodic_orbit` for this scene.
    **options
        As :func:`~pinlin.periodic.analysis.floquet_analysis_matrices` (``rtol``, ``stages``, ``growth``,
        ``harmonics``, ``safety``, ``max_steps``, ``max_time``, ``sampling``, ``max_samples``, ...): M, C and K
        come from one Pinocchio pass per time, sampled once per period (``sampling="auto"``) where their
        trigonometric interpolant converges.

    Returns
    -------
    FloquetAnalysis

    Raises
    ------
    ParameterError
        ``orbit`` is not a :class:`PeriodicOrbit` of ``scene``, or ``autonomous`` is given (the orbit says).
    """
    if not isinstance(orbit, PeriodicOrbit):
        raise ParameterError("orbit", f"expected a PeriodicOrbit (pinlin.periodic_orbit), got {type(orbit).__name__}")
    if orbit.scene is not scene:
        raise ParameterError("orbit", "belongs to another scene: compute it with periodic_orbit(scene, ...)")
    if "autonomous" in options:
        raise ParameterError("autonomous", "is decided by the orbit (orbit.autonomous); do not pass it")
    start = time.perf_counter()
    co = variational_coefficients(scene, orbit)

    def checked():
        return tuple(coefficient(name, f)[0] for name, f in (("M", co.M), ("C", co.C), ("K", co.K)))

    def triple(t):
        p = co.point(t)
        return np.stack([p.M, p.C, p.K])

    return floquet_second_order(triple, checked, scene.n, orbit.period, start=start,
                                autonomous=orbit.autonomous, what=f"scene {scene.robot.name!r}, n = {scene.n}",
                                **options)
