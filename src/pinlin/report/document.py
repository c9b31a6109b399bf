"""What ``pinlin analyze`` computes and its JSON document (SPEC sections 3-5 and 8).

The document is made of the results' own ``to_dict()`` (docs/conventions.md):
each section is the dictionary of the result that the analysis returned, with a
few report-only additions (the scene, the nonzero matrices, the definiteness of
M, D, S, the text table of the modes).  :data:`~pinlin.report.schema.REPORT_SCHEMA`
describes it.
"""

from __future__ import annotations

import time
from typing import Any

from .. import __version__
from ..errors import ParameterError
from ..linearization.equilibrium import find_equilibrium
from ..linearization.linearize import linearize
from ..model.scenefile import SceneSpec
from ..results import to_jsonable
from ..spectral import Modes, modal_analysis
from .schema import REPORT_VERSION

__all__ = ["analyze", "scene_section", "matrix_structure"]

#: The symmetric matrices whose definiteness the report gives (G and N are skew: no definiteness).
STRUCTURE_MATRICES = ("M", "D", "S")


def scene_section(spec: SceneSpec) -> dict[str, Any]:
    """The scene as JSON-serializable data: robot, sizes, gravity, prescribed joints, elements.

    Each element is its own fields (``to_jsonable`` of the element) with its
    scene-file ``kind``.
    """
    scene = spec.scene
    robot = scene.robot
    return {
        "source": spec.path,
        "robot": robot.name,
        "urdf": robot.source,
        "nq": robot.nq,
        "nv": robot.nv,
        "n": scene.n,
        "dof_names": list(scene.dof_names),
        "gravity": to_jsonable(scene.gravity),
        "prescribed": to_jsonable(dict(scene.prescribed)),
        "elements": [{"kind": element.kind, **to_jsonable(element)} for element in scene.elements],
    }


def matrix_structure(modes: Modes) -> dict[str, Any]:
    """Definiteness and inertia of M, D and S, with the numbers behind each decision.

    One decision for everyone: these are the decisions the stability verdict
    used (``modes.structure.definiteness_M``, ``_D``, ``_S``, made by
    :func:`pinlin.numerics.definiteness` against the rounding bound of the data
    and ``modes.structure.uncertainty``), so the report cannot disagree with
    ``modes.structure`` (SPEC section 5).

    Parameters
    ----------
    modes : Modes
        The modal analysis of a :class:`~pinlin.LinearizedSystem`.

    Raises
    ------
    ParameterError
        ``modes`` was computed from plain coefficient matrices (no mechanical
        split, so no definiteness of M, D, S).
    """
    facts = modes.structure
    decisions = {name: getattr(facts, f"definiteness_{name}", None) for name in STRUCTURE_MATRICES}
    missing = [name for name, decision in decisions.items() if decision is None]
    if missing:
        raise ParameterError("modes", f"has no definiteness of {', '.join(missing)}: analyse a LinearizedSystem")
    return {name: decision.to_dict() for name, decision in decisions.items()}


def analyze(spec: SceneSpec):
    """Run equilibrium, linearization and modal analysis on a scene spec; build the report.

    The equilibrium is searched only when the spec asks for it (``[start]
    equilibrium = true``); the linearization uses the spec's ``balancing``.

    Parameters
    ----------
    spec : SceneSpec
        A scene with its starting point (:func:`pinlin.model.scenefile.load_scene`).

    Returns
    -------
    report : dict
        The JSON-serializable document (:data:`~pinlin.report.schema.REPORT_SCHEMA`).
    sys_ : LinearizedSystem
    modes : Modes

    Raises
    ------
    ConvergenceError
        Newton found no equilibrium from the start.
    NotAnEquilibriumError
        The start is no equilibrium and the spec asked neither for a search nor for balancing.
    PinlinError
        Anything else the analyses refuse (see :func:`pinlin.find_equilibrium`,
        :func:`pinlin.linearize`, :func:`pinlin.modal_analysis`).
    """
    t0 = time.perf_counter()
    report: dict[str, Any] = {
        "report_version": REPORT_VERSION,
        "pinlin_version": __version__,
        "scene": scene_section(spec),
    }
    q = spec.q0
    if spec.equilibrium:
        eq = find_equilibrium(spec.scene, q)
        q = eq.q
        report["equilibrium"] = eq.to_dict()
    sys_ = linearize(spec.scene, q, balancing=spec.balancing)
    modes = modal_analysis(sys_)
    report["linearization"] = {
        **sys_.to_dict(),
        "nonzero": list(sys_.nonzero),
        "structure": matrix_structure(modes),
    }
    report["modes"] = {
        **modes.to_dict(),
        "method_reason": modes.method.reason,
        "table": modes.table(max_rows=None),
    }
    report["stability"] = modes.stability.to_dict()
    report["elapsed"] = time.perf_counter() - t0
    return report, sys_, modes
