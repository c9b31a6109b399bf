"""What ``pinlin sweep`` computes: the modes at every point, tracked, the verdicts and their boundaries.

Every point is analysed as ``pinlin analyze`` analyses a scene (theory: equilibrium, stability): the equilibrium from the spec's start when it asks for one, the
linearization, the modal analysis.  Over one parameter the modes are tracked by
shape (:func:`pinlin.studies.track_modes`); wherever the verdict changes class
between two neighbouring points (stable, divergence, flutter) the exact
parameter value is found by :func:`pinlin.critical_parameter` between them
(theory: boundaries).  Over two parameters (a stability map) the boundaries are
found along the first parameter at each value of the second.  Points where the
scene has no equilibrium or is refused are recorded, with their error, never
dropped.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...boundaries import CriticalParameter, critical_parameter
from ...errors import PinlinError
from ...linearization.equilibrium import find_equilibrium
from ...linearization.linearize import linearize
from ...linearization.system import LinearizedSystem
from ...spectral import Modes, modal_analysis
from ...studies import SweepFailure, SweepResult, TrackedModes, sweep, track_modes
from .parameters import SweepPlan

__all__ = ["SweepOutcome", "VerdictChange", "run_sweep", "system_at", "VERDICT_CLASSES"]

#: The class of each stability verdict: a boundary lies between points of different classes
#: (asymptotic and marginal stability are one class; "undecided" has none).
VERDICT_CLASSES = {"asymptotically_stable": "stable", "marginally_stable": "stable", "divergence": "divergence",
                   "flutter": "flutter"}


@dataclass
class VerdictChange:
    """Two neighbouring points of the first parameter whose verdicts differ in class, and the boundary between.

    Attributes
    ----------
    between : (float, float)
        The two values of the first parameter.
    verdicts : (str, str)
        The verdicts there.
    second : float or None
        The second parameter's value (a stability map), else None.
    boundary : CriticalParameter or None
        From :func:`pinlin.critical_parameter` (None when not asked for, or when it failed).
    failure : str or None
        Why no boundary was found (the error of ``critical_parameter``).

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> change = run_sweep(plan).changes[0]
    >>> change.between, change.verdicts, round(change.boundary.value, 6)
    ((10.0, 20.0), ('marginally_stable', 'flutter'), 16.432898)
    """

    between: tuple[float, float]
    verdicts: tuple[str, str]
    second: float | None = None
    boundary: CriticalParameter | None = None
    failure: str | None = None


@dataclass
class SweepOutcome:
    """Everything ``pinlin sweep`` computed.

    Attributes
    ----------
    plan : SweepPlan
    result : SweepResult
        ``values`` are :class:`~pinlin.Modes` or :class:`~pinlin.studies.SweepFailure`, in grid order.
    verdicts : ndarray of str
        ``plan.shape``: each point's verdict, "failed" where the point failed.
    tracked : TrackedModes or None
        One parameter: the modes of the points that succeeded, tracked by shape.
    tracked_values : ndarray or None
        The parameter values of ``tracked``'s rows.
    changes : list of VerdictChange
    elapsed : float
        Wall time [s] of the whole sweep, boundaries included.
    notes : list of str

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> outcome = run_sweep(plan)
    >>> len(outcome.changes), outcome.tracked.eigenvalues.shape
    (1, (4, 4))
    """

    plan: SweepPlan
    result: SweepResult
    verdicts: np.ndarray
    tracked: TrackedModes | None
    tracked_values: np.ndarray | None
    changes: list[VerdictChange]
    elapsed: float
    notes: list[str] = field(default_factory=list)

    @property
    def modes(self) -> list[Modes | SweepFailure]:
        return self.result.values


def system_at(plan: SweepPlan, values) -> LinearizedSystem:
    """The linearized system of the scene at parameter ``values``, analysed as ``pinlin analyze`` does.

    Raises
    ------
    PinlinError
        The scene refuses the values, no equilibrium is found, or the linearization fails.

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> from pinlin.report.sweep.run import system_at
    >>> system_at(plan, [5.0]).nonzero
    ('M', 'S', 'N')
    """
    spec = plan.spec
    scene = plan.scene_at(values)
    q = spec.q0
    if spec.equilibrium:
        q = find_equilibrium(scene, q).q
    return linearize(scene, q, balancing=spec.balancing)


def _point(plan: SweepPlan):
    names = [p.path for p in plan.parameters]

    def analyse(**point: float) -> Modes:
        return modal_analysis(system_at(plan, [point[name] for name in names]))

    analyse.__name__ = "analyse"
    return analyse


def _verdicts(values: list, shape: tuple[int, ...]) -> np.ndarray:
    kinds = [v.stability.kind if isinstance(v, Modes) else "failed" for v in values]
    return np.array(kinds, dtype=object).reshape(shape)


def _track(plan: SweepPlan, values: list, notes: list[str]) -> tuple[TrackedModes | None, np.ndarray | None]:
    ok = [i for i, v in enumerate(values) if isinstance(v, Modes)]
    if len(ok) < len(values):
        notes.append(f"{len(values) - len(ok)} of {len(values)} points failed; the modes are tracked over the others")
    if not ok:
        return None, None
    lam = np.array([values[i].eigenvalues for i in ok])
    vectors = np.array([values[i].right for i in ok])
    return track_modes(lam, vectors), plan.parameters[0].values[ok]


def _boundary(plan: SweepPlan, lo: float, hi: float, second: float | None) -> CriticalParameter:
    def func(p: float) -> LinearizedSystem:
        return system_at(plan, [p] if second is None else [p, second])

    return critical_parameter(func, (min(lo, hi), max(lo, hi)))


def _changes(plan: SweepPlan, verdicts: np.ndarray, notes: list[str]) -> list[VerdictChange]:
    """The verdict changes along the first parameter (at each value of the second), with their boundaries."""
    p1 = plan.parameters[0].values
    rows = [(None, verdicts)] if verdicts.ndim == 1 else [
        (float(y), verdicts[:, j]) for j, y in enumerate(plan.parameters[1].values)]
    out = []
    for second, row in rows:
        for i in range(len(p1) - 1):
            a, b = VERDICT_CLASSES.get(row[i]), VERDICT_CLASSES.get(row[i + 1])
            if a is None or b is None or a == b:
                continue
            change = VerdictChange((float(p1[i]), float(p1[i + 1])), (str(row[i]), str(row[i + 1])), second)
            if plan.boundaries:
                try:
                    change.boundary = _boundary(plan, p1[i], p1[i + 1], second)
                except PinlinError as exc:
                    change.failure = f"{type(exc).__name__}: {exc}"
            out.append(change)
    undecided = int(np.sum(verdicts == "undecided"))
    if undecided:
        notes.append(f"{undecided} point(s) have the verdict 'undecided': no boundary is searched next to them")
    return out


def run_sweep(plan: SweepPlan, *, executor=None) -> SweepOutcome:
    """Analyse the scene at every point of the plan; track the modes; find the boundaries.

    Parameters
    ----------
    plan : SweepPlan
        From :func:`~pinlin.report.sweep.sweep_plan`.
    executor : concurrent.futures.Executor, optional
        Where the points run (see :func:`pinlin.sweep`); the boundaries run here.

    Returns
    -------
    SweepOutcome

    A point or a boundary that fails does not stop the sweep: its error is
    recorded in the outcome (``result.values``, ``changes[k].failure``).

    Examples
    --------
    >>> from pinlin.model.scene_file import load_scene
    >>> from pinlin.report.sweep.parameters import sweep_plan
    >>> from pinlin.report.sweep.run import run_sweep
    >>> spec = load_scene(pinlin.data_path("scenes/double_pendulum_flutter.toml"))
    >>> plan = sweep_plan(spec, {"parameter": "follower.tip.force", "values": [0.0, 10.0, 20.0, 30.0]})
    >>> [change.verdicts for change in run_sweep(plan).changes]
    [('marginally_stable', 'flutter')]
    """
    t0 = time.perf_counter()
    grid = {p.path: p.values for p in plan.parameters}
    result = sweep(_point(plan), grid, executor=executor, progress=False, on_error="record")
    notes: list[str] = []
    verdicts = _verdicts(result.values, plan.shape)
    tracked, tracked_values = (None, None)
    if len(plan.parameters) == 1:
        tracked, tracked_values = _track(plan, result.values, notes)
    changes = _changes(plan, verdicts, notes)
    return SweepOutcome(plan, result, verdicts, tracked, tracked_values, changes, time.perf_counter() - t0, notes)


def headline(values: list[Any]) -> float | None:
    """The largest backward error of the points that succeeded (None when none did).

    Examples
    --------
    >>> from pinlin.report.sweep.run import headline
    >>> headline([]) is None
    True
    """
    errors = [v.error for v in values if isinstance(v, Modes)]
    return max(errors) if errors else None
