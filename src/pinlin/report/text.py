"""The human-readable report of ``pinlin analyze`` (from its JSON document)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..linearization.system import MATRIX_NAMES

__all__ = ["render_text", "MAX_PRINTED_SIZE", "BALANCING_PRECISION"]

#: Matrices with more coordinates than this are summarized by their Frobenius norm (a row must fit a screen).
MAX_PRINTED_SIZE = 12
#: Significant digits of the balancing forces: they are held by actuators, an engineering figure.
BALANCING_PRECISION = 4
#: Extra characters per printed matrix entry beyond its significant digits (sign, point, exponent).
_CELL_PADDING = 7


def _matrix_text(name: str, a: np.ndarray, names: Sequence[str], precision: int) -> str:
    if a.shape[0] > MAX_PRINTED_SIZE:
        return f"  {name}: {a.shape[0]}x{a.shape[0]}, ||{name}||_F = {np.linalg.norm(a):.6g}"
    width = max(len(n) for n in names)
    rows = [f"  {name} ="]
    for label, row in zip(names, a):
        cells = " ".join(f"{x: .{precision}g}".rjust(precision + _CELL_PADDING) for x in row)
        rows.append(f"    {label.rjust(width)}  {cells}")
    return "\n".join(rows)


def _scene_lines(s: dict) -> list[str]:
    return [
        f"  scene file: {s['source']}",
        f"  nq = {s['nq']}, nv = {s['nv']}, free coordinates n = {s['n']}: {', '.join(s['dof_names'])}",
        f"  gravity = {s['gravity']} m/s^2" + (f", prescribed velocities {s['prescribed']}" if s["prescribed"] else ""),
        "  elements: " + (", ".join(f"{e['kind']}({e.get('joint', e.get('frame', ''))})" for e in s["elements"]) or "none"),
        "",
    ]


def _equilibrium_lines(eq: dict, precision: int) -> list[str]:
    return [
        f"Equilibrium: {eq['method']}",
        f"  q = {np.array2string(np.array(eq['q']), precision=precision)}",
        f"  residual = {eq['residual']:.3e} (relative {eq['relative_residual']:.2e}), "
        f"{eq['iterations']} iterations, {eq['elapsed'] * 1e3:.2f} ms",
        *(f"  note: {note}" for note in eq["notes"]),
        "",
    ]


def _structure_text(structure: dict) -> str:
    return "  structure (eigenvalue signs -/0/+): " + "; ".join(
        f"{name}: " + ("zero" if d["kind"] == "zero" else f"{d['negative']}/{d['zero']}/{d['positive']}")
        for name, d in structure.items()
    )


def _linearization_lines(lin: dict, names: Sequence[str], precision: int) -> list[str]:
    out = []
    if lin["balancing"] is not None:
        out += [
            "Operating point held by constant actuator forces (balancing, asked for explicitly)",
            f"  balancing forces = {np.array2string(np.array(lin['balancing']), precision=BALANCING_PRECISION)}",
            "",
        ]
    zero = ", ".join(n for n in MATRIX_NAMES if n not in lin["nonzero"]) or "none"
    out.append("Linearized equations  M x'' + (D + G) x' + (S + N) x = f")
    out.append(f"  nonzero: {', '.join(lin['nonzero'])}; zero: {zero}")
    for name in lin["nonzero"]:
        out.append(_matrix_text(name, np.array(lin[name]), names, precision))
    out.append(_structure_text(lin["structure"]))
    out.append(f"  Pinocchio calls: {', '.join(lin['calls']) or 'none'}")
    if lin["dropped"]:
        out.append("  set to zero as rounding: " + ", ".join(f"{k} ({v:.1e} relative)" for k, v in lin["dropped"].items()))
    out += [f"  note: {note}" for note in lin["notes"]]
    out.append(f"  equilibrium residual (relative) = {lin['residual']:.2e}; linearize {lin['elapsed'] * 1e3:.2f} ms")
    out.append("")
    return out


def render_text(report: dict, precision: int = 6) -> str:
    """The human-readable report of a :func:`pinlin.report.analyze` document.

    Parameters
    ----------
    report : dict
        The JSON document (version :data:`pinlin.report.REPORT_VERSION`).
    precision : int
        Significant digits of the printed matrices and configuration.
    """
    s = report["scene"]
    out = [f"pinlin {report['pinlin_version']}: {s['robot']} from {s['urdf']}", *_scene_lines(s)]
    if "equilibrium" in report:
        out += _equilibrium_lines(report["equilibrium"], precision)
    out += _linearization_lines(report["linearization"], s["dof_names"], precision)
    modes = report["modes"]
    out += [modes["table"], f"  modal analysis {modes['elapsed'] * 1e3:.2f} ms", ""]
    st = report["stability"]
    out += [f"Stability: {st['kind'].replace('_', ' ').upper()}", f"  {st['reason']}", ""]
    out.append(f"Total {report['elapsed'] * 1e3:.1f} ms")
    return "\n".join(out)
