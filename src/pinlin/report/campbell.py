"""``pinlin campbell``: frequencies and damping of a scene against the speed of a prescribed joint.

A Campbell study is a sweep (:mod:`pinlin.report.sweep`) of one prescribed
velocity, ``prescribed.<joint>``: at every speed the scene is analysed as
``pinlin analyze`` analyses it, the modes are tracked by shape
(:func:`pinlin.studies.track_modes`) and one mode of each conjugate pair is
kept (:func:`pinlin.studies.one_per_conjugate_pair`, as :func:`pinlin.plot.campbell`
draws them).  Wherever the verdict changes class between two neighbouring
speeds, the critical speed is found by :func:`pinlin.critical_parameter` on the
speed, to rounding, with its error bound.

The speeds come from the options (``--joint``, ``--speeds``) or from the scene
file's ``[campbell]`` table (:data:`CAMPBELL_FORMAT`).
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..errors import ParameterError, SceneFileError
from ..model.scene_file import SceneSpec
from ..results import to_jsonable
from ..studies import MAX_POINTS, one_per_conjugate_pair
from .sweep import SweepOutcome, SweepPlan, sweep_document, sweep_plan
from .text import complex_text, number

__all__ = ["campbell_plan", "campbell_document", "render_campbell_text", "write_campbell_plot", "CAMPBELL_FORMAT",
           "MAX_PRINTED_BRANCHES"]

CAMPBELL_FORMAT = """\
    [campbell]
    joint = "ring"                  # a prescribed joint; default: the scene's only prescribed joint
    speeds = { start = 0.0, stop = 6.0, num = 61 }   # [rad/s, or m/s for a prismatic joint]; or a list

