"""The human-readable report of ``pinlin analyze`` (rendered from its JSON document, so the two never disagree).

What the text promises, each checked by a test:

- no "-0": a negative zero prints as 0;
- a matrix entry below the matrix's rounding scale prints as 0: the scale is
  the rounding bound c n eps ||A||_2 of :func:`pinlin.numerics.definiteness.rounding_bound`,
  the same below which an eigenvalue of A is not told from zero;
- every printed matrix carries its unit (:func:`pinlin.report.units.matrix_unit`);
- a mode's kind is the result's own (``Modes.kind``: "undamped" on the axis of
  a system with D = 0), never relabelled here;
- the stability verdict is printed once, in its own section.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..linearization.system import MATRIX_NAMES
from ..numerics.definiteness import rounding_bound
from .energy import energy_lines
from .units import matrix_unit

__all__ = ["render_text", "mode_table", "matrix_text", "number", "complex_text", "plural", "MAX_PRINTED_SIZE",
           "BALANCING_PRECISION"]

#: Matrices with more coordinates than this are summarized by their Frobenius norm (a row must fit a screen).
MAX_PRINTED_SIZE = 12
#: Significant digits of the balancing forces: they are held by actuators, an engineering figure.
BALANCING_PRECISION = 4
#: Extra characters per printed matrix entry beyond its significant digits (sign, point, exponent).
_CELL_PADDING = 7
#: Significant digits of the figures of merit (eta, kappa, error bound): their order of magnitude is the message.
_FIGURE_DIGITS = 1


def _float(value) -> float:
    """A number of the JSON document (non-finite ones are the strings "nan", "inf", "-inf") as float."""
    return float(value)


def number(x: float, precision: int, *, zero_below: float = 0.0) -> str:
    """``x`` to ``precision`` significant digits; 0 (never "-0") when ``|x| <= zero_below``.

    Examples
    --------
    >>> from pinlin.report.text import number
    >>> number(3.14159265, 4), number(-1e-20, 4, zero_below=1e-12)
    ('3.142', '0')
    """
    x = _float(x)
    if abs(x) <= zero_below:  # also turns -0.0 into 0
        return "0"
    return f"{x:.{precision}g}"


def complex_text(lam: complex, precision: int = 6) -> str:
    """A complex number as ``a+bi`` (``i``, as the stability verdicts write them; a real one as ``a``).

    Examples
    --------
    >>> from pinlin.report.text import complex_text
    >>> complex_text(-0.5 + 3.2j, 4), complex_text(2.0)
    ('-0.5+3.2i', '2')
    """
    lam = complex(lam)
    if lam.imag == 0:
        return number(lam.real, precision)
    return f"{number(lam.real, precision)}{lam.imag:+.{precision}g}i"


def plural(count: int, noun: str) -> str:
    """``1 iteration``, ``3 iterations``.

    Examples
    --------
    >>> from pinlin.report.text import plural
    >>> plural(1, "mode"), plural(3, "mode")
    ('1 mode', '3 modes')
    """
    return f"{count} {noun}" + ("" if count == 1 else "s")


def matrix_text(name: str, a: np.ndarray, names: Sequence[str], units: Sequence[str], precision: int) -> str:
    """The matrix ``name`` with its unit, entries at rounding level printed as 0.

    Entries with ``|a_ij| <= rounding_bound(n, ||A||_2)`` (c n eps ||A||_2) are
    below what rounding in forming A can tell from zero.

    Examples
    --------
    >>> from pinlin.report.text import matrix_text
    >>> print(matrix_text("M", np.array([[1.0, 0.2], [0.2, 0.5]]), ["joint1", "joint2"], ["rad", "rad"], 4))
      M [kg m^2] =
        joint1            1         0.2
        joint2          0.2         0.5
    """
    unit = matrix_unit(name, units)
    if a.shape[0] > MAX_PRINTED_SIZE:
        return f"  {name} [{unit}]: {a.shape[0]}x{a.shape[0]}, ||{name}||_F = {np.linalg.norm(a):.6g}"
    scale = rounding_bound(a.shape[0], float(np.linalg.norm(a, 2)))
    width = max(len(n) for n in names)
    rows = [f"  {name} [{unit}] ="]
    for label, row in zip(names, a):
        cells = " ".join(number(x, precision, zero_below=scale).rjust(precision + _CELL_PADDING) for x in row)
        rows.append(f"    {label.rjust(width)}  {cells}")
    return "\n".join(rows)


def _vector_text(values, precision: int) -> str:
    return "[" + ", ".join(number(x, precision) for x in values) + "]"


def _scene_lines(s: dict) -> list[str]:
    units = s.get("dof_units") or ["?"] * len(s["dof_names"])
    coordinates = ", ".join(f"{name} [{unit}]" for name, unit in zip(s["dof_names"], units))
    rates = s.get("prescribed_units") or {}
    prescribed = ", prescribed velocities " + ", ".join(
        f"{joint} = {number(omega, 6)} {rates.get(joint, '?/s')}" for joint, omega in s["prescribed"].items()
    ) if s["prescribed"] else ""
    elements = ", ".join(f"{e['kind']}({e.get('joint', e.get('frame', ''))})" for e in s["elements"]) or "none"
    return [
        f"  scene file: {s['source']}",
        f"  nq = {s['nq']}, nv = {s['nv']}, free joint coordinates n = {s['n']}: {coordinates}",
        f"  gravity = {_vector_text(s['gravity'], 6)} m/s^2{prescribed}",
        f"  elements: {elements}",
        "",
    ]


def _constraint_force_lines(eq: dict, precision: int) -> list[str]:
    """One line per constraint: the world-axes force (and torque) it applies on its frame."""
    lines = []
    for f in eq.get("constraint_forces") or ():
        torque = f"; torque {_vector_text(f['torque'], precision)} N m" if f.get("torque") is not None else ""
        lines.append(
            f"  constraint {f['constraint']!r} on {f['frame']!r}: force {_vector_text(f['force'], precision)} N"
            f"{torque} (world axes)"
        )
    return lines


def _equilibrium_lines(eq: dict, precision: int) -> list[str]:
    return [
        f"Equilibrium: {eq['method']}",
        f"  q = {_vector_text(eq['q'], precision)}",
        f"  residual = {_float(eq['residual']):.3e} (relative {_float(eq['relative_residual']):.2e}), "
        f"{plural(eq['iterations'], 'iteration')}, {eq['elapsed'] * 1e3:.2f} ms",
        *_constraint_force_lines(eq, precision),
        *(f"  note: {note}" for note in eq["notes"]),
        "",
    ]


def _force_unit(units: Sequence[str]) -> str:
    """The unit of generalized forces on coordinates of ``units``: N m on angles, N on lengths."""
    force = {"rad": "N m", "m": "N"}
    kinds = set(units)
    if len(kinds) == 1 and units[0] in force:
        return force[units[0]]
    return "N m on rad, N on m coordinates"


def _structure_text(structure: dict) -> str:
    return "  structure (eigenvalue signs -/0/+): " + "; ".join(
        f"{name}: " + ("zero" if d["kind"] == "zero" else f"{d['negative']}/{d['zero']}/{d['positive']}")
        for name, d in structure.items()
    )


def _linearization_lines(lin: dict, names: Sequence[str], units: Sequence[str], precision: int) -> list[str]:
    out = []
    if lin["balancing"] is not None:
        out += [
            "Operating point held by constant actuator forces (balancing, asked for explicitly)",
            f"  balancing forces = {_vector_text(lin['balancing'], BALANCING_PRECISION)} [{_force_unit(units)}]",
            "",
        ]
    zero = ", ".join(n for n in MATRIX_NAMES if n not in lin["nonzero"]) or "none"
    out.append("Linearized equations  M x'' + (D + G) x' + (S + N) x = f")
    out.append(f"  nonzero: {', '.join(lin['nonzero'])}; zero: {zero}")
    for name in lin["nonzero"]:
        out.append(matrix_text(name, np.array(lin[name], dtype=float), names, units, precision))
    out.append(_structure_text(lin["structure"]))
    out.append(f"  Pinocchio calls: {', '.join(lin['calls']) or 'none'}")
    if lin["dropped"]:
        out.append("  set to zero as rounding: " + ", ".join(f"{k} ({v:.1e} relative)" for k, v in lin["dropped"].items()))
    out += [f"  note: {note}" for note in lin["notes"]]
    out.append(f"  equilibrium residual (relative) = {_float(lin['residual']):.2e}; linearize {lin['elapsed'] * 1e3:.2f} ms")
    out.append("")
    return out


def _dominant(modes: dict, i: int) -> str:
    """Mode i's dominant coordinates with their energy shares (``Modes.dominant``), e.g. ``joint1 71%, joint2 29%``."""
    entries = modes.get("dominant") or []
    if i >= len(entries):
        return ""
    return ", ".join(f"{e['name']} {100 * _float(e['share']):.0f}%" for e in entries[i])


