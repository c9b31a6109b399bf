"""The linearized equations of motion as a frozen value (theory: equations).

.. math::  M \\ddot x + (D + G) \\dot x + (S + N) x = f(t)
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import ParameterError, SingularMassError
from ..numerics.arrays import readonly
from ..numerics.norms import fro
from ..results import Result
from .state_form import first_order_form, null_motion

__all__ = ["LinearizedSystem", "check_system", "MATRIX_NAMES"]

#: The five matrices of the linearized equation, in the paper's order.
MATRIX_NAMES = ("M", "D", "G", "S", "N")

#: Default relative tolerance of the (skew-)symmetry checks of the constructor.
SYMMETRY_TOL = 1e-10


def _frozen(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


@dataclass(frozen=True, repr=False, eq=False)
class LinearizedSystem(Result):
    """``M x'' + (D + G) x' + (S + N) x = f(t)`` around an operating point.

    Build one with :func:`pinlin.linearize` from a scene, or with
    :meth:`from_matrices` from plain matrices.  The arrays are copies and
    read-only; C = D + G and K = S + N are available as attributes, formed on
    first access (and kept).

    Attributes
    ----------
    M : (n, n) ndarray
        Mass matrix, symmetric positive definite [kg, kg m^2].
    D : (n, n) ndarray
        Damping, symmetric.
    G : (n, n) ndarray
        Gyroscopic, skew-symmetric.
    S : (n, n) ndarray
        Stiffness, symmetric.
    N : (n, n) ndarray
        Circulatory, skew-symmetric.
    dof_names : tuple of str
        Name of each coordinate.
    q, v : ndarray or None
        The operating point (full Pinocchio configuration and velocity, prescribed
        joints included) when built from a scene.
    residual : float
        Relative equilibrium residual at q (0 for plain matrices).
    balancing : ndarray or None
        Constant generalized forces held by actuators (``balancing=True``).
    elapsed : float
        Seconds spent building the system.
    method : str
        How it was built: ``"analytic"`` (Pinocchio's analytic derivatives and the
        elements' own, :func:`pinlin.linearize`) or ``"matrices"`` (given).
    error : float
        The headline error figure: the relative equilibrium residual at q (how far
        q is from the operating point the matrices assume; 0 for given matrices).
        The rounding left in the matrices is at the level of ``dropped``.
    calls : tuple of str
        Pinocchio algorithms run to build it, in order.
    dropped : mapping
        Relative size of parts set to exactly zero as rounding noise (for
        example the skew part of a gravity stiffness).
    notes : tuple of str
        Anything the builder wants the user to know.
    basis : (nv, n) ndarray or None
        For a scene with constraints (theory: constraints): the basis B of ker J_c
        with joint velocities = ``basis @ z`` (z the coordinates, ``dof_names``);
        ``expand`` maps mode shapes and responses to all joints.  None without
        constraints (the coordinates are the free joints themselves).
    basis_names : tuple of str
        Names of the rows of ``basis`` (the robot's degrees of freedom); empty
        without constraints.
    basis_condition : float or None
        cond(J_d) of the joints that follow the coordinates (1 for an orthonormal
        basis); it grows without bound near a position where the chosen
        coordinates cannot drive the mechanism.  None without constraints.
    constraint_forces : tuple of ConstraintForce
        The constraint forces at q (world axes, on each constraint's frame), in
        scene order; empty without constraints.

    Raises
    ------
    ParameterError
        Matrices of the wrong shape, non-finite, or violating their symmetry.
    SingularMassError
        M is not positive definite.
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
        mats = {}
        n = None
        for name in MATRIX_NAMES:
            try:
                a = np.array(getattr(self, name), dtype=float)
            except (TypeError, ValueError):
                raise ParameterError(name, "expected a real matrix") from None
            if a.ndim != 2 or a.shape[0] != a.shape[1]:
                raise ParameterError(name, f"expected a square matrix, got shape {a.shape}")
            if n is None:
                n = a.shape[0]
                if n == 0:
                    raise ParameterError(name, "the system has no coordinates (n = 0)")
            elif a.shape != (n, n):
                raise ParameterError(name, f"expected shape {(n, n)} like M, got {a.shape}")
            if not np.all(np.isfinite(a)):
                raise ParameterError(name, "has non-finite entries")
            mats[name] = a
        for name, sign in (("M", 1), ("D", 1), ("S", 1), ("G", -1), ("N", -1)):
            a = mats[name]
            defect = fro(a - sign * a.T)
            if defect > SYMMETRY_TOL * max(fro(a), np.finfo(float).tiny):
                kind = "symmetric" if sign == 1 else "skew-symmetric"
                raise ParameterError(
                    name, f"must be {kind}; relative defect {defect / fro(a):.2e} > {SYMMETRY_TOL:g}"
                )
            mats[name] = (a + sign * a.T) / 2
        names = tuple(str(s) for s in self.dof_names) or tuple(f"x{i + 1}" for i in range(n))
        if len(names) != n:
            raise ParameterError("dof_names", f"expected {n} names, got {len(names)}")
        if len(set(names)) != n:
            raise ParameterError("dof_names", f"names must be unique, got {names}")
        try:
            np.linalg.cholesky(mats["M"])
        except np.linalg.LinAlgError:
            smallest, weak = null_motion(mats["M"], names)
            raise SingularMassError(
                f"the mass matrix is not positive definite (smallest eigenvalue {smallest:.3g}); "
                f"the coordinates {weak} carry no inertia",
                weak,
            ) from None
        for name, a in mats.items():
            object.__setattr__(self, name, readonly(a, float))
        object.__setattr__(self, "dof_names", names)
        object.__setattr__(self, "q", readonly(self.q, float))
        object.__setattr__(self, "v", readonly(self.v, float))
        object.__setattr__(self, "balancing", readonly(self.balancing, float))
        object.__setattr__(self, "dropped", dict(self.dropped))
        object.__setattr__(self, "calls", tuple(self.calls))
        object.__setattr__(self, "notes", tuple(self.notes))
        self._check_basis(n)

    def _check_basis(self, n: int) -> None:
        if self.basis is None:
            return
        try:
            B = np.array(self.basis, dtype=float)
        except (TypeError, ValueError):
            raise ParameterError("basis", "expected a real matrix") from None
        if B.ndim != 2 or B.shape[1] != n or not np.all(np.isfinite(B)):
            raise ParameterError("basis", f"expected a finite (nv x {n}) matrix, got shape {B.shape}")
        if self.basis_names and len(self.basis_names) != B.shape[0]:
            raise ParameterError("basis_names", f"expected {B.shape[0]} names, got {len(self.basis_names)}")
        object.__setattr__(self, "basis", readonly(B, float))
        object.__setattr__(self, "basis_names", tuple(str(x) for x in self.basis_names))
        object.__setattr__(self, "constraint_forces", tuple(self.constraint_forces))

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
    def trusted(
        cls,
        M: np.ndarray,
        D: np.ndarray,
        G: np.ndarray,
        S: np.ndarray,
        N: np.ndarray,
        *,
        dof_names: tuple[str, ...],
        q: np.ndarray | None = None,
        v: np.ndarray | None = None,
        residual: float = 0.0,
        balancing: np.ndarray | None = None,
        elapsed: float = 0.0,
        calls: tuple[str, ...] = (),
        dropped: Mapping[str, float] | None = None,
        notes: tuple[str, ...] = (),
        method: str = "analytic",
        basis: np.ndarray | None = None,
        basis_names: tuple[str, ...] = (),
        basis_condition: float | None = None,
        constraint_forces: tuple = (),
        frozen: bool = False,
    ) -> LinearizedSystem:
        """Wrap matrices that are valid by construction, without re-validating them.

        For builders (such as :func:`pinlin.linearize`) that produce M, D, S
        exactly symmetric and G, N exactly skew, with M already checked positive
        definite and every entry finite, and ``dof_names`` of the right length.
        The arrays are taken over (not copied) and made read-only; ``frozen=True``
        says M, D, G, S, N, q and basis are read-only already (views of read-only
        arrays, as :func:`pinlin.linearize_many` hands over).  Everyone else should
        call the constructor, which validates.
        """
        obj = object.__new__(cls)
        for a in (balancing,) if frozen else (M, D, G, S, N, q, balancing, basis):
            if a is not None:
                a.setflags(False)  # write=False; positional: a third of the keyword call's cost
        if v is not None and v.flags.writeable:  # a scene's v0 is read-only already: no copy, no flag
            v.setflags(False)
        object.__setattr__(obj, "__dict__", {
            "M": M, "D": D, "G": G, "S": S, "N": N, "dof_names": tuple(dof_names), "q": q, "v": v,
            "residual": residual, "balancing": balancing, "elapsed": elapsed, "calls": tuple(calls),
            "dropped": dict(dropped or {}), "notes": tuple(notes), "method": method, "basis": basis,
            "basis_names": tuple(basis_names), "basis_condition": basis_condition,
            "constraint_forces": tuple(constraint_forces),
        })  # fmt: skip
        return obj

    @cached_property
    def C(self) -> np.ndarray:
        """C = D + G (n x n), read-only; formed on first access."""
        return _frozen(self.D + self.G)

    @cached_property
    def K(self) -> np.ndarray:
        """K = S + N (n x n), read-only; formed on first access."""
        return _frozen(self.S + self.N)

    def replace(self, **changes) -> LinearizedSystem:
        """A copy with some fields changed (validated again)."""
        changes.pop("C", None)
        changes.pop("K", None)
        return dataclasses.replace(self, **changes)

    # ------------------------------------------------------------------ structure

    @property
    def error(self) -> float:
        """The relative equilibrium residual at q (0 for given matrices); see the class docstring."""
        return float(self.residual)

    @property
    def n(self) -> int:
        """Number of coordinates."""
        return self.M.shape[0]

    def is_zero(self, name: str) -> bool:
        """True when matrix ``name`` (one of M, D, G, S, N, C, K) is exactly zero."""
        if name not in MATRIX_NAMES + ("C", "K"):
            raise ParameterError("name", f"expected one of {MATRIX_NAMES + ('C', 'K')}, got {name!r}")
        return not np.any(getattr(self, name))

    @property
    def nonzero(self) -> tuple[str, ...]:
        """Names of the matrices among M, D, G, S, N that are not exactly zero."""
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
        """L(lam) = lam^2 M + lam C + K: (n, n) for a scalar, (len(lam), n, n) for an array."""
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


#: ``to_dict`` dumps the declared fields, then C and K (formed on access), as before they became lazy.
LinearizedSystem._dict_fields = tuple(f.name for f in dataclasses.fields(LinearizedSystem)) + ("C", "K")

def check_system(sys) -> LinearizedSystem:
    """``sys`` itself if it is a :class:`~pinlin.LinearizedSystem`.

    Raises
    ------
    ParameterError
        ``sys`` is anything else.
    """
    if not isinstance(sys, LinearizedSystem):
        raise ParameterError(
            "sys",
            f"expected a pinlin.LinearizedSystem (from linearize or LinearizedSystem.from_matrices), "
            f"got {type(sys).__name__}",
        )
    return sys