--joint and --speeds (START:STOP:NUM or a comma-separated list) replace the table's entries.
"""

#: Branches (modes, one per conjugate pair) printed in the text table; the JSON document holds all.
MAX_PRINTED_BRANCHES = 4


class _Reader:
    """Fails naming the command-line option, or the scene file and the ``campbell.<key>``."""

    def __init__(self, spec: SceneSpec, option: bool):
        self.spec, self.option = spec, option

    def fail(self, key: str, message: str):
        if self.option:
            raise ParameterError(f"--{key}", message)
        raise SceneFileError(message, self.spec.path, f"campbell.{key}")

    def number(self, value, key: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not abs(value) <= sys.float_info.max:
            self.fail(key, f"expected a finite number, got {value!r:.80}")
        return float(value)

    def speeds(self, raw) -> list[float]:
        if isinstance(raw, Mapping):
            if set(raw) != {"start", "stop", "num"}:
                self.fail("speeds", "expected { start = ..., stop = ..., num = ... } or a list of numbers")
            num = raw["num"]
            if isinstance(num, bool) or not isinstance(num, int) or not 2 <= num <= MAX_POINTS:
                self.fail("speeds", f"num: expected an integer in [2, {MAX_POINTS}], got {num!r:.80}")
            start, stop = self.number(raw["start"], "speeds"), self.number(raw["stop"], "speeds")
            return list(np.linspace(start, stop, num))
        if not isinstance(raw, (list, tuple)) or len(raw) < 2:
            self.fail("speeds", f"expected at least two speeds (a list or START:STOP:NUM), got {raw!r:.80}")
        if len(raw) > MAX_POINTS:
            self.fail("speeds", f"{len(raw)} speeds; at most {MAX_POINTS}")
        values = [self.number(v, "speeds") for v in raw]
        steps = np.diff(values)
        if not (np.all(steps > 0) or np.all(steps < 0)):
            self.fail("speeds", "must be strictly increasing or strictly decreasing")
        return values

    def joint(self, joint) -> str:
        prescribed = sorted(self.spec.scene.prescribed)
        motions = sorted(self.spec.scene.motions)
        if not prescribed and motions:  # only periodic motions: no constant speed to sweep
            self.fail("joint", f"the scene prescribes no constant speed: {', '.join(map(repr, motions))} "
                      f"{'follows a periodic motion' if len(motions) == 1 else 'follow periodic motions'}, so "
                      f"its equations are time-periodic; analyse it with 'pinlin analyze "
                      f"{self.spec.path or 'SCENE'}' (the Floquet multipliers), or in Python with "
                      f"pinlin.floquet_campbell for a Campbell diagram of a periodic family")
        if joint is None:
            if len(prescribed) != 1:
                self.fail("joint", f"name the prescribed joint whose speed varies; the scene prescribes "
                          f"{prescribed or 'no joint: add a [prescribed] table'}")
            return prescribed[0]
        if joint not in prescribed:
            have = prescribed or "none: add a [prescribed] table"
            self.fail("joint", f"expected a prescribed joint of the scene ({have}), got {joint!r:.80}")
        return joint


def campbell_plan(spec: SceneSpec, joint: str | None = None, speeds=None) -> SweepPlan:
    """The sweep of ``prescribed.<joint>`` over the speeds: from the arguments, else from ``spec.campbell``.

    Parameters
    ----------
    spec : SceneSpec
    joint : str, optional
        A prescribed joint of the scene (``--joint``); default the table's
        ``joint``, else the scene's only prescribed joint.
    speeds : list of float or {"start", "stop", "num"}, optional
        The speeds [rad/s or m/s] (``--speeds``); default the table's ``speeds``.

    Raises
    ------
    ParameterError
        A bad ``--joint`` or ``--speeds`` (named by the option).
    SceneFileError
        A bad ``[campbell]`` table, or no speeds anywhere (naming the file and ``campbell.<key>``).

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.campbell import campbell_plan
    >>> plan = campbell_plan(load_scene(pinlin.data_path("scenes/rotating_ring.toml")), speeds=[0.0, 1.0, 2.0])
    >>> plan.parameters[0].path, plan.parameters[0].unit, plan.parameters[0].values
    ('prescribed.ring', 'rad/s', array([0., 1., 2.]))
    """
    table = spec.campbell if spec.campbell is not None else {}
    if not isinstance(table, Mapping):
        raise SceneFileError(f"expected a table, got {table!r:.80}", spec.path, "campbell")
    unknown = sorted(set(table) - {"joint", "speeds"})
    if unknown:
        raise SceneFileError("unknown key; expected 'joint' and 'speeds'", spec.path, f"campbell.{unknown[0]}")
    name = _Reader(spec, joint is not None).joint(joint if joint is not None else table.get("joint"))
    if speeds is None and "speeds" not in table:
        raise SceneFileError("no speeds: give --speeds START:STOP:NUM or a [campbell] table with speeds",
                             spec.path, "campbell.speeds")
    values = _Reader(spec, speeds is not None).speeds(speeds if speeds is not None else table["speeds"])
    return sweep_plan(spec, {"parameter": f"prescribed.{name}", "values": values}, options=True)


def _branches(outcome: SweepOutcome) -> tuple[np.ndarray, list[int]]:
    lam = outcome.tracked.eigenvalues
    return lam, one_per_conjugate_pair(lam)


def campbell_document(outcome: SweepOutcome) -> dict[str, Any]:
    """The sweep document (:func:`~pinlin.report.sweep.sweep_document`) with a ``campbell`` section.

    ``campbell``: ``joint``, ``unit``, ``speeds`` (of the points that succeeded),
    ``branches`` (one per conjugate pair of tracked modes: ``frequency`` |Im lam|
    [rad/s], ``damping_ratio`` -Re lam / |lam|, ``growth`` Re lam [1/s], per
    speed) and ``critical_speeds`` (each verdict change's exact value, error
    bound, kind, mechanism, verdicts, bracketing speeds and eigenvalue there).

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.campbell import campbell_document, campbell_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> plan = campbell_plan(load_scene(pinlin.data_path("scenes/rotating_ring.toml")), speeds=[0.0, 1.0, 2.0])
    >>> doc = campbell_document(run_sweep(plan))
    >>> sorted(doc["campbell"])
    ['branches', 'critical_speeds', 'joint', 'speeds', 'unit']
    """
    doc = sweep_document(outcome)
    p = outcome.plan.parameters[0]
    section: dict[str, Any] = {"joint": p.field, "unit": p.unit, "speeds": [], "branches": [], "critical_speeds": []}
    if outcome.tracked is not None:
        lam, keep = _branches(outcome)
        section["speeds"] = to_jsonable(outcome.tracked_values)
        with np.errstate(invalid="ignore", divide="ignore"):
            zeta = -lam.real / np.abs(lam)
        section["branches"] = [{"frequency": to_jsonable(np.abs(lam[:, j].imag)), "damping_ratio": to_jsonable(zeta[:, j]),
                                "growth": to_jsonable(lam[:, j].real)} for j in keep]
    for change in doc["changes"]:
        b = change["boundary"]
        if b is not None:
            section["critical_speeds"].append({"speed": b["value"], "error_bound": b["error_bound"], "kind": b["kind"],
                                               "mechanism": b["mechanism"], "verdicts": change["verdicts"],
                                               "between": change["between"], "eigenvalue": b["eigenvalue"],
                                               "verified": b["verified"]})
    doc["campbell"] = section
    return doc


def _table(doc: dict, precision: int) -> list[str]:
    """One row per speed: its verdict, then |Im lam| and zeta of each tracked mode (a failed speed: its error)."""
    c = doc["campbell"]
    shown = c["branches"][:MAX_PRINTED_BRANCHES]
    w = precision + 7
    head = f"{'#':>4}  {'speed [' + c['unit'] + ']':>{w + 2}}  {'verdict':<22}" + "  ".join(
        f"{f'|Im lam|{k + 1} [rad/s]':>{w + 8}} {f'zeta{k + 1}':>9}" for k in range(len(shown)))
    lines = [head.rstrip(), "-" * len(head.rstrip())]
    row = 0  # row of the tracked modes: the speeds that succeeded
    for i, point in enumerate(doc["points"]):
        speed = number(point["values"][0], precision)
        if point["failure"] is not None:
            lines.append(f"{i + 1:>4}  {speed:>{w + 2}}  failed: {point['failure']}")
            continue
        cells = "  ".join(f"{number(b['frequency'][row], precision):>{w + 8}} {number(b['damping_ratio'][row], 4):>9}"
                          for b in shown)
        lines.append(f"{i + 1:>4}  {speed:>{w + 2}}  {point['verdict'].replace('_', ' '):<22}{cells}".rstrip())
        row += 1
    if len(c["branches"]) > len(shown):
        lines.append(f"... {len(c['branches']) - len(shown)} more modes in --json")
    if doc["tracked"] is not None:
        lines += ["", f"Modes tracked by shape: matching defect {float(doc['tracked']['error']):.2e} "
                      f"(1 - smallest MAC between neighbouring speeds)"]
    return lines


def render_campbell_text(doc: dict, precision: int = 6) -> str:
    """The text report of a :func:`campbell_document`: the verdict, tracked frequencies and damping ratios at
    each speed, then the critical speeds.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.campbell import campbell_document, campbell_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> plan = campbell_plan(load_scene(pinlin.data_path("scenes/rotating_ring.toml")), speeds=[0.0, 1.0, 2.0])
    >>> doc = campbell_document(run_sweep(plan))
    >>> from pinlin.report.campbell import render_campbell_text
    >>> render_campbell_text(doc).splitlines()[2]
    "  speed of prescribed joint 'ring' [rad/s]: 3 values from 0 to 2"
    """
    c = doc["campbell"]
    s = doc["scene"]
    out = [f"pinlin {doc['pinlin_version']} campbell: {s['robot']} from {s['urdf']}", f"  scene file: {s['source']}",
           f"  speed of prescribed joint {c['joint']!r} [{c['unit']}]: {len(doc['parameters'][0]['values'])} values "
           f"from {number(doc['parameters'][0]['values'][0], precision)} to "
           f"{number(doc['parameters'][0]['values'][-1], precision)}", "",
           "Modes tracked by shape, one per conjugate pair: damped frequency |Im lam| and damping ratio zeta", ""]
    out += _table(doc, precision)
    out += ["", "Critical speeds" + ("" if c["critical_speeds"] else ": none in the range of speeds")]
    for k in c["critical_speeds"]:
        lam = complex(float(k["eigenvalue"]["re"]), float(k["eigenvalue"]["im"]))
        out.append(f"  {k['speed']:.15g} +- {float(k['error_bound']):.1e} {c['unit']}: {k['kind']}, "
                   f"{k['verdicts'][0].replace('_', ' ')} -> {k['verdicts'][1].replace('_', ' ')} ({k['mechanism']}, "
                   f"lam = {complex_text(lam, precision)}; between {number(k['between'][0], precision)} and "
                   f"{number(k['between'][1], precision)}; verified: {k['verified']})")
    failed = [change for change in doc["changes"] if change["boundary"] is None]
    for change in failed:
        out.append(f"  between {number(change['between'][0], precision)} and {number(change['between'][1], precision)}"
                   f": {change['verdicts'][0]} -> {change['verdicts'][1]}, no exact value ({change['failure']})")
    out += [f"note: {note}" for note in doc["notes"]]
    out += ["", f"Campbell study {doc['elapsed']:.2f} s (the analyses at every speed, mode tracking, critical speeds)"]
    return "\n".join(out)


def write_campbell_plot(path: str, outcome: SweepOutcome, option: str = "--plot") -> None:
    """The Campbell diagram (:func:`pinlin.plot.campbell`) with the critical speeds as vertical lines.

    Raises
    ------
    ParameterError
        Every speed failed (nothing to draw), or the file cannot be written (named ``option``).
    MissingDependencyError
        matplotlib is not installed.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.campbell import campbell_plan, write_campbell_plot
    >>> from pinlin.report.sweep.run import run_sweep
    >>> plan = campbell_plan(load_scene(pinlin.data_path("scenes/rotating_ring.toml")), speeds=[0.0, 1.0, 2.0])
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "campbell.png"
    >>> write_campbell_plot(str(path), run_sweep(plan))
    >>> path.stat().st_size > 0
    True
    """
    from .. import plot

    if outcome.tracked is None:
        raise ParameterError(option, "every speed failed: nothing to draw")
    import matplotlib.pyplot as plt

    p = outcome.plan.parameters[0]
    fig, ax = plt.subplots(figsize=(7, 5))
    try:
        plot.campbell(outcome.tracked_values, outcome.tracked.eigenvalues, ax, vectors=outcome.tracked.vectors,
                      label=f"speed of {p.field} [{p.unit}]")
        for change in outcome.changes:
            if change.boundary is not None:
                ax.axvline(change.boundary.value, color="#e63946", ls="--", lw=1.0,
                           label=f"critical speed {change.boundary.value:.6g} {p.unit}")
        if any(change.boundary is not None for change in outcome.changes):
            ax.legend(loc="best", fontsize="small")
        ax.set_title(f"{outcome.plan.spec.scene.robot.name}: Campbell diagram")
        fig.tight_layout()
        fig.savefig(path)
    except OSError as exc:
        raise ParameterError(option, f"cannot write {path}: {exc}") from None
    finally:
        plt.close(fig)
