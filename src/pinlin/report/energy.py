"""The energy section of the ``pinlin analyze`` report: for each mode, where its energy lives.

:func:`energy_section` gives the report's ``energy`` list, one entry per mode (each
eigenvalue with Im lam >= 0; a conjugate partner has the same shares): the mode's
number in the mode table (1-based), its frequency, the dominant body (largest kinetic
share) and dominant element (largest strain share among the elements), and the three
share tables of :meth:`pinlin.Modes.energy`.  :func:`energy_lines` prints it.
:data:`ENERGY_SCHEMA` is the JSON Schema of the section (optional in the report).
"""

from __future__ import annotations

from typing import Any

from ..spectral.energy import mode_energy

__all__ = ["energy_section", "energy_lines", "ENERGY_SCHEMA"]

_SHARES = {"type": "object", "additionalProperties": {"type": "number"}}
#: JSON Schema of the report's ``energy`` section.
ENERGY_SCHEMA = {
    "type": "array",
    "items": {
        "type": "object",
        "required": ["mode", "frequency_hz", "dominant_body", "dominant_element", "kinetic", "strain", "dissipation"],
        "properties": {
            "mode": {"type": "integer", "minimum": 1},
            "frequency_hz": {"type": "number", "minimum": 0},
            "dominant_body": {"type": ["string", "null"]},
            "dominant_element": {"type": ["string", "null"]},
            "kinetic": _SHARES,
            "strain": _SHARES,
            "dissipation": _SHARES,
        },
    },
}


def energy_section(modes, scene) -> list[dict[str, Any]]:
    """One entry per mode of ``modes`` (analysed from ``scene``'s linearization), see the module docstring.

    Raises
    ------
    ParameterError
        ``scene`` is not the scene of the analysed system (:func:`pinlin.spectral.energy.mode_energy`).

    Examples
    --------
    >>> from pinlin.report.energy import energy_section
    >>> from pinlin.model.scene_file import load_scene
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum.toml"))
    >>> modes = pinlin.modal_analysis(pinlin.linearize(spec.scene, spec.q0))
    >>> first = energy_section(modes, spec.scene)[0]
    >>> first["mode"], first["dominant_body"], first["dominant_element"]
    (1, 'link2', 'spring joint1')
    """
    out = []
    for k, lam in enumerate(modes.eigenvalues):
        if lam.imag < 0:
            continue
        energy = mode_energy(modes, k, scene)
        out.append({
            "mode": k + 1,
            "frequency_hz": float(modes.frequency_hz[k]),
            "dominant_body": energy.dominant_body,
            "dominant_element": energy.dominant_element,
            "kinetic": dict(energy.kinetic),
            "strain": dict(energy.strain),
            "dissipation": dict(energy.dissipation),
        })
    return out


def energy_lines(report: dict) -> list[str]:
    """The report's ``energy`` section as text: per mode its dominant body and element with their shares.

    Examples
    --------
    >>> from pinlin.report.energy import energy_lines
    >>> from pinlin.model.scene_file import load_scene
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum.toml"))
    >>> report, _, _ = pinlin.report.analyze(spec)
    >>> print(energy_lines(report)[1])
         1     0.632889 Hz  body link2 84%                 element spring joint1 15%
    """
    entries = report.get("energy")
    if not entries:
        return []
    lines = ["Energy by mode (dominant body: kinetic share; dominant element: strain share)"]
    for e in entries:
        body, element = e["dominant_body"], e["dominant_element"]
        body_text = f"{body} {_percent(e['kinetic'][body])}" if body is not None else "-"
        element_text = f"{element} {_percent(e['strain'][element])}" if element is not None else "-"
        lines.append(f"  {e['mode']:>4}  {e['frequency_hz']:>11.6g} Hz  body {body_text:<24}  element {element_text}")
    lines.append("")
    return lines


def _percent(share: float) -> str:
    text = f"{100 * share:.0f}%"
    return "0%" if text == "-0%" else text