def mode_table(modes: dict, precision: int = 6, max_rows: int | None = None) -> str:
    """The mode table of a report's ``modes`` section: lam, |lam| in rad/s and Hz, zeta, eta, kappa, bound, multiplicity, kind,
    dominant coordinates (their share of the mode's energy).

    The verdict is not part of it (the report prints it once, in its own section).

    Parameters
    ----------
    modes : dict
        ``Modes.to_dict()`` (the report's ``modes`` section).
    precision : int
        Significant digits of lam and |lam|.
    max_rows : int, optional
        Show at most this many eigenvalues (the lowest frequencies); None for all.

    Examples
    --------
    >>> from pinlin.report.text import mode_table
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> modes = pinlin.modal_analysis(pinlin.linearize(pinlin.Scene(robot), np.zeros(2)))
    >>> table = mode_table(modes.to_dict(), precision=4, max_rows=2)
    >>> table.splitlines()[-2]
    '... 2 more (higher frequencies)'
    """
    re = [_float(x) for x in modes["eigenvalues"]["re"]]
    k = len(re)
    rows = range(k) if max_rows is None else range(min(k, max_rows))
    w = max(precision + _CELL_PADDING, len("Im lam [rad/s]"))
    head = (
        f"{'#':>4}  {'Re lam [1/s]':>{w}} {'Im lam [rad/s]':>{w}} {'|lam| [rad/s]':>{w}} {'|lam| [Hz]':>11} "
        f"{'zeta':>9} {'eta':>8} {'kappa':>8} {'bound':>8} {'mult':>4}  {'kind':<12} dominant coordinates"
    )
    method = f"{modes['method']}: {modes['method_reason']}" if modes.get("method_reason") else modes["method"]
    lines = [f"Modal analysis: {k} eigenvalues, method {method}", head, "-" * len(head)]
    for i in rows:
        bound = _float(modes["error_bound"][i])
        cells = [number(x, precision).rjust(w) for x in
                 (re[i], modes["eigenvalues"]["im"][i], modes["natural_frequency"][i])]
        size = _float(modes["natural_frequency"][i])
        cells.append(number(size / (2 * math.pi), 5).rjust(11))
        # zeta at the rounding level of lam (|Re lam| within its bound) prints as 0
        zeta_floor = bound / size if size > 0 else 0.0
        figures = [number(modes["damping_ratio"][i], 4, zero_below=zeta_floor).rjust(9)] + [
            f"{_float(modes[key][i]):>8.{_FIGURE_DIGITS}e}" for key in ("backward_error", "condition")
        ]
        lines.append(
            f"{i + 1:>4}  {' '.join(cells)} {' '.join(figures)} {bound:>8.{_FIGURE_DIGITS}e} "
            f"{modes['multiplicity'][i]:>4}  {modes['kind'][i]:<12} "
            f"{_dominant(modes, i)}".rstrip()
        )
    if len(rows) < k:
        lines.append(f"... {k - len(rows)} more (higher frequencies)")
    lines.append(f"max eta {_float(modes['error']):.2e}; dynamic stiffness simple: {modes['is_simple']}")
    lines += [f"note: {note}" for note in modes.get("notes", ())]
    return "\n".join(lines)


