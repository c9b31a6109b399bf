"""The result of a modal analysis (theory: spectrum, stability, conventions)."""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from ..linearization.system import LinearizedSystem
from ..numerics.accuracy import condition_numbers
from ..numerics.arrays import readonly
from ..numerics.scaling import Scaling
from ..results import Result, persistent
from .deferred import DeferredFigures, DeferredVerdict
from .energy import mode_energy
from .multiplicity import Cluster
from .participation import DOMINANT_COUNT, DOMINANT_SHARE, participation
from .qualitative import ModeConstants, StructuralFacts, constants_of
from .stability import Stability
from .tables import modes_frame

__all__ = ["Modes", "Method", "MODE_KINDS", "DeferredFigures", "DeferredVerdict"]

#: Per-eigenvalue kinds, see :attr:`Modes.kind`.
MODE_KINDS = ("rigid_body", "underdamped", "overdamped", "unstable", "undamped")

@persistent
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


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class Modes(Result):
    """Eigenvalues and eigenvectors of L(lam) = lam^2 M + lam C + K with their error figures.

    Order: ascending |lam|; a conjugate pair adjacent, Im lam > 0 first; among equal |lam| the
    smaller real part first (docs/conventions.md).  The parts marked "on first access" are pure
    functions of data the result keeps (:mod:`pinlin.spectral.deferred`): their values do not
    depend on when or from which thread they are read.  Every check that can raise runs in
    :func:`~pinlin.spectral.modal_analysis` itself.

    Attributes
    ----------
    eigenvalues : (2n,) complex
        lam_k [rad/s].
    right : (n, 2n) complex
        Right eigenvectors x_k (columns), unit 2-norm: L(lam_k) x_k = 0.
    left : (n, 2n) complex
        Left eigenvectors y_k (y_k^T L(lam_k) = 0) with y_k^T L'(lam_k) x_k = 1 (biorthogonalized
        within a semisimple cluster); unit 2-norm where ``left_normalized[k]`` is False (defective).
    left_normalized : (2n,) bool
    backward_error : (2n,) float
        eta of (lam_k, x_k), Frobenius norms (theory: spectrum).
    condition : (2n,) float
        kappa of lam_k in the homogeneous form; inf when defective.  On first access.
    error_bound : (2n,) float
        First-order absolute error estimate of lam_k [rad/s] (theory: error figures).
    natural_frequency, damping_ratio : (2n,) float
        |lam_k| [rad/s] and -Re lam_k / |lam_k| (NaN for lam_k = 0).
    kind : tuple of str
        Per eigenvalue one of :data:`MODE_KINDS`, against its bound times ``safety``.
    multiplicity : (2n,) int
        Algebraic multiplicity of the (cluster of the) eigenvalue.
    clusters : tuple of Cluster
        Multiple eigenvalues with their partial multiplicities.
    is_simple : bool
        Every eigenvalue semisimple (the dynamic stiffness is simple).
    constants : ModeConstants or None
        m, d, g, k, n per mode (None for tuple input).  On first access.
    participation : (n, 2n) float
        Each coordinate's share of each mode's energy (columns sum to 1).  On first access.
    structure : StructuralFacts
        Definiteness, inertia and determinant signs the verdict uses.  On first access.
    stability : Stability
        The verdict (``.kind``, ``.reason``, ``.margin``).  On first access.
    method : Method
        Solver path ("symmetric", "squared", "proportional", "general") with ``.reason``.
    scaling : Scaling or None
        Fan-Lin-Van Dooren parameters of the general path.
    block : (2n,) int
        Companion block each right vector came from (0 on structured paths).
    tolerances : mapping
        cluster_tol, rank_tol, structure_tol, uncertainty, safety, eigh_tol.
    system : LinearizedSystem or None
        The system analysed (None for tuple input); ``matrices``: (M, C, K) as analysed.
    elapsed : float
        Seconds spent in :func:`modal_analysis` [s], without the parts formed later.
    notes : tuple of str
        What the analysis found worth saying.  On first access.
    error : float
        ``max(backward_error)``.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> modes = pinlin.modal_analysis(sys)
    >>> modes.n, len(modes), modes.method.name
    (2, 4, 'proportional')
    >>> np.round(modes.natural_frequency[::2], 6), np.round(modes.damping_ratio[::2], 6)
    (array([1.      , 1.732051]), array([0.05    , 0.028868]))
    >>> np.round(modes.frequency_hz[::2], 6), bool(modes.is_semisimple.all())
    (array([0.159155, 0.275664]), True)
    >>> modes.kind[0], bool(modes.error < 1e-14)
    ('underdamped', True)
    """

    _dict_exclude = ("system", "matrices", "deferred", "verdict")

    #: The fields in ``to_dict()`` in the order of pinlin 0.2 (structure, stability and notes are formed on
    #: first access, so they are no dataclass fields).
    _dict_fields = (
        "eigenvalues", "right", "left", "left_normalized", "backward_error", "error_bound", "natural_frequency",
        "damping_ratio", "kind", "multiplicity", "clusters", "is_simple", "structure", "stability", "method",
        "scaling", "block", "tolerances", "elapsed", "notes",
    )

    eigenvalues: np.ndarray
    right: np.ndarray
    left: np.ndarray
    left_normalized: np.ndarray
    backward_error: np.ndarray
    error_bound: np.ndarray
    natural_frequency: np.ndarray
    damping_ratio: np.ndarray
    kind: tuple[str, ...]
    multiplicity: np.ndarray
    clusters: tuple[Cluster, ...]
    is_simple: bool
    method: Method
    scaling: Scaling | None
    block: np.ndarray
    tolerances: Mapping[str, float]
    system: LinearizedSystem | None
    matrices: tuple[np.ndarray, np.ndarray, np.ndarray]
    elapsed: float
    deferred: DeferredFigures | None = field(default=None, repr=False)
    verdict: DeferredVerdict | None = field(default=None, repr=False)

    def __post_init__(self):
        for name in ("eigenvalues", "right", "left", "left_normalized", "backward_error", "error_bound",
                     "natural_frequency", "damping_ratio", "multiplicity", "block"):
            value = getattr(self, name)
            if not (isinstance(value, np.ndarray) and value.flags.owndata and not value.flags.writeable):
                object.__setattr__(self, name, readonly(value))  # an array nobody else can write is kept

    # ------------------------------------------------------------------ figures formed on first access

    @functools.cached_property
    def structure(self) -> StructuralFacts:
        """Definiteness, inertia and determinant signs (see the class docstring)."""
        return self.verdict.facts()

    @functools.cached_property
    def stability(self) -> Stability:
        """The stability verdict (see the class docstring)."""
        return self.verdict.stability(self.structure)

    @functools.cached_property
    def notes(self) -> tuple[str, ...]:
        """What the analysis found worth saying (see the class docstring)."""
        return self.verdict.all_notes(self.structure)

    @functools.cached_property
    def condition(self) -> np.ndarray:
        """(2n,) kappa per eigenvalue (see the class docstring)."""
        d = self.deferred
        out = condition_numbers(self.eigenvalues, *d.products, d.norms)
        out[list(d.defective)] = np.inf
        out.flags.writeable = False
        return out

    @functools.cached_property
    def constants(self) -> ModeConstants | None:
        """m, d, g, k, n per mode (see the class docstring); None for tuple input."""
        if self.system is None:
            return None
        M, C, K = self.matrices
        d = self.deferred
        return constants_of(self.eigenvalues, np.asarray(self.right), d.quadratic, M, C, K, d.norms[0])

    @functools.cached_property
    def participation(self) -> np.ndarray:
        """(n, 2n) share of each coordinate in each mode's kinetic plus potential energy (columns sum to 1).

        See :func:`participation`; for tuple input M and K enter
        by their symmetric parts.
        """
        M, _, K = self.matrices
        S = self.system.S if self.system is not None else 0.5 * (K + K.T)
        M = self.system.M if self.system is not None else 0.5 * (M + M.T)
        out = participation(self.eigenvalues, self.right, M, S)
        out.flags.writeable = False
        return out

    @property
    def dof_names(self) -> tuple[str, ...]:
        """The coordinates' names (the system's, or x1 ... xn for tuple input)."""
        if self.system is not None:
            return tuple(self.system.dof_names)
        saved = self.__dict__.get("_loaded", {}).get("dof_names")  # read back by pinlin.load
        return tuple(saved) if saved is not None else tuple(f"x{i + 1}" for i in range(self.n))

    def dominant(self, share: float = DOMINANT_SHARE, count: int | None = DOMINANT_COUNT) -> list:
        """Per mode, the coordinates with at least ``share`` of its energy: [(name, share), ...], largest first.

        Parameters
        ----------
        share : float
            Smallest participation listed, in (0, 1] (default :data:`DOMINANT_SHARE`).
        count : int or None
            At most this many per mode (None: all).

        Raises
        ------
        ParameterError
            ``share`` not in (0, 1], or ``count`` not a positive integer.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> pinlin.modal_analysis(sys).dominant()[0]
        [('x1', 0.5), ('x2', 0.5)]
        """
        if not isinstance(share, (int, float, np.floating)) or isinstance(share, bool) or not 0 < share <= 1:
            raise ParameterError("share", f"expected a share in (0, 1], got {share!r}")
        if count is not None and (isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1):
            raise ParameterError("count", f"expected a positive integer or None, got {count!r}")
        names = self.dof_names
        out = []
        for k in range(len(self)):
            p = self.participation[:, k]
            order = [int(i) for i in np.argsort(-p, kind="stable") if p[i] >= share]
            out.append([(names[i], float(p[i])) for i in order[:count]])
        return out

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
        """JSON-serializable data: every field but ``system`` and ``matrices``; ``condition``, ``constants``,
        ``participation`` (n, 2n), ``dominant`` (per mode, the coordinates of :meth:`dominant` with their
        shares), ``method_reason`` and ``dof_names`` added.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> data = pinlin.modal_analysis(sys).to_dict()
        >>> data["method"], data["dof_names"]
        ('proportional', ['x1', 'x2'])
        """
        dominant = [[{"name": name, "share": p} for name, p in row] for row in self.dominant()]
        return super().to_dict(extra={"condition": self.condition, "constants": self.constants, "participation":
                                      self.participation, "dominant": dominant, "method_reason": self.method.reason,
                                      "dof_names": self.dof_names})

    @property
    def frequency_hz(self) -> np.ndarray:
        """|lam| / (2 pi) [Hz]."""
        return self.natural_frequency / (2 * np.pi)

    # ------------------------------------------------------------------ text

    def table(self, max_rows: int | None = 40) -> str:
        """A text table of lam, |lam| [rad/s] and [Hz], damping ratio, eta, kappa, kind, dominant coordinates, verdict.

        The last column lists each mode's dominant coordinates with their share of its
        kinetic plus potential energy (:meth:`dominant`, :attr:`participation`).

        Parameters
        ----------
        max_rows : int or None
            Show at most this many eigenvalues (the lowest frequencies); None for all.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> print(pinlin.modal_analysis(sys).table(max_rows=2))
        Modal analysis: n = 2, 4 eigenvalues, method proportional: ...
           #   Re lam [1/s] Im lam [rad/s] |lam| [rad/s]      f [Hz] ...
        ...
           1          -0.05       0.998749             1    0.159155 ...
        ...
        """
        k = len(self)
        rows = range(k) if max_rows is None else range(min(k, max_rows))
        head = (
            f"{'#':>4}  {'Re lam [1/s]':>13} {'Im lam [rad/s]':>14} {'|lam| [rad/s]':>13} {'f [Hz]':>11} "
            f"{'zeta':>10} {'eta':>8} {'kappa':>8} {'bound':>8} {'mult':>4}  {'kind':<11}  dominant coordinates"
        )
        dominant = self.dominant()
        lines = [
            f"Modal analysis: n = {self.n}, {k} eigenvalues, method {self.method.describe()}",
            head,
            "-" * len(head),
        ]
        for i in rows:
            lam = self.eigenvalues[i]
            zeta = self.damping_ratio[i]
            zs = "nan" if np.isnan(zeta) else f"{zeta + 0.0:.4g}"  # (+ 0.0: no "-0" for an undamped mode)
            lines.append(
                f"{i + 1:>4}  {lam.real + 0.0:>13.6g} {lam.imag + 0.0:>14.6g} {self.natural_frequency[i]:>13.6g} "
                f"{self.frequency_hz[i]:>11.6g} "
                f"{zs:>10} {self.backward_error[i]:>8.1e} {self.condition[i]:>8.1e} "
                f"{self.error_bound[i]:>8.1e} {self.multiplicity[i]:>4}  {self.kind[i]:<11}  "
                + ", ".join(f"{name} {p:.0%}" for name, p in dominant[i])
            )
        if len(rows) < k:
            lines.append(f"... {k - len(rows)} more (higher frequencies)")
        lines.append(f"max eta {self.max_backward_error:.2e}; dynamic stiffness simple: {self.is_simple}")
        lines.append(f"stability: {self.stability}")
        for note in self.notes:
            lines.append(f"note: {note}")
        return "\n".join(lines)

    summary = table

    def to_pandas(self):
        """One row per eigenvalue as a pandas DataFrame (:func:`pinlin.spectral.tables.modes_frame`).

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
        >>> frame = pinlin.modal_analysis(sys).to_pandas()
        >>> frame.shape
        (4, 11)
        >>> list(frame.columns[:3])
        ['eigenvalue_re', 'eigenvalue_im', 'natural_frequency']
        """
        return modes_frame(self)

    def energy(self, k: int, scene=None):
        """Mode k's energy per body and element (:func:`pinlin.spectral.energy.mode_energy`).

        Examples
        --------
        >>> robot = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
        >>> scene = pinlin.Scene(robot, [pinlin.JointSpring(j, 10.0) for j in robot.joint_names])
        >>> modes = pinlin.modal_analysis(pinlin.linearize(scene, robot.neutral()))
        >>> energy = modes.energy(0, scene)
        >>> {body: round(share, 6) for body, share in energy.kinetic.items()}
        {'link1': 0.18182, 'link2': 0.81818}
        """
        return mode_energy(self, k, scene)

    def __repr__(self) -> str:
        return (
            f"Modes(n={self.n}, method={self.method.name!r}, stability={self.stability.kind!r}, "
            f"max_eta={self.max_backward_error:.1e}, elapsed={self.elapsed:.3g}s)"
        )
