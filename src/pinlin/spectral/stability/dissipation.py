"""Which small damping moves an eigenvalue off the imaginary axis, and which way (theory: stability).

For D = eps D1 added to a system with a simple eigenvalue lam on the imaginary
axis, right vector x and left vector y (y^T L(lam) = 0) normalized so that
y^T L'(lam) x = 1 (L'(lam) = 2 lam M + C):

.. math::
    \\frac{d\\lambda}{d\\varepsilon} = -\\lambda\\, y^T D_1 x, \\qquad
    \\frac{d\\,\\mathrm{Re}\\,\\lambda}{d\\varepsilon} = \\langle D_1, H\\rangle,\\quad
    H = \\mathrm{sym}\\,\\mathrm{Re}(-\\lambda\\, x y^T)

for symmetric D1 (<A, B> = trace(A B)).  H is real symmetric of rank at most
2, so some positive semidefinite D1 destabilizes exactly when H has a positive
eigenvalue (then D1 = v v^T with v its eigenvector), and every positive
definite D1 does when H is positive semidefinite and nonzero.  Where a theorem
of theory: stability applies, it decides instead of the computed sign:

- N = 0, S positive definite: Re lam <= 0 for every D >= 0 (Lagrange-Dirichlet,
  Kelvin): no positive semidefinite D1 destabilizes;
- N = 0, S nonsingular with negative eigenvalues (gyroscopic stabilization):
  every positive definite D makes as many eigenvalues unstable as S has
  negative ones (Kelvin-Tait-Chetaev);
- N != 0, D = G = 0: x and y real; some D1 >= 0 destabilizes whenever they are
  not parallel (Bottema 1956), which the computed H tells (an eigenvalue of H
  above its error bound on each side of zero).

Otherwise the sign of the rate against its first-order error decides, and
"undecided" (None) is said when it lies within it.  The error of the rate is
a first-order estimate from the eigenvalue bounds r: the vectors' relative
errors are taken as max_j (r_k + r_j) / |lam_k - lam_j| (the eigenvector
perturbation of a simple eigenvalue), plus the rounding of forming y^T D1 x.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...numerics.floating import EPS
from ...results import Result

__all__ = [
    "DissipationRow", "dissipation_rows", "damping_row", "named_shapes", "axis_eigenvalues", "PSD_ROUNDING",
    "WORST_SHAPE",
]

#: A shape D1 counts as positive semidefinite (definite) when its smallest eigenvalue is above
#: -PSD_ROUNDING n eps ||D1||_2 (above +PSD_ROUNDING n eps ||D1||_2): the rounding of forming it.
PSD_ROUNDING = 10.0

#: Name of the first row of every dissipation table.
WORST_SHAPE = "some positive semidefinite D1 (the rank-one, unit-norm shape of largest rate)"

_LD = "Lagrange-Dirichlet (Kelvin)"
_KTC = "Kelvin-Tait-Chetaev"
_BOTTEMA = "Bottema"


@dataclass(frozen=True, eq=False, kw_only=True)
class DissipationRow(Result):
    """What small damping of one shape D = eps D1 does to the eigenvalues on the imaginary axis.

    Attributes
    ----------
    shape : str
        Its name ("equal dampers on every coordinate (D1 = I)", ...).
    D1 : (n, n) ndarray
        The shape, in the system's coordinates.
    destabilizes : bool or None
        True: for small eps > 0 some eigenvalue moves into Re lam > 0
        (dissipation-induced instability); False: none does; None: the computed
        rate lies within its error and no theorem decides.
    rate : float
        The largest d Re lam / d eps over the eigenvalues on the axis [1/s per unit eps].
    rate_error : float
        Its first-order error estimate (module doc) [1/s per unit eps].
    theorem : str or None
        The theorem that decided ``destabilizes``, None when the computed sign did.
    eigenvalue : complex or None
        The axis eigenvalue of that largest rate [rad/s].
    reason : str
    """

    shape: str
    D1: np.ndarray
    destabilizes: bool | None
    rate: float
    rate_error: float
    theorem: str | None
    eigenvalue: complex | None
    reason: str

    @property
    def error(self) -> float:
        return self.rate_error

    @property
    def method(self) -> str:
        return self.theorem if self.theorem is not None else "sign of the first-order rate against its error"

    elapsed = 0.0

    def __repr__(self) -> str:
        return (f"DissipationRow(shape={self.shape!r}, destabilizes={self.destabilizes}, rate={self.rate:.3g}, "
                f"rate_error={self.rate_error:.1e}, theorem={self.theorem!r})")


def axis_eigenvalues(lam: np.ndarray, r: np.ndarray, left_normalized: np.ndarray) -> np.ndarray:
    """Indices of the simple eigenvalues within their bound r of the axis, Im lam > r (one of each pair)."""
    return np.flatnonzero((np.abs(lam.real) <= r) & (lam.imag > r) & left_normalized)


def _forms(lam, X, Y, r, idx):
    """(H_k, error of H_k) for the axis eigenvalues idx (module doc)."""
    n = X.shape[0]
    out = []
    for k in idx:
        x, y = X[:, k], Y[:, k]
        H = np.real(-lam[k] * np.outer(x, y))
        H = 0.5 * (H + H.T)
        others = np.delete(np.arange(lam.shape[0]), k)
        gap = np.abs(lam[others] - lam[k])
        vec = float(np.max((r[k] + r[others]) / gap)) if others.size else 0.0
        size = np.linalg.norm(x) * np.linalg.norm(y)
        err = abs(lam[k]) * size * (2.0 * vec + PSD_ROUNDING * n * EPS) + r[k] * size
        out.append((H, float(err)))
    return out


def _psd(D1: np.ndarray) -> tuple[bool, bool]:
    """(positive semidefinite, positive definite) of the symmetric shape, within its rounding."""
    w = np.linalg.eigvalsh(D1)
    tol = PSD_ROUNDING * D1.shape[0] * EPS * max(abs(w[0]), abs(w[-1]))
    return bool(w[0] >= -tol), bool(w[0] > tol)


def _theorem(facts, psd: bool, pd: bool) -> tuple[bool | None, str | None, str]:
    """The theorem of theory: stability that decides for this shape, if any."""
    if facts is None or facts.circulatory is None or facts.circulatory:
        return None, None, ""
    base_psd = facts.definiteness_D is not None and facts.definiteness_D.certainly_psd
    if facts.stiffness == "positive_definite" and psd and base_psd:
        return False, _LD, "N = 0, S positive definite, D + eps D1 positive semidefinite: Re lam <= 0"
    neg = facts.negative_stiffness or 0
    if pd and base_psd and neg > 0 and not facts.singular_stiffness:
        return True, _KTC, (f"N = 0, D + eps D1 positive definite, S with {neg} negative eigenvalue(s): as many "
                            "eigenvalues with Re lam > 0")
    return None, None, ""


def _row(shape, D1, forms, lam, idx, facts) -> DissipationRow:
    rates = np.array([float(np.sum(D1 * H)) for H, _ in forms])
    norm = float(np.linalg.norm(D1))
    errs = np.array([norm * e for _, e in forms])
    j = int(np.argmax(rates))
    rate, err, at = float(rates[j]) + 0.0, float(errs[j]), complex(lam[idx[j]])
    psd, pd = _psd(D1)
    decided, theorem, why = _theorem(facts, psd, pd)
    if decided is None:
        if np.any(rates > errs):
            decided = True
        elif np.all(rates < -errs):
            decided = False
        why = (f"the largest rate d Re lam / d eps = {rate:.4g} (at lam = {at.imag:.6g}i) "
               + ("exceeds" if decided else "is below minus" if decided is False else "lies within")
               + f" its error {err:.1e}")
    else:
        why = f"{why} ({theorem}); computed: d Re lam / d eps = {rate:.4g} +- {err:.1e}"
    if not psd:
        why += "; D1 is not positive semidefinite (not a dissipation: it may feed energy in)"
    return DissipationRow(
        shape=shape, D1=D1, destabilizes=decided, rate=rate, rate_error=err, theorem=theorem, eigenvalue=at,
        reason=why,
    )


def _worst(forms, lam, idx, facts) -> DissipationRow:
    """The row "some positive semidefinite D1": the rank-one D1 = v v^T of the largest eigenvalue of any H_k."""
    best = None
    for j, (H, e) in enumerate(forms):
        w, V = np.linalg.eigh(H)
        if best is None or w[-1] > best[0]:
            best = (float(w[-1]), e, j, V[:, -1])
    top, err, j, v = best
    D1 = np.outer(v, v)
    row = _row(WORST_SHAPE, D1, forms, lam, idx, facts)
    if row.theorem is None and facts is not None:
        decided, theorem, why = _theorem(facts, True, True)  # a positive definite D1 exists
        if decided:
            return DissipationRow(
                shape=row.shape, D1=D1, destabilizes=True, rate=row.rate, rate_error=row.rate_error,
                theorem=theorem, eigenvalue=row.eigenvalue,
                reason=f"{why} ({theorem}) for every positive definite D1; the worst rank-one D1 "
                                                  f"computed: d Re lam / d eps = {row.rate:.4g} +- {row.rate_error:.1e}",
            )
    if row.theorem is not None or facts is None or not facts.circulatory or facts.damped or facts.gyroscopic:
        return row
    if top > err:  # x, y not parallel: H indefinite
        return DissipationRow(
            shape=row.shape, D1=D1, destabilizes=True, rate=row.rate, rate_error=row.rate_error,
            theorem=_BOTTEMA, eigenvalue=row.eigenvalue,
            reason=f"N != 0, D = G = 0 and the left and right vectors of lam = {row.eigenvalue.imag:.6g}i "
                                          f"are not parallel (the form H has the eigenvalue {top:.4g} > its error {err:.1e}): "
                                          f"some D1 >= 0 destabilizes ({_BOTTEMA} 1956)",
        )
    return row


def named_shapes(matrices, system) -> list[tuple[str, np.ndarray]]:
    """The named damping shapes in the system's coordinates."""
    M = np.asarray(matrices[0], dtype=float)
    n = M.shape[0]
    shapes = []
    if system is not None and np.any(system.D):
        shapes.append(("the system's own damping D, scaled (D1 = D)", np.array(system.D, dtype=float)))
    shapes.append(("equal dampers on every coordinate (D1 = I)", np.eye(n)))
    shapes.append(("Rayleigh, mass-proportional (D1 = M)", M.copy()))
    if system is not None:
        shapes.append(("Rayleigh, stiffness-proportional (D1 = S)", np.array(system.S, dtype=float)))
    return shapes


