"""What class of perturbations a margin covers, and the unstructured margin (theory: stability).

The structured margin (:attr:`~pinlin.spectral.Stability.margin`) perturbs each
of M, C, K relative to its own norm and decides again with the same rules: a
matrix that is zero stays zero, and a verdict that used an exact zero (D = 0,
G = 0, N = 0, K = 0) keeps it.  :func:`structure_kept` names what it kept.

The unstructured margin allows every real perturbation of all of M, D, G, S, N:

.. math::
    \\|\\Delta M\\|_F \\le \\delta \\|M\\|_F,\\quad
    \\|\\Delta C\\|_F \\le \\delta\\, c_C,\\quad
    \\|\\Delta K\\|_F \\le \\delta \\|K\\|_F,\\qquad
    c_C = \\max(\\|C\\|_F, \\sqrt{\\|M\\|_F \\|K\\|_F})

(Delta C = Delta D + Delta G, Delta K = Delta S + Delta N arbitrary; c_C is the
damping scale of the system, twice the critical damping of a unit oscillator,
so a zero C may become damping of that relative size).  To first order an
eigenvalue moves by at most delta s_k with

.. math::
    s_k = \\frac{(|\\lambda_k|^2\\|M\\|_F + |\\lambda_k| c_C + \\|K\\|_F)\\|x_k\\|\\|y_k\\|}{|y_k^T L'(\\lambda_k) x_k|}

(Tisseur's condition number with these weights), and the computed one is
within eta_k s_k of the exact one.  So, to first order:

- asymptotically stable: delta_u = min_k (|Re lam_k| / (f s_k) - eta_k);
- unstable: delta_u = max over Re lam_k > 0 of (Re lam_k / (f s_k) - eta_k);

with f the verdict's safety factor on first-order bounds (as for the structured margin);
- marginally stable: 0, since some arbitrarily small damping moves an eigenvalue
  on the axis off it (which one and which way: the dissipation table);
- undecided: 0 (no claim).

Members of a defective cluster use the bound spread + scale (eta + delta)^(1/p)
of :class:`~pinlin.spectral.accuracy.DefectiveBound` (scale taken with the
weights above).  The value is capped at :data:`~pinlin.spectral.stability.MARGIN_CAP`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..accuracy import ErrorModel

__all__ = ["structure_kept", "UnstructuredQuestion", "damping_scale"]


def damping_scale(norms: tuple[float, float, float]) -> float:
    """c_C = max(||C||_F, sqrt(||M||_F ||K||_F)): the size a perturbation of C is measured against."""
    nM, nC, nK = norms
    return float(max(nC, np.sqrt(nM * nK)))


def structure_kept(theorem: str | None, facts) -> str:
    """The class of perturbations the structured margin of a verdict decided by ``theorem`` covers."""
    own = "each of M, C = D + G, K = S + N relative to its own norm"
    if theorem == "reflection symmetry":
        zero = "N = 0" if facts is not None and facts.gyroscopic else "G = 0"
        return f"perturbations that keep D = 0 and {zero} exactly ({own})"
    if theorem == "Lagrange-Dirichlet + symmetry":
        return f"perturbations that keep the system conservative, D = 0 and N = 0 exactly ({own})"
    if theorem in ("Lagrange-Dirichlet", "Thomson-Tait-Chetaev", "Kelvin-Tait-Chetaev"):
        return f"perturbations that keep N = 0 exactly and M, D, S symmetric ({own})"
    if theorem == "sign of det K":
        return "every perturbation of M and K, each relative to its own norm"
    if theorem == "Jordan structure":
        return f"perturbations that keep K = 0 exactly ({own})"
    if theorem == "Jordan structure + exact drift":
        return f"perturbations that keep K[:, j] = C[:, j] = 0 exactly ({own})"
    return f"first-order, normwise perturbations of {own} (a zero matrix stays zero)"


@dataclass(frozen=True, eq=False)
class UnstructuredQuestion:
    """The unstructured margin of a verdict as a function of immutable evidence (called on first access).

    Returns ``(value, reason)`` (module doc).  ``rows`` gives the dissipation
    table of a marginal verdict (a callable, so that it is formed only here).
    """

    kind: str
    lam: np.ndarray | None
    model: ErrorModel | None
    norms: tuple[float, float, float]
    rows: object = None
    cap: float = 0.5
    safety: float = 1.0

    def __call__(self) -> tuple[float | None, str]:
        if self.kind == "undecided":
            return 0.0, "0: an undecided verdict makes no claim"
        if self.kind == "marginally_stable":
            return 0.0, self._marginal()
        if self.lam is None:
            return None, "not computed: the verdict was made from the structure alone, without eigenvalues"
        delta = self._first_order()
        cap = "at least " if delta >= self.cap else ""
        return min(delta, self.cap), (
            f"{cap}{min(delta, self.cap):.1e}: first-order, for every real perturbation of all of M, D, G, S, N "
            f"with ||dM|| <= delta ||M||, ||dD + dG|| <= delta c_C, ||dS + dN|| <= delta ||K|| (Frobenius; "
            f"c_C = {damping_scale(self.norms):.3g}, the damping scale), none moves the deciding eigenvalues "
            f"across the imaginary axis (their first-order bounds times the safety factor {self.safety:g})")

    def _marginal(self) -> str:
        rows = tuple(self.rows()) if self.rows is not None else ()
        if not rows:
            return ("0: the eigenvalues on the imaginary axis leave it under arbitrarily small perturbations "
                    "of C or K (no simple eigenvalue with Im lam > 0 lies on the axis to name)")
        pick = next((r for r in rows[1:] if r.destabilizes), None) or (rows[0] if rows[0].destabilizes else None)
        if pick is not None:
            return (f"0: damping D = eps D1 of shape {pick.shape} moves lam = {pick.eigenvalue.imag:.6g}i into "
                    f"Re lam > 0 at d Re lam / d eps = {pick.rate:.3g} (dissipation-induced instability)")
        row = next((r for r in rows[1:] if r.shape.startswith("equal")), rows[0])
        return (f"0: damping D = eps D1 of shape {row.shape} moves lam = {row.eigenvalue.imag:.6g}i off the "
                f"axis at d Re lam / d eps = {row.rate:.3g} (the verdict's kind changes for every eps > 0)")

    def _first_order(self) -> float:
        lam, model = self.lam, self.model
        nM, nC, nK = self.norms
        a = np.abs(lam)
        w = a * a * nM + a * nC + nK
        wu = a * a * nM + a * damping_scale(self.norms) + nK
        with np.errstate(invalid="ignore", divide="ignore"):
            s = self.safety * model.sensitivity * np.where(w > 0, wu / np.where(w > 0, w, 1.0), 1.0)
            delta = np.abs(lam.real) / s - model.eta
        for d in model.defective:
            j = d.indices[0]
            ratio = (wu[j] / w[j]) ** (1.0 / d.index) if w[j] > 0 else 1.0
            room = max(abs(lam[j].real) / self.safety - d.spread, 0.0) / (d.scale * ratio)
            delta[list(d.indices)] = room**d.index - d.eta
        delta = np.nan_to_num(delta, nan=0.0, posinf=self.cap)
        if self.kind == "asymptotically_stable":
            value = float(np.min(delta))
        else:
            value = float(np.max(np.where(lam.real > 0, delta, 0.0)))
        return max(value, 0.0)
