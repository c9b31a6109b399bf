"""What ``pinlin analyze`` computes and its JSON document (theory: equilibrium, stability, error figures).

The document is made of the results' own ``to_dict()`` (docs/conventions.md):
each section is the dictionary of the result that the analysis returned, with a
few report-only additions (the scene, the nonzero matrices, the definiteness of
M, D, S, the text table of the modes).  :data:`~pinlin.report.schema.REPORT_SCHEMA`
describes it.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from ..errors import (
    ConfigurationError,
    ConstraintError,
    InputError,
    NotAnEquilibriumError,
    ParameterError,
    PrescribedJointError,
    SceneFileError,
    SingularMassError,
    TimePeriodicError,
)
from ..linearization.equilibrium import find_equilibrium
from ..linearization.linearize import linearize
from ..model.scene_file import SceneSpec
from ..results import to_jsonable
from ..spectral import Modes, modal_analysis
from ..version import __version__
from .energy import energy_section
from .schema import REPORT_VERSION
from .text import mode_table
from .units import coordinate_units

__all__ = ["analyze", "scene_section", "matrix_structure", "normalized_path", "blame"]

#: The symmetric matrices whose definiteness the report gives (G and N are skew: no definiteness).
STRUCTURE_MATRICES = ("M", "D", "S")


def normalized_path(source: str) -> str:
    """An existing file as its absolute path without ``..`` or symbolic links; anything else
    (``example:ur5``, a URDF given as a string) unchanged.

    Examples
    --------
    >>> from pinlin.report.document import normalized_path
    >>> normalized_path("example:ur5")
    'example:ur5'
    >>> urdf = pinlin.data_path("urdf/double_pendulum.urdf")
    >>> normalized_path(str(urdf.parent / ".." / "urdf" / urdf.name)) == str(urdf.resolve())
    True
    """
    try:
        path = Path(source)
        return str(path.resolve()) if path.is_file() else source
    except (OSError, ValueError):  # a name too long or with a NUL byte is no file
        return source


def scene_section(spec: SceneSpec) -> dict[str, Any]:
    """The scene as JSON-serializable data: robot, sizes, units, gravity, prescribed joints, elements.

    File paths are normalized (:func:`normalized_path`); ``dof_units`` gives the
    unit of each free coordinate ("rad", "m"; see :mod:`pinlin.report.units`).
    Each element is its own fields (``to_jsonable`` of the element) with its
    scene-file ``kind``; ``prescribed_units`` the unit of each prescribed
    velocity ("rad/s" for a revolute joint, "m/s" for a prismatic one).

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> section = pinlin.report.scene_section(load_scene(pinlin.data_path("scenes/double_pendulum.toml")))
    >>> section["dof_names"], section["dof_units"], [e["kind"] for e in section["elements"]]
    (['joint1', 'joint2'], ['rad', 'rad'], ['spring', 'spring', 'follower'])
    """
    scene = spec.scene
    robot = scene.robot
    return {
        "source": normalized_path(spec.path),
        "robot": robot.name,
        "urdf": normalized_path(robot.source),
        "nq": robot.nq,
        "nv": robot.nv,
        "n": scene.n,
        "dof_names": list(scene.dof_names),
        "dof_units": list(coordinate_units(robot, scene.free_dofs)),
        "gravity": to_jsonable(scene.gravity),
        "prescribed": to_jsonable(dict(scene.prescribed)),
        "prescribed_units": {joint: f"{coordinate_units(robot, [robot.joint(joint).idx_v])[0]}/s"
                             for joint in scene.prescribed},
        "elements": [{"kind": element.kind, **to_jsonable(element)} for element in scene.elements],
    }


def matrix_structure(modes: Modes) -> dict[str, Any]:
    """Definiteness and inertia of M, D and S, with the numbers behind each decision.

    One decision for everyone: these are the decisions the stability verdict
    used (``modes.structure.definiteness_M``, ``_D``, ``_S``, made by
    :func:`pinlin.numerics.definiteness` against the rounding bound of the data
    and ``modes.structure.uncertainty``), so the report cannot disagree with
    ``modes.structure`` (theory: stability).

    Parameters
    ----------
    modes : Modes
        The modal analysis of a :class:`~pinlin.LinearizedSystem`.

    Raises
    ------
    ParameterError
        ``modes`` was computed from plain coefficient matrices (no mechanical
        split, so no definiteness of M, D, S).

    Examples
    --------
    >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    >>> modes = pinlin.modal_analysis(pinlin.linearize(pinlin.Scene(robot), np.zeros(2)))
    >>> structure = pinlin.report.matrix_structure(modes)
    >>> {name: decision["kind"] for name, decision in structure.items()}
    {'M': 'positive_definite', 'D': 'zero', 'S': 'positive_definite'}
    """
    facts = modes.structure
    decisions = {name: getattr(facts, f"definiteness_{name}", None) for name in STRUCTURE_MATRICES}
    missing = [name for name, decision in decisions.items() if decision is None]
    if missing:
        raise ParameterError("modes", f"has no definiteness of {', '.join(missing)}: analyse a LinearizedSystem")
    return {name: decision.to_dict() for name, decision in decisions.items()}


#: What a scene-file user changes for each error of the analyses: the key to blame and a hint.
_BLAME = (
    (NotAnEquilibriumError, "start", "set equilibrium = true to search one from q, or balancing = true to hold q"),
    (ConfigurationError, "start", ""),
    (SingularMassError, "robot", ""),
    (PrescribedJointError, "prescribed", ""),
    (ConstraintError, "constraint", ""),
)


def blame(spec: SceneSpec, exc: InputError) -> InputError:
    """``exc``, raised by an analysis of a scene read from a file, as a :class:`~pinlin.SceneFileError`
    naming that file and the key that caused it, so that the user knows what to edit.

    A time-periodic scene blames ``prescribed.<joint>``, a start that is no
    equilibrium ``start``, a singular mass ``robot`` (its URDF), constraints
    ``constraint``; other input errors name the file only.  A spec that did not
    come from a file (``--example``) keeps ``exc`` as it is (returned unchanged).

    Examples
    --------
    >>> from pinlin.report.document import blame
    >>> from pinlin.model.scene_file import load_scene
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum.toml"))
    >>> error = blame(spec, pinlin.SingularMassError("M is singular", ["joint2"]))
    >>> type(error).__name__, error.key
    ('SceneFileError', 'robot')
    """
    if isinstance(exc, SceneFileError) or not Path(spec.path).is_file():
        return exc
    key, hint = None, ""
    if isinstance(exc, TimePeriodicError):
        key, hint = f"prescribed.{exc.joint}", ("its coefficients are periodic: pinlin.periodic_orbit and "
                                                  "pinlin.floquet_analysis analyse it")
    else:
        for kind, blamed, why in _BLAME:
            if isinstance(exc, kind):
                key, hint = blamed, why
                break
    return SceneFileError(f"{exc}" + (f" ({hint})" if hint else ""), spec.path, key)


def analyze(spec: SceneSpec):
    """Run equilibrium, linearization and modal analysis on a scene spec; build the report.

    The equilibrium is searched only when the spec asks for it (``[start]
    equilibrium = true``); the linearization uses the spec's ``balancing``.

    Parameters
    ----------
    spec : SceneSpec
        A scene with its starting point (:func:`pinlin.model.scene_file.load_scene`).

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
    SceneFileError
        For a spec read from a file, what the analyses refuse as bad input (a
        start that is no equilibrium while the spec asked neither for a search
        nor for balancing, a time-periodic scene, a singular mass, ...), naming
        the file and the key (:func:`blame`).
    PinlinError
        Anything else the analyses refuse (see :func:`pinlin.find_equilibrium`,
        :func:`pinlin.linearize`, :func:`pinlin.modal_analysis`); input errors
        of a spec that did not come from a file keep their own type.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> report, sys_, modes = pinlin.report.analyze(load_scene(pinlin.data_path("scenes/double_pendulum.toml")))
    >>> report["stability"]["kind"], report["modes"]["kind"]
    ('marginally_stable', ['undamped', 'undamped', 'undamped', 'undamped'])
    >>> sys_.n, len(modes.eigenvalues)
    (2, 4)
    """
    try:
        return _analyze(spec)
    except InputError as exc:
        error = blame(spec, exc)
        if error is exc:
            raise
        raise error from exc


def _analyze(spec: SceneSpec):
    """:func:`analyze` without the blame."""
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
    report["modes"] = {**modes.to_dict(), "method_reason": modes.method.reason}
    report["modes"]["table"] = mode_table(report["modes"])
    report["stability"] = modes.stability.to_dict()
    report["energy"] = energy_section(modes, spec.scene)
    report["elapsed"] = time.perf_counter() - t0
    return report, sys_, modes
