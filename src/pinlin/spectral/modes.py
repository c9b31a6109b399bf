"""The result of a modal analysis (SPEC sections 4, 5 and 9)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..linearization.system import LinearizedSystem
from ..numerics.scaling import Scaling
from ..results import Result, readonly
from .multiplicity import Cluster
from .qualitative import ModeConstants, StructuralFacts
from .stability import Stability

__all__ = ["Modes", "Method", "MODE_KINDS"]

#: Per-eigenvalue kinds, see :attr:`Modes.kind`.
MODE_KINDS = ("rigid_body", "underdamped", "overdamped", "unstable")


class Method(str):
    """The solver path taken: a string equal to its name, with the reason attached.

    ``modes.method == "symmetric"`` compares the name; ``modes.method.reason``
    says why the path applies; ``modes.method.describe()`` gives both.
    """

    reason: str

    def __new__(cls, name: str, reason: str = ""):
        obj = super().__new__(cls, name)
        obj.reason = reason
        return obj

    @property
    def name(self) -> str:
        return str.__str__(self)

    def describe(self) -> str:
        return f"{self.name}: {self.reason}" if self.reason else self.name

    def __repr__(self) -> str:
        return f"Method({self.name!r}, {self.reason!r})"

    def __reduce__(self):
        return (Method, (self.name, self.reason))


@dataclass(frozen=True, eq=False, repr=False)
class Modes(Result):
    """Eigenvalues and eigenvectors of L(lam) = lam^2 M + lam C + K with their error figures.

    Order: ascending natural frequency |lam|; a complex conjugate pair is
    adjacent, the member with Im lam > 0 first; among equal |lam| the smaller
    real part comes first (so a real pair -a, +a is listed as -a, +a).

    Attributes
    ----------
    eigenvalues : (2n,) complex
        lam_k [rad/s].
    right : (n, 2n) complex
        Right eigenvectors x_k (columns), unit 2-norm: L(lam_k) x_k = 0.
    left : (n, 2n) complex
        Left eigenvectors y_k (plain transpose: y_k^T L(lam_k) = 0), scaled so
        that y_k^T L'(lam_k) x_k = 1 with L'(lam) = 2 lam M + C (Lancaster's
        normalization, so that L(s)^-1 = sum_k x_k y_k^T / (s - lam_k) when L
        is simple).  For a semisimple multiple eigenvalue the cluster's left
        vectors are biorthogonalized: Y_c^T L'(lam_c) X_c = I at the cluster
        mean lam_c.  For a defective eigenvalue no such scaling exists: y_k has
        unit 2-norm and ``left_normalized[k]`` is False.
    left_normalized : (2n,) bool
    backward_error : (2n,) float
        eta of (lam_k, x_k), Frobenius norms (SPEC section 4).
    condition : (2n,) float
        kappa of lam_k in the homogeneous form (SPEC section 4); inf for a
        defective eigenvalue.
    error_bound : (2n,) float
        First-order absolute error estimate of lam_k [rad/s]: eta times
        Tisseur's absolute condition number (SPEC section 5's kappa eta |lam|),
        with eta at least machine epsilon.
        For a defective cluster: the spread of the cluster plus
        c eta^(1/p), p the longest chain and c of
        :func:`pinlin.spectral.accuracy.defective_scale` (about max(|lam_c|, gamma)).
    natural_frequency : (2n,) float
        |lam_k| [rad/s].
    damping_ratio : (2n,) float
        -Re lam_k / |lam_k|; NaN for lam_k = 0 exactly (undefined; the kind is
        then "rigid_body").
    kind : tuple of str
        Per eigenvalue, one of :data:`MODE_KINDS`: "rigid_body" (|lam| within
        its error bound of 0), "unstable" (Re lam above its error bound),
        "underdamped" (|Im lam| above its error bound), "overdamped" (real,
        negative; critically damped included).  Bounds at the data uncertainty, times ``safety``;
        members of a cluster are classified by the cluster's mean.
    multiplicity : (2n,) int
        Algebraic multiplicity of the (cluster of the) eigenvalue.
    clusters : tuple of Cluster
        Multiple eigenvalues with their partial multiplicities (SPEC section 4).
    is_simple : bool
        True when every eigenvalue is semisimple (the dynamic stiffness is simple).
    constants : ModeConstants or None
        m, d, g, k, n per mode and the residual of their equation (SPEC
        section 5); None for tuple input.
    structure : StructuralFacts
        Definiteness, inertia and determinant signs used by the verdict, each
        decided against the rounding bound of the data and the uncertainty
        (``structure.definiteness_M``, ``_D``, ``_S`` carry the numbers; the
        command-line report shows these very decisions).
    stability : Stability
        The verdict (``.kind``, ``.reason``, ``.margin``: how large a relative
        perturbation of the data it survives).
    method : Method
        Solver path ("symmetric", "squared", "proportional", "general") with
        ``.reason`` (in ``to_dict()``: ``method`` and ``method_reason``).
    scaling : Scaling or None
        Fan-Lin-Van Dooren parameters used by the general path (None if none).
        A heavily damped problem is also solved with the tropical scalings (two
        more QZ runs), which ``method.reason`` describes.
    block : (2n,) int
        Companion block each right vector was recovered from (general path; 0
        for structured paths).
    tolerances : mapping
        cluster_tol, rank_tol, structure_tol, uncertainty (the relative data
        uncertainty of the decisions), safety, eigh_tol.
    system : LinearizedSystem or None
        The system analysed (None for tuple input).
    matrices : tuple of (n, n) ndarray
        (M, C, K) as analysed.
    elapsed : float
        Seconds spent in :func:`modal_analysis` [s].
    notes : tuple of str
    error : float
        The largest backward error eta of the eigenpairs, ``max(backward_error)``
        (relative, SPEC section 4); the per-pair figures are ``backward_error``,
        ``condition`` and ``error_bound``.

    ``to_dict()`` leaves out ``system`` and ``matrices`` (the input).
    """

    _dict_exclude = ("system", "matrices")

    eigenvalues: np.ndarray
    right: np.ndarray
    left: np.ndarray
    left_normalized: np.ndarray
    backward_error: np.ndarray
    condition: np.ndarray
    error_bound: np.ndarray
    natural_frequency: np.ndarray
    damping_ratio: np.ndarray
    kind: tuple[str, ...]
    multiplicity: np.ndarray
    clusters: tuple[Cluster, ...]
    is_simple: bool
    constants: ModeConstants | None
    structure: StructuralFacts
    stability: Stability
    method: Method
    scaling: Scaling | None
    block: np.ndarray
    tolerances: Mapping[str, float]
    system: LinearizedSystem | None
    matrices: tuple[np.ndarray, np.ndarray, np.ndarray]
    elapsed: float
    notes: tuple[str, ...] = field(default=())

    def __post_init__(self):
        for name in (
            "eigenvalues",
            "right",
            "left",
            "left_normalized",
            "backward_error",
            "condition",
            "error_bound",
            "natural_frequency",
            "damping_ratio",
            "multiplicity",
            "block",
        ):
            object.__setattr__(self, name, readonly(getattr(self, name)))

    # ------------------------------------------------------------------ access

    @property
    def n(self) -> int:
        """Number of coordinates (there are 2n eigenvalues)."""
        return self.right.shape[0]

    def __len__(self) -> int:
        return self.eigenvalues.shape[0]

    @property
    def is_semisimple(self) -> np.ndarray:
        """(2n,) bool: the eigenvalue (or its cluster) has only chains of length one."""
        out = np.ones(len(self), dtype=bool)
        for c in self.clusters:
            out[list(c.indices)] = c.semisimple
        return out

    @property
    def max_backward_error(self) -> float:
        return float(np.max(self.backward_error))

    @property
    def error(self) -> float:
        """``max(backward_error)``: the headline error figure (see the class docstring)."""
        return self.max_backward_error

    def to_dict(self) -> dict:
        """JSON-serializable data: every field but ``system`` and ``matrices``, ``method_reason`` added."""
        out = super().to_dict()
        out["method_reason"] = self.method.reason
        return out

    @property
    def frequency_hz(self) -> np.ndarray:
        """|lam| / (2 pi) [Hz]."""
        return self.natural_frequency / (2 * np.pi)

    # ------------------------------------------------------------------ text

    def table(self, max_rows: int | None = 40) -> str:
        """A text table of lam, |lam|, damping ratio, eta, kappa and kind, then the verdict.

        Parameters
        ----------
        max_rows : int or None
            Show at most this many eigenvalues (the lowest frequencies); None for all.
        """
        k = len(self)
        rows = range(k) if max_rows is None else range(min(k, max_rows))
        head = (
            f"{'#':>4}  {'Re lam [1/s]':>13} {'Im lam [rad/s]':>14} {'|lam| [rad/s]':>13} "
            f"{'zeta':>10} {'eta':>8} {'kappa':>8} {'bound':>8} {'mult':>4}  kind"
        )
        lines = [
            f"Modal analysis: n = {self.n}, {k} eigenvalues, method {self.method.describe()}",
            head,
            "-" * len(head),
        ]
        for i in rows:
            lam = self.eigenvalues[i]
            zeta = self.damping_ratio[i]
            zs = "nan" if np.isnan(zeta) else f"{zeta:.4g}"
            lines.append(
                f"{i + 1:>4}  {lam.real:>13.6g} {lam.imag:>14.6g} {self.natural_frequency[i]:>13.6g} "
                f"{zs:>10} {self.backward_error[i]:>8.1e} {self.condition[i]:>8.1e} "
                f"{self.error_bound[i]:>8.1e} {self.multiplicity[i]:>4}  {self.kind[i]}"
            )
        if len(rows) < k:
            lines.append(f"... {k - len(rows)} more (higher frequencies)")
        lines.append(f"max eta {self.max_backward_error:.2e}; dynamic stiffness simple: {self.is_simple}")
        lines.append(f"stability: {self.stability}")
        for note in self.notes:
            lines.append(f"note: {note}")
        return "\n".join(lines)

    summary = table

    def __repr__(self) -> str:
        return (
            f"Modes(n={self.n}, method={self.method.name!r}, stability={self.stability.kind!r}, "
            f"max_eta={self.max_backward_error:.1e}, elapsed={self.elapsed:.3g}s)"
        )
