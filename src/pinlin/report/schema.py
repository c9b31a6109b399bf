"""The JSON Schema of the ``pinlin analyze --json`` report: the published contract.

Version 2 (pinlin 0.2) builds every section that has a result object from that
object's ``to_dict()`` (docs/conventions.md), so the sections carry the result
convention's ``type``, ``method``, ``error`` and ``elapsed``:

- ``equilibrium`` is :class:`~pinlin.EquilibriumResult`'s dictionary;
- ``linearization`` is :class:`~pinlin.LinearizedSystem`'s (the matrices M, D, G,
  S, N at its top level, ``residual`` the relative equilibrium residual) plus
  ``nonzero`` and ``structure`` (the definiteness of M, D, S that
  ``modes.structure`` holds, made by :func:`pinlin.numerics.definiteness`);
- ``modes`` is :class:`~pinlin.Modes`' (eigenvalues as ``{"re": [...], "im": [...]}``)
  plus ``method_reason`` and the text ``table``;
- ``stability`` is :class:`~pinlin.Stability`'s;
- ``scene.dof_units`` (added in pinlin 0.2, optional in the schema) gives the unit
  of each coordinate, "rad" or "m" ("?" for a joint kind pinlin does not know);
  ``scene.prescribed_units`` (pinlin 0.3, optional) that of each prescribed velocity, "rad/s" or "m/s";
  ``scene.source`` and ``scene.urdf`` are normalized absolute paths when they name files.

Numbers follow :func:`pinlin.results.to_jsonable`: non-finite floats are the
strings ``"nan"``, ``"inf"``, ``"-inf"`` (version 1 wrote ``null``).

Version 1 (pinlin 0.1) had hand-built sections: ``linearization.matrices``,
``linearization.relative_residual``, ``modes.eigenvalues_real`` and
``modes.eigenvalues_imag``, ``modes.max_backward_error``.
"""

from __future__ import annotations

from ..linearization.system import MATRIX_NAMES
from ..numerics.definiteness import DEFINITENESS_KINDS
from ..spectral.stability import KINDS

__all__ = ["REPORT_SCHEMA", "REPORT_VERSION"]

#: Version of the report's layout; bumped whenever a key changes name or meaning.
REPORT_VERSION = 2

_NONFINITE = {"enum": ["nan", "inf", "-inf"]}
_FLOAT = {"anyOf": [{"type": "number"}, _NONFINITE]}
_FLOATS = {"type": "array", "items": _FLOAT}
_NUMBERS = {"type": "array", "items": {"type": "number"}}
_MATRIX = {"type": "array", "items": _NUMBERS}
_COMPLEX_ARRAY = {"type": "object", "required": ["re", "im"], "properties": {"re": _FLOATS, "im": _FLOATS}}


def _result(required: list[str], properties: dict) -> dict:
    """A section made by a result's ``to_dict()``: the convention's keys, then the result's own."""
    return {
        "type": "object",
        "required": ["type", "method", "error", "elapsed", *required],
        "properties": {
            "type": {"type": "string"},
            "method": {"type": "string", "minLength": 1},
            "error": {"anyOf": [{"type": "number"}, {"type": "null"}, _NONFINITE]},
            "elapsed": {"type": "number", "minimum": 0},
            **properties,
        },
    }


_DEFINITENESS = {
    "type": "object",
    "required": ["kind", "negative", "zero", "positive", "min_eigenvalue", "max_eigenvalue", "tol", "threshold"],
    "properties": {
        "kind": {"enum": list(DEFINITENESS_KINDS)},
        "negative": {"type": "integer", "minimum": 0},
        "zero": {"type": "integer", "minimum": 0},
        "positive": {"type": "integer", "minimum": 0},
    },
}

#: JSON Schema (draft 2020-12) of the ``--json`` report, version :data:`REPORT_VERSION`.
REPORT_SCHEMA = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": f"pinlin analyze report, version {REPORT_VERSION}",
    "type": "object",
    "required": ["report_version", "pinlin_version", "scene", "linearization", "modes", "stability", "elapsed"],
    "properties": {
        "report_version": {"const": REPORT_VERSION},
        "pinlin_version": {"type": "string"},
        "elapsed": {"type": "number", "minimum": 0},
        "scene": {
            "type": "object",
            "required": ["source", "robot", "urdf", "nq", "nv", "n", "dof_names", "gravity", "prescribed", "elements"],
            "properties": {
                "nq": {"type": "integer", "minimum": 1},
                "nv": {"type": "integer", "minimum": 1},
                "n": {"type": "integer", "minimum": 1},
                "dof_names": {"type": "array", "items": {"type": "string"}},
                "dof_units": {"type": "array", "items": {"enum": ["rad", "m", "?"]}},
                "gravity": {**_NUMBERS, "minItems": 3, "maxItems": 3},
                "prescribed": {"type": "object", "additionalProperties": {"type": "number"}},
                "prescribed_units": {"type": "object", "additionalProperties": {"enum": ["rad/s", "m/s", "?/s"]}},
                "elements": {"type": "array", "items": {"type": "object", "required": ["kind"]}},
            },
        },
        "equilibrium": _result(
            ["q", "residual", "relative_residual", "iterations", "notes"],
            {"q": _NUMBERS, "residual": {"type": "number"}, "iterations": {"type": "integer", "minimum": 0}},
        ),
        "linearization": _result(
            [*MATRIX_NAMES, "dof_names", "q", "residual", "balancing", "calls", "dropped", "notes", "nonzero",
             "structure"],
            {
                **{name: _MATRIX for name in MATRIX_NAMES},
                "nonzero": {"type": "array", "items": {"enum": list(MATRIX_NAMES)}},
                "calls": {"type": "array", "items": {"type": "string"}},
                "balancing": {"oneOf": [{"type": "null"}, _NUMBERS]},
                "structure": {
                    "type": "object",
                    "required": ["M", "D", "S"],
                    "additionalProperties": _DEFINITENESS,
                },
            },
        ),
        "modes": _result(
            ["eigenvalues", "natural_frequency", "damping_ratio", "backward_error", "condition", "error_bound",
             "multiplicity", "kind", "is_simple", "method_reason", "table"],
            {
                "eigenvalues": _COMPLEX_ARRAY,
                "natural_frequency": _FLOATS,
                "damping_ratio": _FLOATS,
                "backward_error": _FLOATS,
                "condition": _FLOATS,
                "error_bound": _FLOATS,
                "multiplicity": {"type": "array", "items": {"type": "integer", "minimum": 1}},
                "kind": {"type": "array", "items": {"type": "string"}},
                "is_simple": {"type": "boolean"},
                "method_reason": {"type": "string"},
                "table": {"type": "string"},
            },
        ),
        "stability": _result(["kind", "reason"], {"kind": {"enum": list(KINDS)}, "reason": {"type": "string"}}),
    },
}
