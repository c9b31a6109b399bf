"""The JSON document of ``pinlin sweep --json`` (schema :data:`~pinlin.report.sweep.schema.SWEEP_SCHEMA`).

Built from the results' own ``to_dict()`` where a result exists (the tracked
modes, each boundary's :class:`~pinlin.CriticalParameter`) and compact per-point
records otherwise (a point's eigenvalues, verdict and headline error, not its
full :class:`~pinlin.Modes`, whose eigenvectors would dominate the file).
"""

from __future__ import annotations

from typing import Any

from ...results import to_jsonable
from ...spectral import Modes
from ...version import __version__
from ..document import scene_section
from .run import SweepOutcome, headline
from .schema import SWEEP_VERSION

__all__ = ["sweep_document"]


def _point(point: dict[str, float], value) -> dict[str, Any]:
    if isinstance(value, Modes):
        return {
            "values": to_jsonable(list(point.values())),
            "verdict": value.stability.kind,
            "error": to_jsonable(value.error),
            "eigenvalues": to_jsonable(value.eigenvalues),
            "error_bound": to_jsonable(value.error_bound),
            "failure": None,
        }
    return {"values": to_jsonable(list(point.values())), "verdict": "failed", "error": None, "eigenvalues": None,
            "error_bound": None, "failure": f"{type(value.exception).__name__}: {value.exception}"}


def _change(change) -> dict[str, Any]:
    return {
        "between": list(change.between),
        "verdicts": list(change.verdicts),
        "second": change.second,
        "boundary": None if change.boundary is None else change.boundary.to_dict(),
        "failure": change.failure,
    }


def sweep_document(outcome: SweepOutcome) -> dict[str, Any]:
    """The JSON-serializable document of a sweep (``json.dumps(..., allow_nan=False)`` works).

    Keys: ``sweep_version``, ``pinlin_version``, ``scene`` (as in the analyze
    report), ``parameters`` (path, unit, values), ``points`` (grid order, the
    last parameter varying fastest), ``tracked`` (one parameter: the
    :class:`~pinlin.studies.TrackedModes` dictionary and ``values``, the
    parameter values of its rows), ``changes`` (verdict changes and their
    boundaries), ``method``, ``error`` (the largest backward error of the points),
    ``notes`` and ``elapsed``.

    Examples
    --------
    >>> import json
    >>> from pinlin.report.sweep.document import sweep_document
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> doc = sweep_document(run_sweep(plan))
    >>> len(doc["points"]), len(json.dumps(doc, allow_nan=False)) > 0
    (4, True)
    """
    plan = outcome.plan
    tracked = None
    if outcome.tracked is not None:
        tracked = {**outcome.tracked.to_dict(), "values": to_jsonable(outcome.tracked_values)}
    return {
        "sweep_version": SWEEP_VERSION,
        "pinlin_version": __version__,
        "scene": scene_section(plan.spec),
        "parameters": [{"path": p.path, "unit": p.unit, "values": to_jsonable(p.values)} for p in plan.parameters],
        "points": [_point(point, value) for point, value in zip(outcome.result.points, outcome.result.values)],
        "tracked": tracked,
        "changes": [_change(c) for c in outcome.changes],
        "method": outcome.result.method + ("; boundaries by critical_parameter" if plan.boundaries else ""),
        "error": to_jsonable(headline(outcome.result.values)),
        "notes": list(outcome.notes),
        "elapsed": outcome.elapsed,
    }
