"""The human-readable report of ``pinlin sweep`` (from its JSON document).

One parameter: a table of the points (value, verdict, the largest Re lam, the
lowest nonzero |lam|, the largest backward error).  Two parameters: the map of
verdicts as letters.  Then each verdict change once, with its exact boundary.
"""

from __future__ import annotations

import numpy as np

from ..text import complex_text, number

__all__ = ["render_sweep_text", "VERDICT_LETTERS"]

#: One letter per verdict in the text map of a two-parameter sweep.
VERDICT_LETTERS = {"asymptotically_stable": "S", "marginally_stable": "M", "divergence": "D", "flutter": "F",
                   "undecided": "?", "failed": "x"}


def _label(p: dict) -> str:
    return f"{p['path']} [{p['unit']}]" if p["unit"] else p["path"]


def _points_table(doc: dict, precision: int) -> list[str]:
    name = _label(doc["parameters"][0])
    w = max(len(name), precision + 7)
    head = f"{'#':>4}  {name:>{w}}  {'verdict':<22}{'max Re lam [1/s]':>17}{'min |lam| [rad/s]':>18}{'eta':>9}"
    lines = [head, "-" * len(head)]
    for i, point in enumerate(doc["points"], start=1):
        value = number(point["values"][0], precision).rjust(w)
        if point["eigenvalues"] is None:
            lines.append(f"{i:>4}  {value}  failed: {point['failure']}")
            continue
        lam = np.array(point["eigenvalues"]["re"], dtype=float) + 1j * np.array(point["eigenvalues"]["im"], dtype=float)
        bound = np.array(point["error_bound"], dtype=float)
        moving = np.abs(lam)[np.abs(lam) > bound]  # not a rigid-body zero within its bound
        lowest = number(moving.min(), precision) if moving.size else "-"
        lines.append(
            f"{i:>4}  {value}  {point['verdict'].replace('_', ' '):<22}{number(lam.real.max(), precision):>17}"
            f"{lowest:>18}{float(point['error']):>9.1e}"
        )
    return lines


def _map(doc: dict, precision: int) -> list[str]:
    p1, p2 = doc["parameters"]
    n1, n2 = len(p1["values"]), len(p2["values"])
    verdicts = np.array([VERDICT_LETTERS[p["verdict"]] for p in doc["points"]]).reshape(n1, n2)
    legend = ", ".join(f"{v} {k.replace('_', ' ')}" for k, v in VERDICT_LETTERS.items())
    labels = [number(v, precision) for v in p2["values"]]
    w = max(len(s) for s in labels)
    lines = [f"Verdicts: rows {_label(p2)} (top: last value), columns {_label(p1)} from "
             f"{number(p1['values'][0], precision)} to {number(p1['values'][-1], precision)} ({legend})"]
    for j in reversed(range(n2)):
        lines.append(f"  {labels[j].rjust(w)} | {''.join(verdicts[:, j])}")
    return lines


def _changes(doc: dict, precision: int) -> list[str]:
    p1 = doc["parameters"][0]
    unit = f" {p1['unit']}" if p1["unit"] else ""
    lines = ["Verdict changes" + ("" if doc["changes"] else ": none")]
    for c in doc["changes"]:
        at = "" if c["second"] is None else f" at {doc['parameters'][1]['path']} = {number(c['second'], precision)}"
        what = f"{c['verdicts'][0].replace('_', ' ')} -> {c['verdicts'][1].replace('_', ' ')}"
        between = f"between {number(c['between'][0], precision)} and {number(c['between'][1], precision)}"
        b = c["boundary"]
        if b is None:
            why = f": no exact value ({c['failure']})" if c["failure"] else ""
            lines.append(f"  {what} {between}{unit}{at}{why}")
            continue
        lam = complex(b["eigenvalue"]["re"], b["eigenvalue"]["im"])
        lines.append(
            f"  {b['kind']} at {p1['path']} = {b['value']:.15g} +- {float(b['error_bound']):.1e}{unit}{at}: {what} "
            f"({b['mechanism']}, lam = {complex_text(lam, precision)}; {between}; verified: {b['verified']})"
        )
    return lines


def render_sweep_text(doc: dict, precision: int = 6) -> str:
    """The text report of a :func:`~pinlin.report.sweep.sweep_document`.

    Parameters
    ----------
    doc : dict
        The sweep document.
    precision : int
        Significant digits of parameter values and eigenvalues.

    Examples
    --------
    >>> from pinlin.report.sweep.document import sweep_document
    >>> from pinlin.report.sweep.text import render_sweep_text
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> render_sweep_text(sweep_document(run_sweep(plan))).splitlines()[2]
    '  follower.tip.force [N]: 4 values from 0 to 30'
    """
    s = doc["scene"]
    out = [f"pinlin {doc['pinlin_version']} sweep: {s['robot']} from {s['urdf']}", f"  scene file: {s['source']}"]
    for p in doc["parameters"]:
        values = p["values"]
        out.append(f"  {_label(p)}: {len(values)} values from {number(values[0], precision)} "
                   f"to {number(values[-1], precision)}")
    out.append("")
    out += _points_table(doc, precision) if len(doc["parameters"]) == 1 else _map(doc, precision)
    out.append("")
    if doc["tracked"] is not None:
        out += [f"Modes tracked by shape: matching defect {float(doc['tracked']['error']):.2e} "
                f"(1 - smallest MAC between neighbouring points)", ""]
    out += _changes(doc, precision)
    out += [f"note: {note}" for note in doc["notes"]]
    out += ["", f"Sweep {doc['elapsed']:.2f} s (the analyses at every point, mode tracking, boundaries)"]
    return "\n".join(out)
