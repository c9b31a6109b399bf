"""The rules of the stability verdict, tried in order (theory: stability).

Each rule takes the :class:`Evidence` (structural facts, computed eigenvalues,
their error bounds r after the safety factor and the data uncertainty, the
clusters) and returns a :class:`~pinlin.spectral.Stability` or None when it
does not decide.  The first three are theorems of theory: stability (the
structure alone, then Kelvin-Tait-Chetaev and Lagrange-Dirichlet completed by
the spectrum); the others are numerical decisions on the computed spectrum,
the last of which always decides ("undecided").  Every definiteness the
theorems use is certain within rounding and the uncertainty
(:func:`pinlin.numerics.definiteness`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from ..multiplicity import Cluster
from ..qualitative import StructuralFacts
from .verdict import Stability, theorem_verdict

__all__ = ["Evidence", "RULES", "ISOLATION_FACTOR"]

#: A simple eigenvalue within its bound r of the imaginary axis is its own mirror
#: image -conj(lam) when no other computed eigenvalue lies within ISOLATION_FACTOR r
#: (plus that one's bound): the mirror image lies within 2 r of lam, and within r
#: of where it was computed.
ISOLATION_FACTOR = 3.0

#: Eigenvalues whose isolation :meth:`Evidence.isolated` tests in one block (bounds its memory to 256 x 2n).
_ISOLATION_ROWS = 256


def _fmt(lam: complex) -> str:
    lam = complex(lam)
    if lam.imag == 0:
        return f"{lam.real:.6g}"
    return f"{lam.real:.6g}{lam.imag:+.6g}i"


@dataclass(frozen=True, eq=False)
class Evidence:
    """What the rules decide from.

    Attributes
    ----------
    facts : StructuralFacts
    lam : (2n,) complex
        Computed eigenvalues [rad/s].
    r : (2n,) float
        Their first-order error bounds at the data uncertainty, times ``safety`` [rad/s]
        (:meth:`pinlin.spectral.accuracy.ErrorModel.bound`).
    clusters : tuple of Cluster
    clustered : (2n,) bool
        Member of some cluster.
    K_is_zero, exact_drift : bool
        See :func:`pinlin.spectral.stability.decide_stability`.
    safety : float
    uncertainty : float
        The relative data uncertainty r and ``facts`` were decided against.
    """

    facts: StructuralFacts
    lam: np.ndarray
    r: np.ndarray
    clusters: tuple[Cluster, ...]
    clustered: np.ndarray
    K_is_zero: bool
    exact_drift: bool
    safety: float
    uncertainty: float = 0.0

    @classmethod
    def of(
        cls, facts, lam, bound, clusters: Sequence[Cluster], *, K_is_zero, exact_drift, safety, uncertainty=0.0
    ) -> Evidence:
        """Evidence from the bounds *before* the safety factor (``bound``, at the data uncertainty)."""
        lam = np.asarray(lam, dtype=complex)
        r = safety * np.asarray(bound, dtype=float)
        clustered = np.zeros(lam.shape[0], dtype=bool)
        for c in clusters:
            clustered[list(c.indices)] = True
        return cls(
            facts, lam, r, tuple(clusters), clustered, bool(K_is_zero), bool(exact_drift), float(safety),
            float(uncertainty),
        )

    @property
    def re(self) -> np.ndarray:
        return self.lam.real

    @property
    def right(self) -> int:
        """Index of the eigenvalue farthest right."""
        return int(np.argmax(self.re))

    @property
    def near(self) -> np.ndarray:
        """Indices of the eigenvalues within their bound of the imaginary axis."""
        return np.flatnonzero(np.abs(self.re) <= self.r)

    def at(self, kind: str, reason: str, i: int | None = None, theorem=None, bounded=None) -> Stability:
        """The verdict, with eigenvalue i and its bound attached (when given)."""
        return Stability(
            kind=kind, reason=reason, theorem=theorem, eigenvalue=None if i is None else complex(self.lam[i]),
            error_bound=None if i is None else float(self.r[i]), bounded=bounded, safety=self.safety,
            uncertainty=self.uncertainty,
        )

    def quoted(self, i: int) -> str:
        """The bound r_i as the verdict quotes it, with the safety factor and the bound it multiplies named
        (the bound of ``Modes.error_bound`` and the table's column when the uncertainty is 0)."""
        r, s = float(self.r[i]), self.safety
        at = f" at the data uncertainty {self.uncertainty:g}" if self.uncertainty else ""
        if s == 1.0:
            return f"{r:.1e}"
        return f"{r:.1e} (the safety factor {s:g} times the error bound {r / s:.1e}{at})"

    def certainly_real(self, i: int) -> bool:
        """lam_i computed real, simple and farther than r_i + r_j from every other: it stays real."""
        return bool(self.lam[i].imag == 0 and self.isolated(np.array([i]), 1.0)[0])

    def isolated(self, idx: np.ndarray, factor: float = ISOLATION_FACTOR) -> np.ndarray:
        """Per index i of idx: lam_i is in no cluster and |lam_j - lam_i| > factor r_i + r_j for all j != i.

        The distances are formed for up to :data:`_ISOLATION_ROWS` eigenvalues i at once (memory 2n per row).
        """
        lam, r = self.lam, self.r
        out = ~self.clustered[idx]
        for start in range(0, idx.size, _ISOLATION_ROWS):
            rows = idx[start : start + _ISOLATION_ROWS]
            far = np.abs(lam[None, :] - lam[rows, None]) > (factor * r[rows])[:, None] + r[None, :]
            far[np.arange(rows.size), rows] = True  # j = i is no neighbour
            out[start : start + rows.size] &= far.all(axis=1)
        return out

    def instability(self, idx) -> tuple[str, int, str]:
        """Kind of an instability from the eigenvalues idx known (or computed) to lie in Re > 0."""
        lam, r = self.lam, self.r
        idx = np.asarray(idx, dtype=int)
        real = idx[(lam[idx].imag == 0) & self.isolated(idx, 1.0)]  # the certainly real ones (certainly_real)
        if real.size:
            return "divergence", int(real[np.argmax(lam[real].real)]), "real"
        cplx = [i for i in idx if abs(lam[i].imag) > r[i]]
        if cplx:
            return "flutter", max(cplx, key=lambda j: lam[j].real), "complex"
        i = max(idx, key=lambda j: lam[j].real)
        kind = "divergence" if lam[i].imag == 0 else "flutter"
        return kind, i, "not certainly real or complex"


# ---------------------------------------------------------------------------- theorems


def structure_theorems(ev: Evidence) -> Stability | None:
    """theory: stability from the structure alone (:func:`theorem_verdict`), with the deciding eigenvalue attached."""
    pure = theorem_verdict(ev.facts, safety=ev.safety)
    if pure is None:
        return None
    lam, re = ev.lam, ev.re
    if pure.kind == "undecided":  # M positive definite only within rounding: the largest eigenvalue is doubtful
        i = int(np.argmax(np.abs(lam)))
        return pure.replace(eigenvalue=complex(lam[i]), error_bound=float(ev.r[i]), uncertainty=ev.uncertainty)
    if pure.kind == "divergence":
        pos = np.flatnonzero((lam.imag == 0) & (re > 0))
        i = int(pos[np.argmax(re[pos])]) if pos.size else ev.right
        reason = f"{pure.reason}; computed: lam = {_fmt(lam[i])}"
    else:
        i = ev.right
        reason = pure.reason
    reason += _certificates(ev.facts)
    return pure.replace(
        reason=reason, eigenvalue=complex(lam[i]), error_bound=float(ev.r[i]), uncertainty=ev.uncertainty
    )


def _certificates(facts) -> str:
    """What certified the definiteness the theorems used (theory: stability; :func:`pinlin.numerics.definiteness`)."""
    parts = [
        f"{name} {d.kind.replace('_', ' ')} by {d.certificate} (margin {d.margin:.1e})"
        for name, d in (("M", facts.definiteness_M), ("D", facts.definiteness_D), ("S", facts.definiteness_S))
        if d is not None and d.kind != "zero"
    ]
    if not parts and facts.definiteness_S is None:
        parts = [f"det M and det K of sign margins {facts.det_margin_M:.1e} and {facts.det_margin_K:.1e}"]
    return f" [{'; '.join(parts)}]" if parts else ""


def _non_circulatory(ev: Evidence) -> bool:
    return ev.facts.damping is not None and not ev.facts.circulatory


def kelvin_tait_chetaev(ev: Evidence) -> Stability | None:
    """N = 0, D positive definite, S nonsingular with k negative eigenvalues: exactly k with Re lam > 0.

    The theorem proves instability; the k rightmost computed eigenvalues tell its kind.
    """
    facts = ev.facts
    if not _non_circulatory(ev) or facts.damping != "positive_definite" or facts.singular_stiffness:
        return None
    neg = facts.negative_stiffness
    if neg == 0:  # S positive definite: Thomson-Tait-Chetaev's case, not an instability
        return None
    kind, i, how = ev.instability(np.argsort(ev.re)[-neg:])
    return ev.at(
        kind,
        f"N = 0, D positive definite, S nonsingular with {neg} negative eigenvalue(s): exactly {neg} "
        f"eigenvalue(s) with Re lam > 0 (Kelvin-Tait-Chetaev); the largest, lam = {_fmt(ev.lam[i])}, is "
        f"{how} (error bound {ev.quoted(i)})",
        i,
        "Kelvin-Tait-Chetaev",
        False,
    )


def lagrange_dirichlet(ev: Evidence) -> Stability | None:
    """N = 0, D positive semidefinite, S positive definite: Re lam <= 0 (bounded motions).

    D must be certainly positive semidefinite (:attr:`pinlin.numerics.Definiteness.certainly_psd`:
    zero, positive definite, or positive definite where it is not exactly zero).
    Asymptotic stability then needs every computed eigenvalue left of its bound;
    otherwise asymptotic and marginal stability cannot be told apart.
    """
    facts = ev.facts
    if not _non_circulatory(ev) or facts.stiffness != "positive_definite":
        return None
    if facts.definiteness_D is None or not facts.definiteness_D.certainly_psd:
        return None
    re, r, right = ev.re, ev.r, ev.right
    if np.count_nonzero(re < -r) == re.shape[0]:
        return ev.at(
            "asymptotically_stable",
            f"N = 0, D positive semidefinite, S positive definite: Re lam <= 0 (Lagrange-Dirichlet/"
            f"Kelvin); and the eigenvalue closest to the axis, lam = {_fmt(ev.lam[right])}, has "
            f"Re lam < -{ev.quoted(right)}",
            right,
            "Lagrange-Dirichlet",
            True,
        )
    near = np.flatnonzero(re >= -r)
    i = int(near[np.argmax(re[near])])
    return ev.at(
        "undecided",
        f"N = 0, D positive semidefinite, S positive definite: bounded (Lagrange-Dirichlet), but "
        f"lam = {_fmt(ev.lam[i])} lies within its error bound {ev.quoted(i)} of the imaginary axis: "
        f"asymptotic or marginal stability cannot be told apart",
        i,
        "Lagrange-Dirichlet",
        True,
    )


# ---------------------------------------------------------------------------- the computed spectrum


def certainly_unstable(ev: Evidence) -> Stability | None:
    """Some eigenvalue has Re lam above its error bound."""
    unstable = (ev.re > ev.r).nonzero()[0]
    if not unstable.size:
        return None
    kind, i, how = ev.instability(unstable)
    lam = ev.lam[i]
    return ev.at(kind, f"lam = {_fmt(lam)} ({how}) has Re lam = {lam.real:.4g} > {ev.quoted(i)} (its error bound)", i,
                 None, False)


def certainly_asymptotic(ev: Evidence) -> Stability | None:
    """Every eigenvalue has Re lam below minus its error bound (the one whose bound comes closest is named)."""
    if np.count_nonzero(ev.re < -ev.r) != ev.lam.shape[0]:
        return None
    i = int(np.argmax(ev.re + ev.r))
    return ev.at(
        "asymptotically_stable",
        f"every eigenvalue lies left of the axis by more than its error bound; closest: lam = "
        f"{_fmt(ev.lam[i])}, Re lam = {ev.lam[i].real:.4g} < -{ev.quoted(i)}",
        i,
        None,
        True,
    )


def defective_on_axis(ev: Evidence) -> Stability | None:
    """A defective cluster on the imaginary axis: secular growth if the drift is exact, else a boundary.

    On the axis means: the spectrum is reflection symmetric, or K = 0 and the
    cluster is at zero.  Defective only to the rank tolerance, rounding-level
    changes of the data split it into simple eigenvalues on the axis (bounded)
    or off it (growing): undecided.  With an exact drift x = t e_j the growth is certain.
    """
    near = ev.near
    for c in ev.clusters:
        if not any(j in near for j in c.indices) or not c.consistent or c.semisimple:
            continue
        j = c.indices[0]
        at_zero = abs(c.center) <= ev.r[j]
        if not (ev.facts.reflection_symmetric or (ev.K_is_zero and at_zero)):
            continue
        onset = "divergence" if at_zero else "flutter"
        if not (at_zero and ev.exact_drift):
            return ev.at(
                "undecided",
                f"the eigenvalue {_fmt(c.center)} of multiplicity {c.algebraic} lies on the imaginary axis and is "
                f"defective to the rank tolerance (Jordan chains of lengths {c.partial}): the system is at a "
                f"stability boundary ({onset} onset) within rounding, where a perturbation of the data at the "
                f"rounding level leaves simple eigenvalues on the axis (marginally stable) or moves a pair off it "
                f"({onset}); the computed spectrum cannot tell which",
                j,
            )
        return ev.at(
            "divergence",
            f"the eigenvalue {_fmt(c.center)} of multiplicity {c.algebraic} is defective (Jordan chains of "
            f"lengths {c.partial}) and K[:, j] = C[:, j] = 0 for a coordinate j, so x(t) = t e_j solves the "
            f"equations exactly: secular growth t^{c.index - 1} (rigid-body drift)",
            j,
            "Jordan structure + exact drift",
            False,
        )
    return None


def reflection_symmetry(ev: Evidence) -> Stability | None:
    """D = 0 and (G = 0 or N = 0): an isolated simple eigenvalue near the axis lies on it (see ISOLATION_FACTOR)."""
    if not ev.facts.reflection_symmetric:
        return None
    lam, r, near = ev.lam, ev.r, ev.near
    doubtful = near[~ev.isolated(near)]
    if not doubtful.size:
        i = int(near[np.argmax(r[near])])
        return ev.at(
            "marginally_stable",
            f"D = 0 and {'G' if not ev.facts.gyroscopic else 'N'} = 0: the spectrum is symmetric under "
            f"lam -> -conj(lam), and each of the {near.size} eigenvalue(s) within its error bound of the "
            f"axis is simple and isolated (e.g. lam = {_fmt(lam[i])}, bound {ev.quoted(i)}), so it lies on it",
            i,
            "reflection symmetry",
            True,
        )
    i = int(doubtful[0])
    return ev.at(
        "undecided",
        f"lam = {_fmt(lam[i])} lies within its error bound {ev.quoted(i)} of the imaginary axis and is not "
        f"isolated from its neighbours, so symmetry cannot place it on the axis",
        i,
    )


def semisimple_zero(ev: Evidence) -> Stability | None:
    """K = 0: lam = 0 is exact; semisimple with every other eigenvalue certainly left: marginally stable."""
    if not ev.K_is_zero:
        return None
    near, r, re = ev.near, ev.r, ev.re
    for c in ev.clusters:
        if not (any(j in near for j in c.indices) and abs(c.center) <= r[c.indices[0]] and c.semisimple):
            continue
        rest = np.setdiff1d(np.arange(ev.lam.shape[0]), c.indices)
        if np.all(re[rest] < -r[rest]):
            j = int(rest[np.argmax(re[rest])]) if rest.size else c.indices[0]
            return ev.at(
                "marginally_stable",
                f"K = 0, so lam = 0 is exact; it is semisimple (multiplicity {c.algebraic}) and every other "
                f"eigenvalue has Re lam < -bound (farthest right {_fmt(ev.lam[j])}, bound {ev.quoted(j)})",
                j,
                "Jordan structure",
                True,
            )
        return None  # only the first such cluster is considered
    return None


def undecided(ev: Evidence) -> Stability:
    """No theorem or symmetry applies and an eigenvalue lies within its bound of the axis."""
    near, re = ev.near, ev.re
    i = int(near[np.argmax(re[near])])
    return ev.at(
        "undecided",
        f"lam = {_fmt(ev.lam[i])} has |Re lam| = {abs(ev.lam[i].real):.2e} within its error bound {ev.quoted(i)} "
        f"and no theorem or symmetry applies",
        i,
    )


#: The rules in the order they are tried; the last always decides.
RULES: tuple[Callable[[Evidence], Stability | None], ...] = (
    structure_theorems,
    kelvin_tait_chetaev,
    lagrange_dirichlet,
    certainly_unstable,
    certainly_asymptotic,
    defective_on_axis,
    reflection_symmetry,
    semisimple_zero,
    undecided,
)