def dissipation_rows(matrices, system, facts, lam, X, Y, r, left_normalized) -> tuple[DissipationRow, ...]:
    """The dissipation table of a marginal verdict (module doc): the worst psd shape, then the named ones.

    Parameters
    ----------
    matrices : (M, C, K)
    system : LinearizedSystem or None
    facts : StructuralFacts or None
    lam : (2n,) complex
    X, Y : (n, 2n) complex
        Right and left vectors, y^T L'(lam) x = 1.
    r : (2n,) float
        Error bounds of lam (after the safety factor).
    left_normalized : (2n,) bool

    Returns
    -------
    tuple of DissipationRow
        Empty when no simple eigenvalue lies on the axis.
    """
    lam = np.asarray(lam, dtype=complex)
    idx = axis_eigenvalues(lam, np.asarray(r), np.asarray(left_normalized, dtype=bool))
    if not idx.size:
        return ()
    forms = _forms(lam, X, Y, np.asarray(r, dtype=float), idx)
    rows = [_worst(forms, lam, idx, facts)]
    rows += [_row(name, D1, forms, lam, idx, facts) for name, D1 in named_shapes(matrices, system)]
    return tuple(rows)


def damping_row(modes, D1, shape: str = "the given D1") -> DissipationRow | None:
    """The dissipation row of one shape D1 for a computed spectrum (``Modes``), None without axis eigenvalues.

    The eigenvalues on the axis are those within their bound (times the analysis' safety factor) of it;
    the theorems of the module doc decide where they apply, the computed sign otherwise.
    """
    lam = np.asarray(modes.eigenvalues)
    r = float(modes.tolerances["safety"]) * np.asarray(modes.error_bound)
    idx = axis_eigenvalues(lam, r, np.asarray(modes.left_normalized, dtype=bool))
    if not idx.size:
        return None
    facts = modes.structure if modes.system is not None else None
    forms = _forms(lam, modes.right, modes.left, r, idx)
    return _row(shape, np.asarray(D1, dtype=float), forms, lam, idx, facts)
