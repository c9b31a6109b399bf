"""The stability verdict from Floquet multipliers and their error bounds (theory: stability, Floquet).

Mapping to :data:`pinlin.spectral.stability.verdict.KINDS` (each multiplier mu with bound b, widened by ``safety``):

- "asymptotically_stable": every non-trivial |mu| + safety b < 1;
- "divergence": some |mu| - safety b > 1 and the multiplier of largest modulus among those is real positive
  (|Im mu| <= safety b): a solution growing without oscillation (in the Floquet sense: a T-periodic factor);
- "flutter": the same, with that multiplier complex or negative real (mu < -1: period doubling, a solution
  of period 2 T growing);
- "marginally_stable": none outside, some within their bounds of the unit circle, and the monodromy is
  symplectic for a known form Omega (conservative: Phi^T Omega Phi = Omega, so multipliers come in pairs
  mu, 1 / conj(mu)): a multiplier isolated from every other by more than 2 ||mu| - 1| + safety (3 b + b')
  lies on the circle (its partner 1 / conj(mu) would be that close); a cluster of multipliers that are not
  isolated is stable when the Krein form i z^H Omega z is definite on their eigenvectors (all signatures
  agree: strongly stable), and "undecided" otherwise, naming the cluster;
- "undecided": a multiplier within its bound of the circle with no structure to decide, or a mixed-signature
  collision.

Trivial multipliers (an autonomous orbit's 1, with its Jordan partner) are excluded and named in the reason.
``margin`` (first order, capped at 0.5): the relative perturbation of the segment transitions Phi_j
(||E_j|| <= delta ||Phi_j||) that the verdict survives, with kappa_k the multipliers' relative condition
(:func:`pinlin.periodic.bounds.relative_condition`): min_k |1 - |mu_k|| / (|mu_k| kappa_k) over the deciding
multipliers (all for "asymptotically_stable", the unstable one for an instability); for "marginally_stable"
the structured margin, half the distance from each near-circle multiplier (or cluster) to the nearest other
one, over |mu_k| kappa_k (a conservative perturbation keeps them on the circle until they collide); 0 for
"undecided".  It is a statement about the integration's data (the step transitions), not about M, C, K.
"""

from __future__ import annotations

import numpy as np

from ..spectral.stability.verdict import Stability

__all__ = ["floquet_verdict", "KREIN_TOLERANCE", "MARGIN_LIMIT"]

#: Largest margin reported (as :data:`pinlin.spectral.stability.verdict.MARGIN_CAP`).
MARGIN_LIMIT = 0.5

#: Relative size below which an eigenvalue of the Krein form on a cluster counts as zero (indefinite).
KREIN_TOLERANCE = 1e-8


def _clusters(mu: np.ndarray, b: np.ndarray, near: np.ndarray) -> list:
    """Groups of near-circle multipliers that are not isolated from each other (connected components)."""
    idx = list(np.flatnonzero(near))
    parent = {i: i for i in idx}

    def root(i):
        while parent[i] != i:
            i = parent[i]
        return i

    for a in idx:
        for c in idx:
            if a < c:
                reach = 2 * max(abs(abs(mu[a]) - 1), abs(abs(mu[c]) - 1)) + 3 * max(b[a], b[c]) + min(b[a], b[c])
                if abs(mu[a] - mu[c]) <= reach:
                    parent[root(a)] = root(c)
    groups: dict = {}
    for i in idx:
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def _krein_definite(vectors: np.ndarray, form: np.ndarray) -> bool:
    """Is i Z^H Omega Z (Hermitian) definite on the cluster's eigenvectors Z (columns)?"""
    H = 1j * vectors.conj().T @ form @ vectors
    ev = np.linalg.eigvalsh((H + H.conj().T) / 2)
    scale = max(float(np.max(np.abs(ev))), np.finfo(float).tiny)
    return bool(np.all(ev > KREIN_TOLERANCE * scale) or np.all(ev < -KREIN_TOLERANCE * scale))


def _margin(values) -> float:
    values = [v for v in values if np.isfinite(v)]
    return float(min(MARGIN_LIMIT, min(values))) if values else 0.0


def _unstable(mu, b, outside, kappa) -> Stability:
    k = max(np.flatnonzero(outside), key=lambda i: abs(mu[i]))
    real_positive = abs(mu[k].imag) <= b[k] and mu[k].real > 0
    kind = "divergence" if real_positive else "flutter"
    shape = "real positive" if real_positive else ("negative real (period doubling)"
                                                   if abs(mu[k].imag) <= b[k] else "complex")
    reason = (f"multiplier {complex(mu[k]):.6g} ({shape}, |mu| = {abs(mu[k]):.6g}) lies outside the unit circle "
              f"beyond its error bound {b[k]:.2g}")
    margin = _margin([(abs(mu[k]) - 1) / (abs(mu[k]) * kappa[k])])
    return Stability(kind, reason, None, complex(mu[k]), float(b[k]), False, margin=margin)


