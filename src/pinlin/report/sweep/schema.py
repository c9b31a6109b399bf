"""The JSON Schema of the ``pinlin sweep --json`` document: the published contract, version 1."""

from __future__ import annotations

from ...spectral.stability import KINDS
from ..schema import REPORT_SCHEMA

__all__ = ["SWEEP_SCHEMA", "SWEEP_VERSION"]

#: Version of the sweep document's layout; bumped whenever a key changes name or meaning.
SWEEP_VERSION = 1

_NONFINITE = {"enum": ["nan", "inf", "-inf"]}
_FLOAT = {"anyOf": [{"type": "number"}, _NONFINITE]}
_FLOATS = {"type": "array", "items": _FLOAT}
_COMPLEX_ARRAY = {"type": "object", "required": ["re", "im"], "properties": {"re": _FLOATS, "im": _FLOATS}}
_NULLABLE_FLOAT = {"anyOf": [{"type": "null"}, *_FLOAT["anyOf"]]}
_VERDICT = {"enum": [*KINDS, "failed"]}

_POINT = {
    "type": "object",
    "required": ["values", "verdict", "error", "eigenvalues", "error_bound", "failure"],
    "properties": {
        "values": {"type": "array", "items": {"type": "number"}, "minItems": 1, "maxItems": 2},
        "verdict": _VERDICT,
        "error": _NULLABLE_FLOAT,
        "eigenvalues": {"oneOf": [{"type": "null"}, _COMPLEX_ARRAY]},
        "error_bound": {"oneOf": [{"type": "null"}, _FLOATS]},
        "failure": {"type": ["string", "null"]},
    },
}

_BOUNDARY = {
    "type": "object",
    "required": ["type", "method", "error", "elapsed", "value", "kind", "mechanism", "eigenvalue", "error_bound",
                 "bracket", "verdicts", "verified"],
    "properties": {
        "type": {"const": "CriticalParameter"},
        "value": {"type": "number"},
        "kind": {"enum": ["divergence", "flutter"]},
        "error_bound": _FLOAT,
        "verified": {"type": "boolean"},
    },
}

_CHANGE = {
    "type": "object",
    "required": ["between", "verdicts", "second", "boundary", "failure"],
    "properties": {
        "between": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
        "verdicts": {"type": "array", "items": _VERDICT, "minItems": 2, "maxItems": 2},
        "second": {"type": ["number", "null"]},
        "boundary": {"oneOf": [{"type": "null"}, _BOUNDARY]},
        "failure": {"type": ["string", "null"]},
    },
}

#: JSON Schema (draft 2020-12) of the ``pinlin sweep --json`` document, version :data:`SWEEP_VERSION`.
SWEEP_SCHEMA = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": f"pinlin sweep document, version {SWEEP_VERSION}",
    "type": "object",
    "required": ["sweep_version", "pinlin_version", "scene", "parameters", "points", "tracked", "changes", "method",
                 "error", "notes", "elapsed"],
    "properties": {
        "sweep_version": {"const": SWEEP_VERSION},
        "pinlin_version": {"type": "string"},
        "scene": REPORT_SCHEMA["properties"]["scene"],
        "parameters": {
            "type": "array",
            "minItems": 1,
            "maxItems": 2,
            "items": {
                "type": "object",
                "required": ["path", "unit", "values"],
                "properties": {"path": {"type": "string"}, "unit": {"type": "string"},
                               "values": {"type": "array", "items": {"type": "number"}, "minItems": 1}},
            },
        },
        "points": {"type": "array", "items": _POINT, "minItems": 1},
        "tracked": {"oneOf": [{"type": "null"}, {
            "type": "object",
            "required": ["type", "eigenvalues", "error", "values"],
            "properties": {"type": {"const": "TrackedModes"}, "values": {"type": "array", "items": {"type": "number"}}},
        }]},
        "changes": {"type": "array", "items": _CHANGE},
        "method": {"type": "string", "minLength": 1},
        "error": _NULLABLE_FLOAT,
        "notes": {"type": "array", "items": {"type": "string"}},
        "elapsed": {"type": "number", "minimum": 0},
    },
}
