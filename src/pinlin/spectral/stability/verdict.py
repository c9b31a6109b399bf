"""The stability verdict and the theorems that decide it without eigenvalues (theory: stability).

:class:`Stability` is the verdict; :func:`theorem_verdict` applies the theorems
of theory: stability that need only the structural facts (definiteness of D and S,
N = 0, determinant signs).  The rules that also look at the computed
eigenvalues are in :mod:`pinlin.spectral.stability.rules`.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable

from ...numerics.floating import EPS
from ...results import Result
from ..qualitative import StructuralFacts

__all__ = ["Stability", "KINDS", "STABILITY_SAFETY", "MARGIN_CAP", "theorem_verdict", "mass_verdict"]

KINDS = ("asymptotically_stable", "marginally_stable", "divergence", "flutter", "undecided")

#: Default factor applied to the first-order error bounds before they decide: the
#: bounds are first-order estimates, and a decade of margin covers their
#: second-order terms for all but nearly defective eigenvalues.
STABILITY_SAFETY = 10.0

#: Largest margin looked for: a verdict that survives a relative perturbation of
#: one half of the data survives anything a margin could usefully say.
MARGIN_CAP = 0.5

_SPECTRUM_METHOD = "computed eigenvalues against their first-order error bounds"


class Stability(Result):
    """A stability verdict and why.

    An immutable value.  The verdict (``kind``, ``theorem``, ``eigenvalue``,
    ``error_bound``, ``bounded``) is decided when it is made; the ``margin``
    (a bisection that re-decides the verdict about twenty times) is computed on
    first access of ``margin``, ``error``, ``reason`` (which quotes it) or
    ``to_dict()``, and kept: a pure function of the immutable evidence, so
    concurrent first accesses compute the same number.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    reason : str
        The theorem applied, or the eigenvalue that decides and its error bound;
        for a verdict of :func:`~pinlin.spectral.stability.decide_stability`
        that decides, followed by its margin.
    theorem : str or None
        Short name of the theorem used ("Thomson-Tait-Chetaev", ...), None when
        the computed eigenvalues alone decide.
    eigenvalue : complex or None
        The deciding eigenvalue (the one farthest right, or the doubtful one) [rad/s].
    error_bound : float or None
        Its error bound after the safety factor [rad/s].
    bounded : bool or None
        True when every free motion is known to stay bounded (Lyapunov
        stable), False when some certainly grows, None when unknown.
    safety : float
        Factor applied to the first-order bounds.
    elapsed : float
        Seconds spent deciding [s] (the eigenvalues' own cost is in
        ``Modes.elapsed``; the margin's, paid on first access, is not included).
    margin : float
        The *structured* margin: the largest relative perturbation of the data
        (each matrix in its own norm, and normwise for the eigenvalue bounds)
        for which the verdict keeps its kind: the verdict decided against that
        uncertainty instead of ``uncertainty`` is the same (capped at
        :data:`MARGIN_CAP`).  A matrix that is zero stays zero, and a verdict
        that used an exact zero (D = 0, G = 0, N = 0) keeps it: ``kept`` names
        the class.  At least ``uncertainty`` for a decided verdict; 0 for
        "undecided" (no claim).
    kept : str
        The class of perturbations ``margin`` covers ("perturbations that keep
        D = 0 and G = 0 exactly ...",
        :func:`~pinlin.spectral.stability.unstructured.structure_kept`).
    unstructured_margin : float or None
        The largest relative perturbation of *all* of M, D, G, S, N under which
        the kind provably holds, to first order
        (:mod:`pinlin.spectral.stability.unstructured`): 0 for every marginal
        verdict (some arbitrarily small damping moves an axis eigenvalue off
        the axis; ``unstructured_reason`` names it) and for "undecided"; None
        for a verdict of the structure alone (no eigenvalues to measure).
    unstructured_reason : str
        What ``unstructured_margin`` claims, or which perturbation breaks the verdict.
    dissipation : tuple of DissipationRow
        For a marginal verdict, what small damping of each shape does to the
        eigenvalues on the axis (:mod:`pinlin.spectral.stability.dissipation`):
        rows with ``.shape``, ``.destabilizes``, ``.rate``, ``.rate_error``,
        ``.theorem``; empty otherwise.  Formed on first access.
    uncertainty : float
        The relative data uncertainty the verdict was decided against (0: the
        data as stored, only their rounding).
    method : str
        The theorem, or "computed eigenvalues against their first-order error bounds".
    error : float
        ``min(1, max(uncertainty, eps) / margin)``: the data's uncertainty (at
        least the unit of rounding eps) as a share of the perturbation the
        verdict survives (relative; below 1 the verdict holds beyond the
        uncertainty of the data, 1 for "undecided", whose margin is 0).

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> verdict = pinlin.modal_analysis(sys).stability
    >>> verdict.kind, verdict.theorem, verdict.bounded
    ('asymptotically_stable', 'Thomson-Tait-Chetaev', True)
    >>> bool(verdict.margin > 0.1)
    True
    """

    _dict_fields = (
        "kind", "reason", "theorem", "eigenvalue", "error_bound", "bounded", "safety", "elapsed", "margin",
        "uncertainty", "kept", "unstructured_margin", "unstructured_reason", "dissipation",
    )
    #: The fields that decide equality (the dissipation rows are a function of the same evidence).
    _key_fields = _dict_fields[:-1]

    #: Names of the lazy parts handed on by :meth:`replace`.
    _LAZY = ("kept", "unstructured_of", "dissipation_of")

    def __init__(
        self,
        kind: str,
        reason: str,
        theorem: str | None = None,
        eigenvalue: complex | None = None,
        error_bound: float | None = None,
        bounded: bool | None = None,
        safety: float = STABILITY_SAFETY,
        elapsed: float = 0.0,
        margin: float | None = 0.0,
        uncertainty: float = 0.0,
        *,
        margin_of: Callable[[], float] | None = None,
        quote_margin: bool = False,
        kept: str | None = None,
        unstructured_of: Callable[[], tuple] | None = None,
        dissipation_of: Callable[[], tuple] | None = None,
    ):
        """``margin=None`` with ``margin_of`` (a pure function of immutable data) computes it on first access;
        ``quote_margin`` appends it to the reason.  ``unstructured_of() -> (value, reason)`` and
        ``dissipation_of() -> rows`` are called on first access (None: no claim, no rows)."""
        values = {
            "kind": kind, "_basis": reason, "theorem": theorem, "eigenvalue": eigenvalue,
            "error_bound": error_bound, "bounded": bounded, "safety": safety, "elapsed": elapsed,
            "_margin": margin, "uncertainty": uncertainty, "_margin_of": margin_of, "_quote": bool(quote_margin),
            "_kept": kept, "_unstructured_of": unstructured_of, "_unstructured": None,
            "_dissipation_of": dissipation_of, "_dissipation": None,
        }
        if margin is None and margin_of is None:  # pragma: no cover (programming error)
            raise TypeError("Stability needs a margin or a function that computes it")
        self.__dict__.update(values)

    def __setattr__(self, name, value):
        raise AttributeError(f"Stability is immutable: cannot set {name!r}")

    def __delattr__(self, name):
        raise AttributeError(f"Stability is immutable: cannot delete {name!r}")

    def replace(self, **changes) -> Stability:
        """A copy with some attributes changed (as :func:`dataclasses.replace`); a lazy margin stays lazy.

        Raises
        ------
        TypeError
            An unknown attribute name.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> verdict = pinlin.modal_analysis(sys).stability
        >>> relaxed = verdict.replace(safety=2.0)
        >>> relaxed.safety, verdict.safety, relaxed.kind
        (2.0, 10.0, 'asymptotically_stable')
        """
        args = {name: changes.pop(name, getattr(self, "_basis" if name == "reason" else name))
                for name in ("kind", "reason", "theorem", "eigenvalue", "error_bound", "bounded", "safety",
                             "elapsed", "uncertainty")}
        margin = changes.pop("margin", self.__dict__["_margin"])
        margin_of = changes.pop("margin_of", self.__dict__["_margin_of"] if margin is None else None)
        quote = changes.pop("quote_margin", self._quote)
        lazy = {name: changes.pop(name, self.__dict__["_" + name]) for name in self._LAZY}
        if changes:
            raise TypeError(f"unknown Stability attributes {sorted(changes)}")
        return Stability(**args, margin=margin, margin_of=margin_of, quote_margin=quote, **lazy)

    @property
    def margin(self) -> float:
        value = self.__dict__["_margin"]
        if value is None:
            value = float(self.__dict__["_margin_of"]())
            self.__dict__["_margin"] = value  # pure function of immutable data: every thread gets this number
        return value

    @property
    def kept(self) -> str:
        kept = self.__dict__["_kept"]
        return kept if kept is not None else "perturbations of each matrix relative to its own norm"

    def _unstructured_pair(self) -> tuple:
        pair = self.__dict__["_unstructured"]
        if pair is None:
            of = self.__dict__["_unstructured_of"]
            if of is not None:
                pair = tuple(of())
            elif self.kind == "undecided":
                pair = (0.0, "0: an undecided verdict makes no claim")
            else:
                pair = (None, "not computed")
            self.__dict__["_unstructured"] = pair  # pure function of immutable data, as the margin
        return pair

    @property
    def unstructured_margin(self) -> float | None:
        return self._unstructured_pair()[0]

    @property
    def unstructured_reason(self) -> str:
        return self._unstructured_pair()[1]

    @property
    def dissipation(self) -> tuple:
        rows = self.__dict__["_dissipation"]
        if rows is None:
            of = self.__dict__["_dissipation_of"]
            rows = tuple(of()) if of is not None else ()
            self.__dict__["_dissipation"] = rows
        return rows

    @classmethod
    def _from_values(cls, values: dict):
        """Rebuild a verdict read back by :func:`pinlin.load`: the constructor's fields, and the margins and
        dissipation rows as they were saved (their inputs are not kept)."""
        params = inspect.signature(cls).parameters
        obj = cls(**{k: v for k, v in values.items() if k in params and k != "reason"}, reason=values["reason"])
        obj.__dict__["_unstructured"] = (values.get("unstructured_margin"), values.get("unstructured_reason"))
        obj.__dict__["_dissipation"] = tuple(values.get("dissipation") or ())
        return obj

    @property
    def destabilizing_shapes(self) -> tuple[str, ...]:
        """The named shapes of ``dissipation`` (the worst-case row left out) that certainly destabilize."""
        return tuple(r.shape for r in self.dissipation[1:] if r.destabilizes)

    @property
    def reason(self) -> str:
        if not self._quote:
            return self._basis
        margin = self.margin
        cap = "at least " if margin >= MARGIN_CAP else ""
        basis = self._basis
        if self.kind == "marginally_stable":
            shapes = self.destabilizing_shapes
            if shapes:
                basis += ("; marginally stable, but small damping destabilizes (dissipation-induced instability) "
                          f"for the shape(s): {'; '.join(shapes)}")
            elif self.dissipation and self.dissipation[0].destabilizes:
                basis += ("; marginally stable, but some small positive semidefinite damping destabilizes "
                          f"(dissipation-induced instability, since {self.dissipation[0].reason})")
        return (
            f"{basis}; structured margin {cap}{margin:.1e}: the verdict holds for every system within that "
            f"relative size of {self.kept}; unstructured margin {self.unstructured_reason}"
        )

    @property
    def stable(self) -> bool:
        return self.kind in ("asymptotically_stable", "marginally_stable")

    @property
    def unstable(self) -> bool:
        return self.kind in ("divergence", "flutter")

    @property
    def method(self) -> str:
        return self.theorem if self.theorem is not None else _SPECTRUM_METHOD

    @property
    def error(self) -> float:
        floor = max(self.uncertainty, EPS)
        return 1.0 if self.margin <= floor else float(floor / self.margin)

    def _key(self) -> tuple:
        return tuple(getattr(self, name) for name in self._key_fields)

    def __eq__(self, other) -> bool:
        if not isinstance(other, Stability):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __getstate__(self) -> dict:
        return dict(self.__dict__)

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)

    def __str__(self) -> str:
        return f"{self.kind.replace('_', ' ')}: {self.reason}"

    def __repr__(self) -> str:
        lam = "None" if self.eigenvalue is None else f"{complex(self.eigenvalue):.6g}"
        return (
            f"Stability(kind={self.kind!r}, theorem={self.theorem!r}, eigenvalue={lam}, "
            f"error={self.error:.2g}, bounded={self.bounded}, margin={self.margin:.2g}, "
            f"unstructured_margin={self.unstructured_margin!r})"
        )


_DET_REASON = (
    "p(lam) = det L(lam) has leading coefficient det M and p(0) = det K of opposite signs (each certain "
    "within rounding), so a real root lies in (0, inf)"
)
_TTC_REASON = (
    "N = 0, D positive definite, S positive definite (both certain within rounding): every eigenvalue has "
    "Re lam < 0 (Thomson-Tait-Chetaev, whatever G)"
)
_LD_REASON = (
    "N = 0, D = 0, S positive definite (certain within rounding): Re lam <= 0 (Lagrange-Dirichlet, whatever G) "
    "and the spectrum is symmetric under lam -> -conj(lam), so every eigenvalue lies on the imaginary axis, "
    "semisimple since the energy bounds every motion"
)


def mass_verdict(facts: StructuralFacts, *, safety: float = STABILITY_SAFETY) -> Stability | None:
    """"undecided" when M is positive definite (or, for a tuple, nonsingular) only within rounding, else None.

    Every theorem of theory: stability assumes M > 0, and a rounding-level change of
    such an M makes it singular (an infinite eigenvalue) or indefinite: the data
    decide nothing.
    """
    on_M = facts.definiteness_M
    if on_M is None:
        if facts.det_sign_M != 0:
            return None
        reason = (
            f"M is singular within rounding (relative distance to singularity {facts.det_margin_M:.1e} <= "
            f"the uncertainty {facts.uncertainty:g} plus rounding): the eigenvalues of largest modulus have no meaning"
        )
        return Stability(kind="undecided", reason=reason, safety=safety)
    if on_M.kind == "positive_definite":
        return None
    reason = (
        f"M is positive definite only within rounding: its smallest eigenvalue {on_M.min_eigenvalue:.3g} lies "
        f"within {on_M.threshold:.2g} (rounding c n eps ||M|| plus the uncertainty) of zero, so a perturbation of "
        f"the data at that level makes M singular or indefinite and moves eigenvalues to infinity: no theorem "
        f"applies and the largest eigenvalues have no meaning"
    )
    return Stability(kind="undecided", reason=reason, safety=safety)


def theorem_verdict(facts: StructuralFacts, *, safety: float = STABILITY_SAFETY) -> Stability | None:
    """The verdict the theorems of theory: stability give without any eigenvalue, or None.

    Decides (every definiteness and sign certain within rounding and the
    uncertainty, :func:`pinlin.numerics.definiteness`): sign(det M) !=
    sign(det K) => divergence; N = 0, D > 0, S > 0 => asymptotically stable
    (Thomson-Tait-Chetaev); N = 0, D = 0, S > 0 => marginally stable
    (Lagrange-Dirichlet and the reflection symmetry).  An M positive definite
    only within rounding decides "undecided" (:func:`mass_verdict`).
    Kelvin-Tait-Chetaev with an even, nonzero number of negative eigenvalues
    of S proves instability but not its kind, and D >= 0 singular with S > 0
    proves boundedness but not whether it is asymptotic: both return None
    (:func:`~pinlin.spectral.stability.decide_stability` completes them with the spectrum).
    """
    doubt = mass_verdict(facts, safety=safety)
    if doubt is not None:
        return doubt
    if facts.det_sign_M * facts.det_sign_K < 0:
        return Stability(kind="divergence", reason=_DET_REASON, theorem="sign of det K", bounded=False, safety=safety)
    if facts.damping is None or facts.circulatory:
        return None
    if facts.damping == "positive_definite" and facts.stiffness == "positive_definite":
        return Stability(
            kind="asymptotically_stable", reason=_TTC_REASON, theorem="Thomson-Tait-Chetaev", bounded=True, safety=safety
        )
    if facts.stiffness == "positive_definite" and not facts.damped:
        return Stability(
            kind="marginally_stable", reason=_LD_REASON, theorem="Lagrange-Dirichlet + symmetry", bounded=True,
            safety=safety,
        )
    return None
