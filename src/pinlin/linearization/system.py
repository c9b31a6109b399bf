"""The linearized equations of motion as a frozen value (theory: equations).

.. math::  M \\ddot x + (D + G) \\dot x + (S + N) x = f(t)
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from itertools import repeat

import numpy as np

from ..errors import ParameterError
from ..results import Result
from .matrices import MATRIX_NAMES, SYMMETRY_TOL, checked_basis, checked_matrices, copied, square_matrix, taken
from .state_form import first_order_form

__all__ = ["LinearizedSystem", "check_system", "MATRIX_NAMES", "SYMMETRY_TOL"]


@dataclass(frozen=True, repr=False, eq=False)
class LinearizedSystem(Result):
    """``M x'' + (D + G) x' + (S + N) x = f(t)`` around an operating point.

    Build one with :func:`pinlin.linearize` from a scene, or with
    :meth:`from_matrices` from plain matrices.  The arrays are copies and
    read-only; C = D + G and K = S + N are available as attributes, formed on
    first access (and kept).

    Attributes
    ----------
    M, D, S : (n, n) ndarray
        Mass (symmetric positive definite [kg, kg m^2]), damping and stiffness (symmetric).
    G, N : (n, n) ndarray
        Gyroscopic and circulatory, skew-symmetric.
    dof_names : tuple of str
        Name of each coordinate.
    q, v : ndarray or None
        The operating point (full configuration and velocity) when built from a scene.
    residual : float
        Relative equilibrium residual at q (0 for plain matrices).
    balancing : ndarray or None
        Constant generalized forces held by actuators (``balancing=True``).
    elapsed : float
        Seconds spent building the system.
    method : str
        ``"analytic"`` (Pinocchio's and the elements' derivatives, :func:`pinlin.linearize`) or ``"matrices"``.
    error : float
        The headline error figure: ``residual`` (the rounding left in the matrices is at the level of ``dropped``).
    calls : tuple of str
        Pinocchio algorithms run to build it, in order.
    dropped : mapping
        Relative size of parts set to exactly zero as rounding noise (for
        example the skew part of a gravity stiffness).
    notes : tuple of str
        Anything the builder wants the user to know.
    basis : (nv, n) ndarray or None
        With constraints (theory: constraints): the basis B of ker J_c, joint
        velocities = ``basis @ z`` (``expand``); None without constraints.
    basis_names : tuple of str
        Names of the rows of ``basis`` (the robot's degrees of freedom), or empty.
    basis_condition : float or None
        cond(J_d) of the joints that follow the coordinates (1 for an orthonormal
        basis; unbounded where they cannot drive the mechanism), or None.
    constraint_forces : tuple of ConstraintForce
        The constraint forces at q (world axes, on each constraint's frame), or empty.

    Raises
    ------
    ParameterError
        Matrices of the wrong shape, non-finite, or violating their symmetry.
    SingularMassError
        M is not positive definite.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, 1.0], [0.0, 3.0]])
    >>> sys
    LinearizedSystem(n=2, dofs=('x1', 'x2'), nonzero=M+D+S+N, method='matrices', error=0.0e+00)
    >>> sys.N
    array([[ 0. ,  0.5],
           [-0.5,  0. ]])
    """

    M: np.ndarray
    D: np.ndarray
    G: np.ndarray
    S: np.ndarray
    N: np.ndarray
    dof_names: tuple[str, ...] = ()
    q: np.ndarray | None = None
    v: np.ndarray | None = None
    residual: float = 0.0
    balancing: np.ndarray | None = None
    elapsed: float = 0.0
    calls: tuple[str, ...] = ()
    dropped: Mapping[str, float] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    method: str = "matrices"
    basis: np.ndarray | None = None
    basis_names: tuple[str, ...] = ()
    basis_condition: float | None = None
    constraint_forces: tuple = ()

    def __post_init__(self):
        matrices = {name: square_matrix(name, getattr(self, name)) for name in MATRIX_NAMES}
        n = matrices["M"].shape[0]
        names = tuple(str(s) for s in self.dof_names) or tuple(f"x{i + 1}" for i in range(n))
        (system,) = type(self).stack(
            **matrices, dof_names=names, q=None if self.q is None else copied(self.q)[None], v=copied(self.v),
            residual=[self.residual], balancing=None if self.balancing is None else copied(self.balancing)[None],
            elapsed=self.elapsed, calls=self.calls, dropped=[dict(self.dropped)], notes=[tuple(self.notes)],
            method=self.method, basis=copied(self.basis), basis_names=tuple(str(x) for x in self.basis_names),
            basis_condition=self.basis_condition, constraint_forces=self.constraint_forces,
        )  # fmt: skip
        self.__dict__.update(vars(system))

    # ------------------------------------------------------------------ construction

    @classmethod
    def from_matrices(
        cls,
        M,
        C=None,
        K=None,
        *,
        dof_names: Sequence[str] = (),
    ) -> LinearizedSystem:
        """Build a system from M, C = D + G and K = S + N.

        C and K are split exactly into their symmetric and skew parts; omitted
        ones are zero.  M must be symmetric positive definite.

        Raises
        ------
        ParameterError
            Not real square matrices of one shape, non-finite entries, bad ``dof_names``.
        SingularMassError
            M is not positive definite.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.diag([1.0, 4.0]), dof_names=("a", "b"))
        >>> sys.dof_names, sys.nonzero
        (('a', 'b'), ('M', 'S'))
        """
        for name, a in (("M", M), ("C", C), ("K", K)):  # numpy would drop the imaginary part with a warning
            try:
                complex_entries = a is not None and np.iscomplexobj(a)
            except (TypeError, ValueError):  # a ragged nested list
                raise ParameterError(name, "expected a real matrix of numbers (rectangular)") from None
            if complex_entries:
                raise ParameterError(name, "expected a real matrix, got complex entries")
        try:
            M = np.array(M, dtype=float)
        except (TypeError, ValueError):
            raise ParameterError("M", "expected a real matrix") from None
        if M.ndim != 2 or M.shape[0] != M.shape[1]:
            raise ParameterError("M", f"expected a square matrix, got shape {M.shape}")
        parts = {}
        for name, a in (("C", C), ("K", K)):
            if a is None:
                a = np.zeros_like(M)
            try:
                a = np.array(a, dtype=float)
            except (TypeError, ValueError):
                raise ParameterError(name, "expected a real matrix") from None
            if a.shape != M.shape:
                raise ParameterError(name, f"expected shape {M.shape} like M, got {a.shape}")
            parts[name] = ((a + a.T) / 2, (a - a.T) / 2)
        (D, G), (S, N) = parts["C"], parts["K"]
        return cls(M, D, G, S, N, dof_names=tuple(dof_names))

    @classmethod
    def stack(
        cls,
        *,
        M,
        D,
        G,
        S,
        N,
        dof_names: Sequence[str],
        residual: Sequence[float],
        dropped: Sequence[Mapping[str, float]],
        notes: Sequence[Sequence[str]],
        q=None,
        v: np.ndarray | None = None,
        balancing=None,
        elapsed: float = 0.0,
        calls: Sequence[str] = (),
        method: str = "analytic",
        basis: np.ndarray | None = None,
        basis_names: Sequence[str] = (),
        basis_condition: float | None = None,
        constraint_forces: Sequence = (),
    ) -> tuple[LinearizedSystem, ...]:
        """The systems of P operating points of one model, their matrices checked in one pass.

        For builders (:func:`pinlin.linearize` with P = 1, :func:`pinlin.linearize_many`);
        the constructor is this with P = 1 and copies of its arguments.  Each of M, D, G, S,
        N is a (P, n, n) stack, a sequence of P matrices, or one (n, n) matrix the systems
        share; ``q`` (P, nq) or None, ``balancing`` (P, n) or None, and ``residual``,
        ``dropped`` (dictionaries), ``notes`` (tuples), one entry per point, vary with the
        point, the rest is shared.  The arrays and dictionaries are taken over (not copied),
        the arrays made read-only.

        Raises
        ------
        ParameterError, SingularMassError
            As the constructor (:func:`~pinlin.linearization.matrices.checked_matrices`).

        Examples
        --------
        >>> M = np.stack([np.eye(2), 2.0 * np.eye(2)])
        >>> systems = pinlin.LinearizedSystem.stack(
        ...     M=M, D=np.zeros((2, 2)), G=np.zeros((2, 2)), S=np.eye(2), N=np.zeros((2, 2)),
        ...     dof_names=("a", "b"), residual=[0.0, 0.0], dropped=[{}, {}], notes=[(), ()])
        >>> [float(s.M[0, 0]) for s in systems]
        [1.0, 2.0]
        """
        names = tuple(dof_names)
        matrices = checked_matrices({"M": M, "D": D, "G": G, "S": S, "N": N}, names)
        n = matrices["M"].shape[-1]
        template = dict.fromkeys(_FIELDS)  # the attributes in field order: shared ones now, the others per point
        template.update(
            dof_names=names, v=taken(v), elapsed=elapsed, calls=tuple(calls), method=method,
            basis=checked_basis(basis, basis_names, n), basis_names=tuple(basis_names),
            basis_condition=basis_condition, constraint_forces=tuple(constraint_forces),
        )  # fmt: skip
        per_point = [repeat(a) if a.ndim == 2 else a for a in map(matrices.get, MATRIX_NAMES)]
        per_point += [repeat(None) if a is None else taken(a) for a in (q, balancing)]
        out = []
        for M_p, D_p, G_p, S_p, N_p, q_p, b_p, r_p, d_p, n_p in zip(*per_point, residual, dropped, notes):
            attributes = template.copy()
            attributes["M"], attributes["D"], attributes["G"], attributes["S"], attributes["N"] = M_p, D_p, G_p, S_p, N_p
            attributes["q"], attributes["balancing"], attributes["residual"] = q_p, b_p, r_p
            attributes["dropped"], attributes["notes"] = d_p, n_p
            system = object.__new__(cls)
            object.__setattr__(system, "__dict__", attributes)
            out.append(system)
        return tuple(out)

    @cached_property
    def C(self) -> np.ndarray:
        """C = D + G (n x n), read-only; formed on first access.
        """
        return taken(self.D + self.G)

    @cached_property
    def K(self) -> np.ndarray:
        """K = S + N (n x n), read-only; formed on first access.
        """
        return taken(self.S + self.N)

    def replace(self, **changes) -> LinearizedSystem:
        """A copy with some fields changed (validated again).

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
        >>> sys.replace(dof_names=("a", "b")).dof_names
        ('a', 'b')
        """
        changes.pop("C", None)
        changes.pop("K", None)
        return dataclasses.replace(self, **changes)

    # ------------------------------------------------------------------ structure

    @property
    def error(self) -> float:
        """The relative equilibrium residual at q (0 for given matrices); see the class docstring.
        """
        return float(self.residual)

    @property
    def n(self) -> int:
        """Number of coordinates.
        """
        return self.M.shape[0]

    def is_zero(self, name: str) -> bool:
        """True when matrix ``name`` (one of M, D, G, S, N, C, K) is exactly zero.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
        >>> sys.is_zero("G"), sys.is_zero("K")
        (True, False)
        """
        if name not in MATRIX_NAMES + ("C", "K"):
            raise ParameterError("name", f"expected one of {MATRIX_NAMES + ('C', 'K')}, got {name!r}")
        return not np.any(getattr(self, name))

    @property
    def nonzero(self) -> tuple[str, ...]:
        """Names of the matrices among M, D, G, S, N that are not exactly zero.

        Examples
        --------
        >>> pinlin.LinearizedSystem.from_matrices(np.eye(2), [[0.0, 1.0], [-1.0, 0.0]]).nonzero
        ('M', 'G')
        """
        return tuple(name for name in MATRIX_NAMES if not self.is_zero(name))

    def expand(self, x) -> np.ndarray:
        """Coordinates z to joint velocities (or displacements): ``basis @ x``.

        ``x`` is any array whose first axis has length n: a vector (n,), mode
        shapes in columns (n, k), ...; the first axis becomes the robot's nv
        degrees of freedom (``basis_names``).  Without constraints x is returned
        unchanged (a copy).

        .. math::  \\dot q = B z  \\quad \\text{(theory: constraints)}

        Raises
        ------
        ParameterError
            The first axis of x is not of length n.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2))
        >>> sys.expand(np.array([1.0, 2.0]))  # no constraints: x itself (a copy)
        array([1., 2.])
        """
        x = np.asarray(x)
        if x.ndim == 0 or x.shape[0] != self.n:
            raise ParameterError("x", f"expected an array whose first axis has length n = {self.n}, got shape {x.shape}")
        if self.basis is None:
            return x.copy()
        return np.tensordot(self.basis, x, axes=(1, 0))

    def first_order(self, F=None) -> tuple[np.ndarray, np.ndarray, float]:
        """(A, B, residual) of z' = A z + B u, z = (x, x'), f = F u (F n x m, default I): first_order_form.

        Examples
        --------
        >>> print(pinlin.LinearizedSystem.from_matrices([[2.0]], [[0.4]], [[8.0]]).first_order()[0].tolist())
        [[0.0, 1.0], [-4.0, -0.2]]
        """
        return first_order_form(self.M, self.C, self.K, np.eye(self.n) if F is None else F)

    # ------------------------------------------------------------------ dynamic stiffness

    def dynamic_stiffness(self, lam) -> np.ndarray:
        """L(lam) = lam^2 M + lam C + K: (n, n) for a scalar, (len(lam), n, n) for an array.

        Examples
        --------
        >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(1), [[0.5]], [[4.0]])
        >>> sys.dynamic_stiffness(2.0), sys.dynamic_stiffness([1.0, 2.0]).shape
        (array([[9.]]), (2, 1, 1))
        """
        lam = np.asarray(lam)
        if lam.ndim == 0:
            return lam * lam * self.M + lam * self.C + self.K
        lam = lam.reshape(-1, 1, 1)
        return lam * lam * self.M + lam * self.C + self.K

    def __repr__(self) -> str:
        names = self.dof_names if self.n <= 6 else self.dof_names[:3] + ("...",) + self.dof_names[-2:]
        basis = "" if self.basis is None else f", basis={self.basis.shape[0]}x{self.n}"
        return (
            f"LinearizedSystem(n={self.n}, dofs={names}, nonzero={'+'.join(self.nonzero)}{basis}, "
            f"method={self.method!r}, error={self.error:.1e})"
        )


#: The declared fields, in order: the attributes of every system.
_FIELDS = tuple(f.name for f in dataclasses.fields(LinearizedSystem))
#: ``to_dict`` dumps the declared fields, then C and K (formed on access), as before they became lazy.
LinearizedSystem._dict_fields = _FIELDS + ("C", "K")


def check_system(sys) -> LinearizedSystem:
    """``sys`` itself if it is a :class:`~pinlin.LinearizedSystem`.

    Raises
    ------
    ParameterError
        ``sys`` is anything else.

    Examples
    --------
    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(1))
    >>> check_system(sys) is sys
    True
    """
    if not isinstance(sys, LinearizedSystem):
        raise ParameterError(
            "sys",
            f"expected a pinlin.LinearizedSystem (from linearize or LinearizedSystem.from_matrices), "
            f"got {type(sys).__name__}",
        )
    return sys
