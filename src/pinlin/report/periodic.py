"""``pinlin analyze`` of a periodic scene: the periodic orbit and its Floquet analysis (theory: Floquet).

A scene is periodic when a prescribed joint follows a periodic motion (``[prescribed] pivot = { amplitude = ...,
omega = ... }``) or turns at a constant speed on which the equations depend (:func:`pinlin.scene_period`): its
linearized equations have periodic coefficients, so the report is the periodic reference motion
(:func:`pinlin.periodic_orbit` from the file's start) and the Floquet multipliers, exponents and frequencies
with their error bounds and the verdict (:func:`pinlin.floquet_analysis`) instead of eigenvalues.
"""

from __future__ import annotations

import time
from typing import Any

from ..errors import ParameterError
from ..model.scene_file import SceneSpec
from ..periodic import floquet_analysis, periodic_orbit, scene_period
from ..version import __version__
from .document import scene_section

__all__ = ["is_periodic", "analyze_periodic", "render_periodic_text", "check_periodic_options", "PERIODIC_REPORT_VERSION"]

#: Version of the periodic report's JSON layout.
PERIODIC_REPORT_VERSION = 1


def is_periodic(spec: SceneSpec) -> bool:
    """True when the scene's linearized equations are time-periodic at the file's start.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.periodic import is_periodic
    >>> is_periodic(load_scene(pinlin.data_path("scenes/kapitza.toml")))
    True
    >>> is_periodic(load_scene(pinlin.data_path("scenes/double_pendulum.toml")))
    False
    """
    scene = spec.scene
    if scene.motions:
        return True
    return bool(scene.prescribed) and scene_period(scene, spec.q0) is not None


def analyze_periodic(spec: SceneSpec):
    """The periodic orbit from the spec's start and its Floquet analysis, as a report.

    Returns
    -------
    report : dict
        JSON-serializable: ``scene``, ``orbit``, ``floquet`` (each result's ``to_dict()``), ``stability``,
        ``elapsed``.
    orbit : PeriodicOrbit
    flo : FloquetAnalysis

    Raises
    ------
    PinlinError
        What :func:`pinlin.periodic_orbit` and :func:`pinlin.floquet_analysis` refuse.

    Examples
    --------
    >>> from pinlin.report.periodic import analyze_periodic
    >>> from pinlin.model.scene_file import load_scene
    >>> spec = load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> report, orbit, floquet = analyze_periodic(spec)
    >>> report["kind"], orbit.constant, round(orbit.period, 9)
    ('periodic', True, 0.031415927)
    """
    t0 = time.perf_counter()
    orbit = periodic_orbit(spec.scene, spec.q0)
    flo = floquet_analysis(spec.scene, orbit)
    report: dict[str, Any] = {
        "report_version": PERIODIC_REPORT_VERSION,
        "kind": "periodic",
        "pinlin_version": __version__,
        "scene": {**scene_section(spec), "motions": {j: repr(m) for j, m in spec.scene.motions.items()}},
        "orbit": orbit.to_dict(),
        "floquet": flo.to_dict(),
        "stability": flo.stability.to_dict(),
    }
    report["elapsed"] = time.perf_counter() - t0
    return report, orbit, flo


def render_periodic_text(report: dict, orbit, flo, precision: int = 6) -> str:
    """The periodic report as text: scene, orbit, the multipliers' table (:meth:`FloquetAnalysis.table`) and
    the verdict; ``precision`` is accepted for the command line's option (the table has its own digits).

    Examples
    --------
    >>> from pinlin.report.periodic import analyze_periodic, render_periodic_text
    >>> from pinlin.model.scene_file import load_scene
    >>> spec = load_scene(pinlin.data_path("scenes/kapitza.toml"))
    >>> text = render_periodic_text(*analyze_periodic(spec))
    >>> text.splitlines()[0]
    'pinlin ...: kapitza (.../kapitza.toml), periodic'
    """
    sc = report["scene"]
    lines = [f"pinlin {report['pinlin_version']}: {sc['robot']} ({sc['source']}), periodic",
             f"  free coordinates ({sc['n']}): {', '.join(sc['dof_names'])}"]
    for joint, motion in sc["motions"].items():
        lines.append(f"  {joint} follows {motion}")
    for joint, speed in sc["prescribed"].items():
        lines.append(f"  {joint} turns at {speed} {sc['prescribed_units'][joint]}")
    lines += ["", f"Periodic orbit: period {orbit.period:.10g} s, "
                  + ("constant (the free coordinates stay at an equilibrium)" if orbit.constant else
                     f"{orbit.iterations} Newton step{'s' if orbit.iterations != 1 else ''} of shooting")
                  + f", error {orbit.error:.1e}", ""]
    lines.append(f"Floquet multipliers ({flo.steps} steps in {flo.segments} segment"
                 f"{'s' if flo.segments != 1 else ''}, {flo.evaluations} evaluations of the coefficients, "
                 f"largest relative bound {flo.error:.1e})")
    lines += ["  " + line for line in flo.table().splitlines()[:-1]]   # the verdict follows in its own section
    lines += ["", f"Stability: {flo.stability.kind.replace('_', ' ').upper()}", f"  {flo.stability.reason}", ""]
    lines.append(f"Analysis {report['elapsed'] * 1e3:.1f} ms (periodic orbit, Floquet analysis)")
    return "\n".join(lines)


def check_periodic_options(plot, animate) -> None:
    """Refuse, before anything is computed, the outputs a periodic report does not have.

    Raises
    ------
    ParameterError
        ``--plot`` or ``--animate`` given for a periodic scene (they draw eigenvalues and mode shapes).

    Examples
    --------
    >>> from pinlin.report.periodic import check_periodic_options
    >>> check_periodic_options(None, None)
    >>> check_periodic_options("modes.png", None)
    Traceback (most recent call last):
    ...
    pinlin.errors.base.ParameterError: --plot: draws eigenvalues or a mode shape; a periodic scene has ...
    """
    for option, value in (("--plot", plot), ("--animate", animate)):
        if value is not None:
            raise ParameterError(option, "draws eigenvalues or a mode shape; a periodic scene has Floquet "
                                         "multipliers instead (use --json, or pinlin.floquet_analysis in Python)")