def floquet_verdict(multipliers, bounds, *, trivial=None, form=None, vectors=None, condition=None,
                    safety: float = 10.0, trivial_note: str = "") -> Stability:
    """The verdict from multipliers, their bounds and (optionally) a conserved form.

    Parameters
    ----------
    multipliers, bounds : ndarray (m,)
        mu_k and their error bounds (absolute).
    trivial : bool ndarray (m,) or None
        Multipliers set apart (autonomous orbit).
    form : (m, m) ndarray or None
        Omega with Phi^T Omega Phi = Omega (the system is conservative), or None.
    vectors : (m, m) ndarray or None
        Right eigenvectors of the monodromy at t = 0 (columns), needed with ``form``.
    condition : ndarray (m,) or None
        Relative condition kappa_k of each multiplier, for the margin (None: margin 0).
    safety : float
        Factor applied to the bounds before they decide.

    Examples
    --------
    >>> from pinlin.periodic.floquet_verdict import floquet_verdict
    >>> print(floquet_verdict(np.array([0.5, 0.2]), np.array([1e-12, 1e-12])).kind)
    asymptotically_stable
    >>> print(floquet_verdict(np.array([1.5, 0.2]), np.array([1e-12, 1e-12])).kind)
    divergence
    """
    mu = np.asarray(multipliers, dtype=complex)
    b = safety * np.asarray(bounds, dtype=float)
    keep = np.ones(mu.size, bool) if trivial is None else ~np.asarray(trivial, bool)
    r = np.abs(mu)
    kappa = np.full(mu.size, np.inf) if condition is None else np.asarray(condition, dtype=float)
    outside, inside = keep & (r - b > 1), keep & (r + b < 1)
    near = keep & ~outside & ~inside
    if outside.any():
        return _unstable(mu, b, outside, kappa)
    if not near.any():
        k = max(np.flatnonzero(keep), key=lambda i: r[i]) if keep.any() else None
        if k is None:
            return Stability("undecided", "every multiplier is trivial" + trivial_note)
        reason = (f"every multiplier lies inside the unit circle beyond its error bound; the largest, "
                  f"{complex(mu[k]):.6g}, has |mu| = {r[k]:.6g} +- {b[k]:.2g}{trivial_note}")
        margin = _margin([(1 - r[i]) / (r[i] * kappa[i]) for i in np.flatnonzero(keep)])
        return Stability("asymptotically_stable", reason, None, complex(mu[k]), float(b[k]), True, margin=margin)
    k = max(np.flatnonzero(near), key=lambda i: r[i])
    if form is None:
        reason = (f"multiplier {complex(mu[k]):.6g} lies within its error bound {b[k]:.2g} of the unit circle "
                  f"(||mu| - 1| = {abs(r[k] - 1):.2g}) and no structure decides (not known to be conservative)"
                  f"{trivial_note}")
        return Stability("undecided", reason, None, complex(mu[k]), float(b[k]), None)
    groups = _clusters(mu, b, near)
    for group in groups:
        if len(group) > 1 and not _krein_definite(vectors[:, group], form):
            shown = ", ".join(f"{complex(mu[i]):.6g} (+- {b[i]:.2g})" for i in group)
            reason = (f"multipliers {shown} collide on the unit circle with Krein signatures that differ: "
                      f"a conservative perturbation may move them off it{trivial_note}")
            return Stability("undecided", reason, "Krein signature", complex(mu[group[0]]),
                             float(b[group[0]]), None)
    reason = (f"the system is conservative (symplectic monodromy): multiplier {complex(mu[k]):.6g}, within "
              f"its error bound {b[k]:.2g} of the unit circle, lies on it (simple, or in a cluster of equal "
              f"Krein signature), and no multiplier lies outside{trivial_note}")
    gaps = []
    for group in groups:
        others = [j for j in np.flatnonzero(keep) if j not in group]
        for i in group:
            gap = min((abs(mu[i] - mu[j]) for j in others), default=2.0)
            gaps.append(gap / 2 / (r[i] * kappa[i]))
    return Stability("marginally_stable", reason, "symplectic monodromy (Krein)", complex(mu[k]),
                     float(b[k]), True, margin=_margin(gaps))
