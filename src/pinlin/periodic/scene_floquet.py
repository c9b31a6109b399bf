"""Floquet analysis of a scene along its periodic orbit (theory: Floquet): :func:`floquet_analysis`."""

from __future__ import annotations

import time

import numpy as np

from ..errors import ParameterError
from ..errors.deprecated import renamed_keywords
from ..model.scene import Scene
from .analysis import floquet_second_order
from .coefficients import variational_coefficients
from .inputs import coefficient
from .options import (GROWTH, HARMONICS, MAX_SAMPLES, MAX_STEPS, MAX_TIME, RTOL, SAFETY, SAMPLING, STAGES,
                      STRUCTURE_TOL, FloquetOptions)
from .orbit_error import orbit_bound
from .orbit_result import PeriodicOrbit
from .result import FloquetAnalysis

__all__ = ["floquet_analysis"]


@renamed_keywords(structure_tolerance="structure_tol")
def floquet_analysis(scene: Scene, orbit: PeriodicOrbit, *, rtol: float = RTOL, stages: int = STAGES,
                     growth: float = GROWTH, harmonics: int = HARMONICS, conservative: bool | None = None,
                     safety: float = SAFETY, structure_tol: float = STRUCTURE_TOL, max_steps: int = MAX_STEPS,
                     max_time: float = MAX_TIME, sampling: str = SAMPLING, max_samples: int = MAX_SAMPLES,
                     autonomous: None = None) -> FloquetAnalysis:
    """Floquet multipliers of the variational equation of ``scene`` along ``orbit``.

    .. math::  M(t)\\, \\ddot x + C(t)\\, \\dot x + K(t)\\, x = 0

    with M, C, K from :func:`~pinlin.periodic.coefficients.variational_coefficients` (Pinocchio's RNEA
    derivatives at the orbit's actual acceleration, elements included, on the free coordinates), handed
    to the Floquet pipeline of :func:`~pinlin.periodic.analysis.floquet_analysis_matrices` with the orbit's
    period: one Pinocchio pass gives M, C and K at a time, sampled once per period (``sampling="auto"``)
    where their trigonometric interpolant converges.  An autonomous orbit is analysed as such (its
    multiplier 1, with the Jordan partner of a conservative family, set apart from the verdict).  A
    ``constant`` orbit is the equilibrium itself, with the prescribed joints moving.

    Parameters
    ----------
    scene : Scene
    orbit : PeriodicOrbit
        From :func:`pinlin.periodic_orbit` for this scene.
    rtol, stages, growth, harmonics, conservative, safety, structure_tol, max_steps, max_time, sampling, max_samples
        As :func:`~pinlin.periodic.analysis.floquet_analysis_matrices` (defaults in
        :mod:`pinlin.periodic.options`; ``structure_tolerance`` is the deprecated spelling of
        ``structure_tol``).
    autonomous : None
        Decided by the orbit (``orbit.autonomous``): passing it is an error.

    Returns
    -------
    FloquetAnalysis

    Raises
    ------
    ParameterError
        ``orbit`` is not a :class:`PeriodicOrbit` of ``scene``, ``autonomous`` is given, or an option is out
        of its range.

    Examples
    --------
    The bundled pendulum on a vertically vibrating pivot (Kapitza), its orbit the equilibrium itself:

    >>> spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> orbit = pinlin.periodic_orbit(spec.scene, spec.q0)
    >>> flo = pinlin.floquet_analysis(spec.scene, orbit)
    >>> print(orbit.constant, flo.multipliers.shape, flo.stability.kind)
    True (2,) marginally_stable
    """
    if not isinstance(orbit, PeriodicOrbit):
        raise ParameterError("orbit", f"expected a PeriodicOrbit (pinlin.periodic_orbit), got {type(orbit).__name__}")
    if orbit.scene is not scene:
        raise ParameterError("orbit", "belongs to another scene: compute it with periodic_orbit(scene, ...)")
    if autonomous is not None:
        raise ParameterError("autonomous", "is decided by the orbit (orbit.autonomous); do not pass it")
    start = time.perf_counter()
    options = FloquetOptions(rtol=rtol, stages=stages, growth=growth, harmonics=harmonics, safety=safety,
                             max_steps=max_steps, max_time=max_time, sampling=sampling, max_samples=max_samples,
                             structure_tol=structure_tol)
    co = variational_coefficients(scene, orbit)

    def checked():
        return tuple(coefficient(name, f)[0] for name, f in (("M", co.M), ("C", co.C), ("K", co.K)))

    def triple(t):
        p = co.point(t)
        return np.stack([p.M, p.C, p.K])

    return floquet_second_order(triple, checked, scene.n, orbit.period, options, start=start,
                                autonomous=orbit.autonomous, conservative=conservative,
                                what=f"scene {scene.robot.name!r}, n = {scene.n}",
                                orbit_errors=lambda tr, eig, monodromy: orbit_bound(scene, orbit, tr, eig, monodromy))
