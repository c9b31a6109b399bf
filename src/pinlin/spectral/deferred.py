"""What :class:`~pinlin.spectral.modes.Modes` keeps to form some of its parts on first access.

:func:`~pinlin.spectral.modal_analysis` computes eagerly what every caller
reads and what can fail: the eigenvalues, both sets of vectors, the backward
errors (``modes.error``), the error bounds, the clusters with their Jordan
structure, the multiplicities and the kinds, and every check that raises.
The rest is a pure function of immutable data kept here and is formed on first
access, by exactly the code (and the same inputs) the eager analysis ran:

- :class:`DeferredFigures` -- the condition numbers and the modal constants;
- :class:`DeferredVerdict` -- the structural facts (definiteness of M, D and S,
  det K: O(n^3) each), the stability verdict and the notes that depend on them.

Both are picklable; two threads that form the same part at once compute the
same value (nothing here is mutated after construction).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..numerics.definiteness import Definiteness
from ..numerics.threads import small_kernels
from .accuracy import ErrorModel
from .problem import QuadraticProblem
from .qualitative import StructuralFacts, structural_facts
from .stability import Stability, decide_stability

__all__ = ["DeferredFigures", "DeferredVerdict", "mass_notes"]


@dataclass(frozen=True, eq=False)
class DeferredFigures:
    """What :class:`Modes` keeps to form its condition numbers on first access (picklable).

    Attributes
    ----------
    products : (3, 2n) complex
        y^T M x, y^T C x, y^T K x of the unit right and left vectors.
    quadratic : (3, 2n) complex
        x^H M x, x^H C x, x^H K x of the unit right vectors (from the solver's products).
    norms : tuple of float
        (||M||, ||C||, ||K||), Frobenius.
    defective : tuple of int
        Members of defective clusters (condition inf).
    """

    products: np.ndarray
    quadratic: np.ndarray
    norms: tuple[float, float, float]
    defective: tuple[int, ...] = ()


@dataclass(frozen=True, eq=False)
class DeferredVerdict:
    """The evidence of the structural facts, the stability verdict and the notes (picklable).

    Attributes
    ----------
    problem : QuadraticProblem
        The coefficients analysed.
    lam : (2n,) complex
        The eigenvalues (read-only).
    model : ErrorModel
        Their error model (bounds as functions of the data uncertainty).
    clusters : tuple of Cluster
    bound : (2n,) float
        ``model.bound(0)``, the error bounds of the computation (read-only).
    uncertainty, safety : float
        The validated options of the analysis.
    mass : Definiteness or None
        The decision about M when the caller made it already; made on first
        access otherwise (:func:`~pinlin.spectral.modal_analysis` leaves it to
        the first access: its symmetric paths predict from a Cholesky factor of M).
    notes : tuple of str
        The notes of the analysis that do not depend on the facts (clusters,
        biorthogonalization), in the order the analysis found them.
    vectors : (X, Y, left_normalized) or None
        The right and left vectors (read-only), for the verdict's dissipation
        table and unstructured margin.
    """

    problem: QuadraticProblem
    lam: np.ndarray
    model: ErrorModel
    clusters: tuple
    bound: np.ndarray
    uncertainty: float
    safety: float
    mass: Definiteness | None = None
    notes: tuple[str, ...] = ()
    vectors: tuple | None = None

    def facts(self) -> StructuralFacts:
        """:func:`~pinlin.spectral.qualitative.structural_facts` of the problem at the uncertainty.

        Its eigenvalue decompositions of M, D and S run on one BLAS thread for a
        small problem (:func:`~pinlin.numerics.threads.small_kernels`), as the analysis did.
        """
        with small_kernels(self.problem.n):
            return structural_facts(self.problem, self.uncertainty, self.mass)

    def stability(self, facts: StructuralFacts) -> Stability:
        """The verdict of :func:`~pinlin.spectral.stability.decide_stability` (its margin still deferred)."""
        problem = self.problem
        # a coordinate on which neither K nor C acts drifts exactly: x(t) = t e_j
        K, C = problem.K, problem.C
        drift = bool(np.count_nonzero(K.any(axis=0) | C.any(axis=0)) < K.shape[1])
        stability = decide_stability(
            facts, self.lam, self.model, self.clusters, K_is_zero=not np.count_nonzero(K), exact_drift=drift,
            safety=self.safety, uncertainty=self.uncertainty, problem=problem, vectors=self.vectors,
        )
        return with_contact_notes(stability, problem.system)

    def all_notes(self, facts: StructuralFacts) -> tuple[str, ...]:
        """The analysis' notes followed by the note on an M definite only within rounding (if any)."""
        return self.notes + tuple(mass_notes(facts, self.lam, self.bound))


def mass_notes(facts: StructuralFacts, lam: np.ndarray, bound: np.ndarray) -> list[str]:
    """An M positive definite only within rounding is said, with the eigenvalues it spoils."""
    on_M = facts.definiteness_M
    if on_M is None or on_M.kind == "positive_definite":
        return []
    lost = int(np.sum(bound >= np.abs(lam)))
    return [
        f"M is positive definite only within rounding: its smallest eigenvalue {on_M.min_eigenvalue:.3g} is "
        f"within {on_M.threshold:.2g} (c n eps ||M|| + uncertainty ||M||) of zero, so a perturbation of M at that "
        f"level makes it singular; {lost} of the {lam.shape[0]} eigenvalues have an error bound at least their "
        f"modulus (they lose their meaning)"
    ]


def with_contact_notes(stability: Stability, system) -> Stability:
    """The verdict's reason quotes a contact that the equilibrium violates (the ground would have to pull, or
    friction exceed mu): the linearization treats contacts as bilateral, so such a verdict holds only while
    the contact is held (theory: constraints)."""
    notes = [n for n in getattr(system, "notes", ()) if n.startswith("contact '")]
    if not notes:
        return stability
    return stability.replace(reason=f"{stability._basis}; but {'; '.join(notes)}")
