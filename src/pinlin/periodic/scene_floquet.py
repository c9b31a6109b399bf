"""Floquet analysis of a scene along its periodic orbit (theory: Floquet): :func:`floquet_analysis`."""

from __future__ import annotations

from ..errors import ParameterError
from ..model.scene import Scene
from .analysis import floquet_analysis_matrices
from .coefficients import variational_coefficients
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
        Passed to :func:`~pinlin.periodic.analysis.floquet_analysis_matrices` (``rtol``, ``stages``,
        ``growth``, ``harmonics``, ``safety``, ``max_steps``, ``max_time``, ...).

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
    coefficients = variational_coefficients(scene, orbit)
    return floquet_analysis_matrices(coefficients.M, coefficients.C, coefficients.K, orbit.period,
                                     autonomous=orbit.autonomous, **options)
