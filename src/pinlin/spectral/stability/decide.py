"""The honest stability verdict (theory: stability, conventions).

The verdict is one of

* ``"asymptotically_stable"`` -- every eigenvalue has Re lam < 0;
* ``"marginally_stable"`` -- Re lam <= 0, those on the imaginary axis semisimple;
* ``"divergence"`` -- a real positive eigenvalue, or an exact rigid-body
  drift x = t e_j (a coordinate on which neither K nor C acts, with the
  defective zero eigenvalue it causes);
* ``"flutter"`` -- a complex pair with Re lam > 0;
* ``"undecided"`` -- rounding cannot tell and no theorem decides; in
  particular a multiple eigenvalue on the imaginary axis that is defective
  only to the rank tolerance (a flutter or divergence onset: rounding-level
  changes of the data split it into simple eigenvalues on the axis or a pair
  off it),

each with a reason naming the theorem, or the eigenvalue and its error bound.

Order of the arguments: first the theorems of theory: stability, which decide
from definiteness and determinant signs alone, each decided against the
rounding bound of the data (:func:`pinlin.numerics.definiteness`); then the
computed eigenvalues with their error bounds r (first-order estimates at the
data uncertainty, multiplied by the documented ``safety`` factor): Re lam > r
is certainly unstable, Re lam < -r certainly stable.  An eigenvalue with |Re lam| <= r is decided only by
symmetry: when the spectrum is symmetric under reflection in the imaginary
axis (D = 0 and G = 0 or N = 0), a simple eigenvalue lam whose disk of radius
3 r holds no other computed eigenvalue (with its own bound) is its own mirror
image -conj(lam), so it lies exactly on the axis.

The verdict is the first of the rules in :data:`pinlin.spectral.stability.rules.RULES`
that decides; each rule is one theorem of theory: stability or one numerical
decision, and says which in its docstring.  A relative data ``uncertainty``
(default 0: the data as stored) widens every threshold and bound, so that the
verdict holds for every system within it; the ``margin`` says how large an
uncertainty the verdict survives.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ...numerics.checks import check_uncertainty
from ...numerics.definiteness import DEFAULT_UNCERTAINTY
from ..accuracy import ErrorModel
from ..multiplicity import Cluster
from ..problem import as_problem
from ..qualitative import StructuralFacts, structural_facts
from .dissipation import dissipation_rows
from .rules import RULES, Evidence
from .unstructured import UnstructuredQuestion, structure_kept
from .verdict import KINDS, MARGIN_CAP, STABILITY_SAFETY, Stability, theorem_verdict

__all__ = [
    "Stability",
    "KINDS",
    "STABILITY_SAFETY",
    "MARGIN_CAP",
    "MARGIN_FLOOR",
    "decide_stability",
    "theorem_verdict",
    "stability_from_structure",
]

#: Smallest margin told apart from zero by the bisection (a relative perturbation far
#: below the unit roundoff: a verdict that needs exactness to that level has none).
MARGIN_FLOOR = 1e-20

#: Bisection steps on log10(margin) between MARGIN_FLOOR and MARGIN_CAP (about 19 decades):
#: 20 halvings leave the margin known to 2e-5 decades, far more than a report prints.
_MARGIN_STEPS = 20


def stability_from_structure(
    sys, *, uncertainty: float = DEFAULT_UNCERTAINTY, definiteness_tol: float | None = None
) -> Stability | None:
    """The stability verdict from the theorems alone, without solving for the spectrum (O(n^3)).

    Parameters
    ----------
    sys : LinearizedSystem or tuple (M, C, K)
    uncertainty : float
        Relative data uncertainty in [0, 1) the definiteness decisions hold
        against (:func:`pinlin.numerics.definiteness`; default 0, rounding only).
    definiteness_tol : float, optional
        The name of pinlin 0.2 for ``uncertainty``.

    Returns
    -------
    Stability or None
        None when no theorem decides (see :func:`theorem_verdict`); then call
        :func:`pinlin.modal_analysis`.  "undecided" when M is positive definite
        only within rounding.

    Raises
    ------
    ParameterError
        Bad uncertainty or matrices.
    SingularMassError
        M of a tuple is singular.
    """
    t0 = time.perf_counter()
    u = check_uncertainty(uncertainty if definiteness_tol is None else definiteness_tol)
    facts = structural_facts(as_problem(sys), u)
    verdict = theorem_verdict(facts)
    if verdict is None:
        return None
    if verdict.kind == "undecided":
        return verdict.replace(elapsed=time.perf_counter() - t0, uncertainty=u, margin=0.0)
    question = _MarginQuestion(verdict.kind, u, facts, None, None, (), {}, verdict.safety)
    return verdict.replace(elapsed=time.perf_counter() - t0, uncertainty=u, margin=None, margin_of=question,
                           kept=structure_kept(verdict.theorem, facts))


@dataclass(frozen=True, eq=False)
class _DissipationQuestion:
    """The dissipation table of a marginal verdict as a function of immutable evidence (called on first access)."""

    matrices: tuple
    system: object
    facts: StructuralFacts
    lam: np.ndarray
    vectors: tuple
    r: np.ndarray

    def __call__(self) -> tuple:
        X, Y, ok = self.vectors
        return dissipation_rows(self.matrices, self.system, self.facts, self.lam, X, Y, self.r, ok)


@dataclass(frozen=True, eq=False)
class _MarginQuestion:
    """The margin of a verdict as a function of immutable evidence (picklable; called on first access).

    ``lam is None``: a verdict of the theorems alone (:func:`theorem_verdict` at
    the facts decided against delta); otherwise the rules of
    :data:`~pinlin.spectral.stability.rules.RULES` at the evidence against delta.
    """

    kind: str
    uncertainty: float
    facts: StructuralFacts
    lam: np.ndarray | None
    model: ErrorModel | None
    clusters: tuple
    flags: dict
    safety: float

    def kind_at(self, delta: float) -> str | None:
        if self.lam is None:
            verdict = theorem_verdict(self.facts.at(delta))
            return None if verdict is None else verdict.kind
        return _verdict(self.facts, self.lam, self.model, self.clusters, self.flags, self.safety, delta).kind

    def __call__(self) -> float:
        return _margin(self.kind, self.kind_at, self.uncertainty)


def _margin(kind: str, kind_at, uncertainty: float) -> float:
    """The largest delta in [uncertainty, MARGIN_CAP] with ``kind_at(delta) == kind`` (bisection in log delta).

    The verdict is monotone in delta up to the bisection's resolution: a larger
    uncertainty only widens bounds and thresholds.
    """
    if kind_at(MARGIN_CAP) == kind:
        return MARGIN_CAP
    lo = max(uncertainty, MARGIN_FLOOR)
    if lo > uncertainty and kind_at(lo) != kind:
        return uncertainty
    a, b = np.log10(lo), np.log10(MARGIN_CAP)
    for _ in range(_MARGIN_STEPS):
        mid = 0.5 * (a + b)
        if kind_at(10.0**mid) == kind:
            a = mid
        else:
            b = mid
    return float(max(10.0**a, uncertainty))


def _verdict(facts, lam, model: ErrorModel, clusters, flags: dict, safety: float, delta: float) -> Stability:
    """The first rule of RULES that decides, with the evidence at data uncertainty ``delta``."""
    ev = Evidence.of(
        facts if delta == facts.uncertainty else facts.at(delta), lam, model.bound(delta), clusters,
        safety=safety, uncertainty=delta, **flags,
    )
    *rules, last = RULES
    for rule in rules:
        verdict = rule(ev)
        if verdict is not None:
            return verdict
    return last(ev)  # "undecided": always decides


def decide_stability(
    facts: StructuralFacts,
    lam: np.ndarray,
    model: ErrorModel,
    clusters: Sequence[Cluster],
    *,
    K_is_zero: bool = False,
    exact_drift: bool = False,
    safety: float = STABILITY_SAFETY,
    uncertainty: float | None = None,
    problem=None,
    vectors: tuple | None = None,
) -> Stability:
    """The verdict for eigenvalues ``lam`` with their error model (see module doc), and its margin.

    The rules of :data:`pinlin.spectral.stability.rules.RULES` are tried in
    order; the first that decides gives the verdict (the last always does).
    The bounds are ``safety * model.bound(uncertainty)``.  The margin is the
    largest data uncertainty at which the same rules still give the same kind
    (bisection, :data:`MARGIN_CAP` at most), computed on first access of
    ``margin``, ``error``, ``reason`` (which states it) or ``to_dict()``: the
    verdict itself costs one pass through the rules.

    Parameters
    ----------
    facts : StructuralFacts
        Decided against ``uncertainty``.
    lam : (2n,) complex
    model : ErrorModel
        First-order error bounds as functions of the data uncertainty.
    clusters : sequence of Cluster
        Multiple eigenvalues with their Jordan structure.
    K_is_zero : bool
        K = 0 exactly: lam = 0 is then exactly an eigenvalue of multiplicity >= n.
    exact_drift : bool
        Some coordinate j has K[:, j] = C[:, j] = 0 exactly, so x(t) = t e_j
        solves M x'' + C x' + K x = 0 exactly: a rigid-body drift.
    safety : float
        Factor applied to the bounds.
    uncertainty : float, optional
        Relative data uncertainty (default: the one ``facts`` were decided against).
    problem : QuadraticProblem, optional
        The coefficients: with ``vectors``, a marginal verdict gets its dissipation table, and every
        verdict its unstructured margin (both formed on first access).
    vectors : (X, Y, left_normalized), optional
        Right and left vectors of ``lam`` (y^T L'(lam) x = 1 where ``left_normalized``).
    """
    t0 = time.perf_counter()
    u = facts.uncertainty if uncertainty is None else float(uncertainty)
    flags = {"K_is_zero": K_is_zero, "exact_drift": exact_drift}
    verdict = _verdict(facts, lam, model, clusters, flags, safety, u)
    if verdict.kind == "undecided":
        return verdict.replace(margin=0.0, elapsed=time.perf_counter() - t0)
    question = _MarginQuestion(
        verdict.kind, u, facts, np.asarray(lam), model, tuple(clusters), flags, safety
    )
    lazy = {"kept": structure_kept(verdict.theorem, facts)}
    if problem is not None:
        rows = None
        if vectors is not None and verdict.kind == "marginally_stable":
            rows = _DissipationQuestion((problem.M, problem.C, problem.K), problem.system, facts,
                                        np.asarray(lam), tuple(vectors), safety * model.bound(u))
        lazy["dissipation_of"] = rows
        lazy["unstructured_of"] = UnstructuredQuestion(verdict.kind, np.asarray(lam), model, problem.norms, rows,
                                                       MARGIN_CAP, safety)
    return verdict.replace(margin=None, margin_of=question, quote_margin=True, elapsed=time.perf_counter() - t0,
                           **lazy)