def _dissipation_lines(st: dict) -> list[str]:
    """The dissipation table of a marginal verdict (``Stability.dissipation``), one row per shape."""
    rows = st.get("dissipation") or []
    if not rows:
        return []
    lines = ["  small damping D = eps D1 (first-order rate d Re lam / d eps of the eigenvalues on the axis):"]
    for r in rows:
        says = {True: "destabilizes", False: "does not destabilize", None: "undecided"}[r["destabilizes"]]
        by = f" ({r['theorem']})" if r.get("theorem") else ""
        rate = number(r["rate"], 4, zero_below=_float(r["rate_error"]))
        lines.append(f"    {r['shape']}: {says}{by}; rate {rate} +- {_float(r['rate_error']):.1e}")
    return lines


def render_text(report: dict, precision: int = 6) -> str:
    """The human-readable report of a :func:`pinlin.report.analyze` document.

    Parameters
    ----------
    report : dict
        The JSON document (version :data:`pinlin.report.REPORT_VERSION`).
    precision : int
        Significant digits of the printed matrices, configuration and eigenvalues.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> report, _, _ = pinlin.report.analyze(load_scene(pinlin.data_path("scenes/double_pendulum.toml")))
    >>> text = pinlin.report.render_text(report, precision=4)
    >>> text.splitlines()[0]
    'pinlin ...: double_pendulum from .../double_pendulum.urdf'
    >>> "Stability: MARGINALLY STABLE" in text
    True
    """
    s = report["scene"]
    units = s.get("dof_units") or ["?"] * len(s["dof_names"])
    out = [f"pinlin {report['pinlin_version']}: {s['robot']} from {s['urdf']}", *_scene_lines(s)]
    if "equilibrium" in report:
        out += _equilibrium_lines(report["equilibrium"], precision)
    # the system's coordinates: the scene's free joints, or the independent ones of a constrained scene
    lin = report["linearization"]
    names = lin.get("dof_names") or s["dof_names"]
    unit_of = dict(zip(s["dof_names"], units))
    said = set(report.get("equilibrium", {}).get("notes", ()))  # a note both stages make is printed once
    lin = {**lin, "notes": [note for note in lin["notes"] if note not in said]}
    out += _linearization_lines(lin, names, [unit_of.get(n, "?") for n in names], precision)
    modes = report["modes"]
    out += [mode_table(modes, precision), f"  modal analysis {modes['elapsed'] * 1e3:.2f} ms", ""]
    st = report["stability"]
    out += [f"Stability: {st['kind'].replace('_', ' ').upper()}", f"  {st['reason']}", *_dissipation_lines(st), ""]
    out += energy_lines(report)
    out.append(f"Analysis {report['elapsed'] * 1e3:.1f} ms (equilibrium, linearization, modal analysis)")
    return "\n".join(out)
