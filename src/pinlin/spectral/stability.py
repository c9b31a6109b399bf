"""The honest stability verdict (SPEC sections 5 and 9).

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

Order of the arguments: first the theorems of SPEC section 5, which decide
from definiteness and determinant signs alone; then the computed eigenvalues
with their error bounds r (first-order estimates, multiplied by the
documented ``safety`` factor): Re lam > r is certainly unstable, Re lam < -r
certainly stable.  An eigenvalue with |Re lam| <= r is decided only by
symmetry: when the spectrum is symmetric under reflection in the imaginary
axis (D = 0 and G = 0 or N = 0), a simple eigenvalue lam whose disk of radius
3 r holds no other computed eigenvalue (with its own bound) is its own mirror
image -conj(lam), so it lies exactly on the axis.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from .jordan import Cluster
from .problem import as_problem, check_tolerance
from .qualitative import DEFINITENESS_TOL, StructuralFacts, structural_facts

__all__ = ["Stability", "KINDS", "STABILITY_SAFETY", "decide_stability", "theorem_verdict", "stability_from_structure"]

KINDS = ("asymptotically_stable", "marginally_stable", "divergence", "flutter", "undecided")

#: Default factor applied to the first-order error bounds before they decide.
STABILITY_SAFETY = 10.0


@dataclass(frozen=True)
class Stability:
    """A stability verdict and why.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    reason : str
        The theorem applied, or the eigenvalue that decides and its error bound.
    theorem : str or None
        Short name of the theorem used ("Thomson-Tait-Chetaev", ...), None when
        the computed eigenvalues alone decide.
    eigenvalue : complex or None
        The deciding eigenvalue (the one farthest right, or the doubtful one).
    error_bound : float or None
        Its error bound after the safety factor [rad/s].
    bounded : bool or None
        True when every free motion is known to stay bounded (Lyapunov
        stable), False when some certainly grows, None when unknown.
    safety : float
        Factor applied to the first-order bounds.
    """

    kind: str
    reason: str
    theorem: str | None = None
    eigenvalue: complex | None = None
    error_bound: float | None = None
    bounded: bool | None = None
    safety: float = STABILITY_SAFETY

    @property
    def stable(self) -> bool:
        return self.kind in ("asymptotically_stable", "marginally_stable")

    @property
    def unstable(self) -> bool:
        return self.kind in ("divergence", "flutter")

    def __str__(self) -> str:
        return f"{self.kind.replace('_', ' ')}: {self.reason}"


def _fmt(lam: complex) -> str:
    lam = complex(lam)
    if lam.imag == 0:
        return f"{lam.real:.6g}"
    return f"{lam.real:.6g}{lam.imag:+.6g}i"


def _certainly_real(i: int, lam: np.ndarray, r: np.ndarray, clustered: np.ndarray) -> bool:
    """lam_i computed real, simple and farther than r_i + r_j from every other: it stays real."""
    if lam[i].imag != 0 or clustered[i]:
        return False
    others = np.delete(np.arange(lam.shape[0]), i)
    return bool(np.all(np.abs(lam[others] - lam[i]) > r[i] + r[others]))


def _instability(
    idx: np.ndarray, lam: np.ndarray, r: np.ndarray, clustered: np.ndarray
) -> tuple[str, int, str]:
    """Kind of an instability from the eigenvalues idx known (or computed) to lie in Re > 0."""
    real = [i for i in idx if _certainly_real(i, lam, r, clustered)]
    if real:
        i = max(real, key=lambda j: lam[j].real)
        return "divergence", i, "real"
    cplx = [i for i in idx if abs(lam[i].imag) > r[i]]
    if cplx:
        i = max(cplx, key=lambda j: lam[j].real)
        return "flutter", i, "complex"
    i = max(idx, key=lambda j: lam[j].real)
    kind = "divergence" if lam[i].imag == 0 else "flutter"
    return kind, i, "not certainly real or complex"


_DET_REASON = (
    "p(lam) = det L(lam) has leading coefficient det M and p(0) = det K of opposite signs, so a real root lies "
    "in (0, inf)"
)
_TTC_REASON = (
    "N = 0, D positive definite, S positive definite: every eigenvalue has Re lam < 0 "
    "(Thomson-Tait-Chetaev, whatever G)"
)
_LD_REASON = (
    "N = 0, D = 0, S positive definite: Re lam <= 0 (Lagrange-Dirichlet, whatever G) and the spectrum is "
    "symmetric under lam -> -conj(lam), so every eigenvalue lies on the imaginary axis, semisimple since the "
    "energy bounds every motion"
)


def theorem_verdict(facts: StructuralFacts, *, safety: float = STABILITY_SAFETY) -> Stability | None:
    """The verdict the theorems of SPEC section 5 give without any eigenvalue, or None.

    Decides: sign(det M) != sign(det K) => divergence; N = 0, D > 0, S > 0 =>
    asymptotically stable (Thomson-Tait-Chetaev); N = 0, D = 0, S > 0 =>
    marginally stable (Lagrange-Dirichlet and the reflection symmetry).
    Kelvin-Tait-Chetaev with an even, nonzero number of negative eigenvalues
    of S proves instability but not its kind, and D >= 0 singular with S > 0
    proves boundedness but not whether it is asymptotic: both return None
    (:func:`decide_stability` completes them with the spectrum).
    """
    if facts.det_sign_M * facts.det_sign_K < 0:
        return Stability("divergence", _DET_REASON, "sign of det K", None, None, False, safety)
    if facts.damping is None or facts.circulatory:
        return None
    if facts.damping == "positive_definite" and not facts.singular_stiffness and facts.negative_stiffness == 0:
        return Stability("asymptotically_stable", _TTC_REASON, "Thomson-Tait-Chetaev", None, None, True, safety)
    if facts.stiffness == "positive_definite" and not facts.damped:
        return Stability(
            "marginally_stable", _LD_REASON, "Lagrange-Dirichlet + symmetry", None, None, True, safety
        )
    return None


def stability_from_structure(sys, *, definiteness_tol: float = DEFINITENESS_TOL) -> Stability | None:
    """The stability verdict from the theorems alone, without solving for the spectrum (O(n^3)).

    Parameters
    ----------
    sys : LinearizedSystem or tuple (M, C, K)
    definiteness_tol : float
        Relative eigenvalue threshold of the definiteness and singularity tests.

    Returns
    -------
    Stability or None
        None when no theorem decides (see :func:`theorem_verdict`); then call
        :func:`pinlin.modal_analysis`.
    """
    tol = check_tolerance("definiteness_tol", definiteness_tol)
    return theorem_verdict(structural_facts(as_problem(sys), tol))


def decide_stability(
    facts: StructuralFacts,
    lam: np.ndarray,
    bound: np.ndarray,
    clusters: Sequence[Cluster],
    *,
    K_is_zero: bool = False,
    exact_drift: bool = False,
    safety: float = STABILITY_SAFETY,
) -> Stability:
    """The verdict for eigenvalues ``lam`` with first-order bounds ``bound`` (see module doc).

    Parameters
    ----------
    facts : StructuralFacts
    lam : (2n,) complex
    bound : (2n,) float
        First-order absolute error bounds [rad/s] (infinite when unknown).
    clusters : sequence of Cluster
        Multiple eigenvalues with their Jordan structure.
    K_is_zero : bool
        K = 0 exactly: lam = 0 is then exactly an eigenvalue of multiplicity >= n.
    exact_drift : bool
        Some coordinate j has K[:, j] = C[:, j] = 0 exactly, so x(t) = t e_j
        solves M x'' + C x' + K x = 0 exactly: a rigid-body drift.
    safety : float
        Factor applied to ``bound``.
    """
    lam = np.asarray(lam, dtype=complex)
    r = safety * np.asarray(bound, dtype=float)
    k = lam.shape[0]
    clustered = np.zeros(k, dtype=bool)
    for c in clusters:
        clustered[list(c.indices)] = True
    re = lam.real
    right = int(np.argmax(re))
    ctx = dict(safety=safety)

    def at(kind, reason, i=None, theorem=None, bounded=None):
        if i is None:
            return Stability(kind, reason, theorem, None, None, bounded, **ctx)
        return Stability(kind, reason, theorem, complex(lam[i]), float(r[i]), bounded, **ctx)

    # -- theorems ---------------------------------------------------------------
    pure = theorem_verdict(facts, safety=safety)
    if pure is not None:
        if pure.kind == "divergence":
            pos = np.flatnonzero((lam.imag == 0) & (re > 0))
            i = int(pos[np.argmax(re[pos])]) if pos.size else right
            reason = f"{pure.reason}; computed: lam = {_fmt(lam[i])}"
        else:
            i = right
            reason = pure.reason
        return replace(pure, reason=reason, eigenvalue=complex(lam[i]), error_bound=float(r[i]))
    mechanical = facts.damping is not None
    if mechanical and not facts.circulatory:
        if facts.damping == "positive_definite" and not facts.singular_stiffness:
            neg = facts.negative_stiffness
            idx = np.argsort(re)[-neg:]
            kind, i, how = _instability(idx, lam, r, clustered)
            return at(
                kind,
                f"N = 0, D positive definite, S nonsingular with {neg} negative eigenvalue(s): exactly {neg} "
                f"eigenvalue(s) with Re lam > 0 (Kelvin-Tait-Chetaev); the largest, lam = {_fmt(lam[i])}, is "
                f"{how} (error bound {r[i]:.1e})",
                i,
                "Kelvin-Tait-Chetaev",
                False,
            )
        if facts.stiffness == "positive_definite" and facts.damping in (
            "zero",
            "positive_semidefinite",
            "positive_definite",
        ):
            if np.all(re < -r):
                return at(
                    "asymptotically_stable",
                    f"N = 0, D positive semidefinite, S positive definite: Re lam <= 0 (Lagrange-Dirichlet/"
                    f"Kelvin); and the eigenvalue closest to the axis, lam = {_fmt(lam[right])}, has "
                    f"Re lam < -{r[right]:.1e} (its error bound)",
                    right,
                    "Lagrange-Dirichlet",
                    True,
                )
            near = np.flatnonzero(re >= -r)
            i = int(near[np.argmax(re[near])])
            return at(
                "undecided",
                f"N = 0, D positive semidefinite, S positive definite: bounded (Lagrange-Dirichlet), but "
                f"lam = {_fmt(lam[i])} lies within its error bound {r[i]:.1e} of the imaginary axis: "
                f"asymptotic or marginal stability cannot be told apart",
                i,
                "Lagrange-Dirichlet",
                True,
            )
    # -- the computed spectrum ----------------------------------------------------
    unstable = np.flatnonzero(re > r)
    if unstable.size:
        kind, i, how = _instability(unstable, lam, r, clustered)
        return at(
            kind,
            f"lam = {_fmt(lam[i])} ({how}) has Re lam = {lam[i].real:.4g} > {r[i]:.1e}, its error bound",
            i,
            None,
            False,
        )
    if np.all(re < -r):
        return at(
            "asymptotically_stable",
            f"the eigenvalue farthest right, lam = {_fmt(lam[right])}, has Re lam = {lam[right].real:.4g} "
            f"< -{r[right]:.1e} (its error bound)",
            right,
            None,
            True,
        )
    near = np.flatnonzero(np.abs(re) <= r)
    near_clusters = [c for c in clusters if any(j in near for j in c.indices)]
    for c in near_clusters:
        if not c.consistent or c.semisimple:
            continue
        j = c.indices[0]
        at_zero = abs(c.center) <= r[j]
        on_axis = facts.reflection_symmetric or (K_is_zero and at_zero)
        if not on_axis:
            continue
        growth = "divergence" if at_zero else "flutter"
        if not (at_zero and exact_drift):
            # Defective only to rank_tol: rounding-level changes of the data split a multiple
            # eigenvalue on the axis into simple ones on it (bounded) or off it (growing).
            onset = "divergence" if at_zero else "flutter"
            return at(
                "undecided",
                f"the eigenvalue {_fmt(c.center)} of multiplicity {c.algebraic} lies on the imaginary axis and is "
                f"defective to the rank tolerance (Jordan chains of lengths {c.partial}): the system is at a "
                f"stability boundary ({onset} onset) within rounding, where a perturbation of the data at the "
                f"rounding level leaves simple eigenvalues on the axis (marginally stable) or moves a pair off it "
                f"({onset}); the computed spectrum cannot tell which",
                j,
                None,
                None,
            )
        what = "rigid-body drift" if growth == "divergence" else "oscillation with linearly growing amplitude"
        why = "K[:, j] = C[:, j] = 0 for a coordinate j, so x(t) = t e_j solves the equations exactly"
        return at(
            growth,
            f"the eigenvalue {_fmt(c.center)} of multiplicity {c.algebraic} is defective (Jordan chains of "
            f"lengths {c.partial}) and {why}: secular growth t^{c.index - 1} ({what})",
            j,
            "Jordan structure + exact drift",
            False,
        )
    if facts.reflection_symmetric:
        doubtful = []
        for i in near:
            others = np.delete(np.arange(k), i)
            isolated = not clustered[i] and np.all(np.abs(lam[others] - lam[i]) > 3 * r[i] + r[others])
            if not isolated:
                doubtful.append(i)
        if not doubtful:
            i = int(near[np.argmax(r[near])])
            return at(
                "marginally_stable",
                f"D = 0 and {'G' if not facts.gyroscopic else 'N'} = 0: the spectrum is symmetric under "
                f"lam -> -conj(lam), and each of the {near.size} eigenvalue(s) within its error bound of the "
                f"axis is simple and isolated (e.g. lam = {_fmt(lam[i])}, bound {r[i]:.1e}), so it lies on it",
                i,
                "reflection symmetry",
                True,
            )
        i = doubtful[0]
        return at(
            "undecided",
            f"lam = {_fmt(lam[i])} lies within its error bound {r[i]:.1e} of the imaginary axis and is not "
            f"isolated from its neighbours, so symmetry cannot place it on the axis",
            i,
            None,
            None,
        )
    zero_cluster = [c for c in near_clusters if K_is_zero and abs(c.center) <= r[c.indices[0]] and c.semisimple]
    if zero_cluster:
        c = zero_cluster[0]
        rest = np.setdiff1d(np.arange(k), c.indices)
        if np.all(re[rest] < -r[rest]):
            j = int(rest[np.argmax(re[rest])]) if rest.size else c.indices[0]
            return at(
                "marginally_stable",
                f"K = 0, so lam = 0 is exact; it is semisimple (multiplicity {c.algebraic}) and every other "
                f"eigenvalue has Re lam < -bound (farthest right {_fmt(lam[j])}, bound {r[j]:.1e})",
                j,
                "Jordan structure",
                True,
            )
    i = int(near[np.argmax(re[near])])
    return at(
        "undecided",
        f"lam = {_fmt(lam[i])} has |Re lam| = {abs(lam[i].real):.2e} within its error bound {r[i]:.1e} and no "
        f"theorem or symmetry applies",
        i,
        None,
        None,
    )
