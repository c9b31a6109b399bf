"""The checks every :class:`~pinlin.LinearizedSystem`'s five matrices pass, on stacks of systems.

Shapes, finite entries, symmetry of M, D, S and skewness of G, N (within
:data:`SYMMETRY_TOL`, then made exact), and a positive definite M.  One system is
a stack of one; :func:`pinlin.linearize_many` checks all its points' matrices in
one pass, which is why the checks are written on stacks.
"""

from __future__ import annotations

import functools

import numpy as np
import scipy.linalg.lapack as lapack

from ..errors import ParameterError, SingularMassError
from .state_form import null_motion

__all__ = [
    "MATRIX_NAMES", "SYMMETRY_TOL", "PIVOT_MARGIN", "checked_matrices", "checked_basis", "square_matrix", "copied", "taken",
]

#: The five matrices of the linearized equation, in the paper's order.
MATRIX_NAMES = ("M", "D", "G", "S", "N")

#: Relative tolerance of the (skew-)symmetry checks of the constructor.
SYMMETRY_TOL = 1e-10

#: A mass matrix of a stack passes the stacked Cholesky check outright when every pivot satisfies
#: L_jj^2 >= PIVOT_MARGIN M_jj; a Cholesky factorization's pivots are off by about n eps M_jj, so
#: any LAPACK's (one matrix's is scipy's, the stack's numpy's) succeeds on it too.  Closer ones are
#: decided by the one matrix's factorization.
PIVOT_MARGIN = 1e-8

#: The symmetry each matrix has: +1 symmetric, -1 skew-symmetric.
_SIGNS = {"M": 1, "D": 1, "G": -1, "S": 1, "N": -1}


def _as_stack(name: str, value, count: int | None) -> np.ndarray:
    """``value`` as a float array (P, n, n) or one shared (n, n) matrix; a sequence of matrices is stacked."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, "expected a real matrix") from None
    if a.ndim not in (2, 3) or a.shape[-1] != a.shape[-2] or (a.ndim == 3 and count is not None and len(a) != count):
        raise ParameterError(name, f"expected a square matrix (or one per point), got shape {a.shape}")
    return a


def checked_matrices(matrices: dict, dof_names: tuple[str, ...]) -> dict[str, np.ndarray]:
    """The five matrices checked and made exactly (skew-)symmetric, read-only: name -> (P, n, n) or (n, n).

    ``matrices`` maps each of M, D, G, S, N to a (P, n, n) stack, a sequence of P
    matrices, or one (n, n) matrix shared by the P systems.  Matrices that are
    exactly (skew-)symmetric already are taken over as they are and made read-only
    (callers hand over arrays nobody else writes to).

    Raises
    ------
    ParameterError
        Not square, shapes that differ, no coordinates, non-finite entries, or a
        symmetry defect above :data:`SYMMETRY_TOL` (relative, Frobenius norm).
    SingularMassError
        An M that is not positive definite; the message names the coordinates
        that carry no inertia.
    """
    stacks = {}
    n = count = None
    for name in MATRIX_NAMES:
        a = _as_stack(name, matrices[name], count)
        if n is None:
            n = a.shape[-1]
            if n == 0:
                raise ParameterError(name, "the system has no coordinates (n = 0)")
        elif a.shape[-1] != n:
            raise ParameterError(name, f"expected shape {(n, n)} like M, got {a.shape}")
        if a.ndim == 3:
            count = len(a)
        stacks[name] = a
    # exactly (skew-)symmetric and finite is the usual case: one test for the shared matrices, one per stack
    shared = tuple(name for name, a in stacks.items() if a.ndim == 2)
    out = {}
    for names in [shared] * bool(shared) + [(name,) for name, a in stacks.items() if a.ndim == 3]:
        exact = _exact(names, stacks)
        for name in names:
            out[name] = stacks[name] if exact else _symmetric(name, stacks[name])
            out[name].flags.writeable = False  # taken over
    if len(dof_names) != n:
        raise ParameterError("dof_names", f"expected {n} names, got {len(dof_names)}")
    if len(set(dof_names)) != n:
        raise ParameterError("dof_names", f"names must be unique, got {dof_names}")
    _check_mass(out["M"], dof_names)
    return {name: out[name] for name in MATRIX_NAMES}


def _exact(names: tuple[str, ...], stacks: dict[str, np.ndarray]) -> bool:
    """The matrices ``names`` are finite and exactly (skew-)symmetric: X - sign X^T is zero only there.

    (inf - inf and NaN are NaN.)  Shared (n, n) matrices are stacked and tested at once;
    a per-point stack (P, n, n) alone, with no sign factor (one temporary of its size).
    """
    if len(names) > 1:
        X = np.array([stacks[name] for name in names])
        return not (X - _signs(names) * X.swapaxes(-1, -2)).any()
    a = stacks[names[0]]
    return not (a - a.swapaxes(-1, -2) if _SIGNS[names[0]] > 0 else a + a.swapaxes(-1, -2)).any()


@functools.cache
def _signs(names: tuple[str, ...]) -> np.ndarray:
    """The symmetry signs of the matrices ``names``, shaped (k, 1, 1) to scale a stack of them."""
    signs = np.array([_SIGNS[name] for name in names], dtype=float)[:, None, None]
    signs.flags.writeable = False  # shared by every call
    return signs


def _symmetric(name: str, a: np.ndarray) -> np.ndarray:
    """``a`` made exactly (skew-)symmetric, after the checks of its entries and of its symmetry defect."""
    if not np.isfinite(a).all():
        raise ParameterError(name, "has non-finite entries")
    mirrored = _SIGNS[name] * a.swapaxes(-1, -2)
    big = np.abs(a).max(axis=(-2, -1), keepdims=True)
    scaled = a / np.where(big > 0, big, 1.0)  # the norms of entries near 1e300 do not overflow
    defect = np.linalg.norm(scaled - _SIGNS[name] * scaled.swapaxes(-1, -2), axis=(-2, -1))
    size = np.linalg.norm(scaled, axis=(-2, -1))
    bad = defect > SYMMETRY_TOL * np.maximum(size, np.finfo(float).tiny)
    if bad.any():
        worst = float(np.max(np.where(bad, defect / np.where(size > 0, size, 1.0), 0.0)))
        kind = "symmetric" if _SIGNS[name] == 1 else "skew-symmetric"
        raise ParameterError(name, f"must be {kind}; relative defect {worst:.2e} > {SYMMETRY_TOL:g}")
    return (a + mirrored) / 2


def _check_mass(M: np.ndarray, dof_names: tuple[str, ...]) -> None:
    """SingularMassError at the first M of the stack (or the one M) that is not positive definite.

    One M is decided by its own Cholesky factorization (:func:`_positive_definite`); a stack
    by one factorization of all its matrices, the points whose pivots come within
    :data:`PIVOT_MARGIN` of failing (or all, when it fails) decided again one by one, so
    that every point is decided as it would be alone.
    """
    stack = M.reshape(-1, *M.shape[-2:])
    undecided = range(len(stack))
    if M.ndim == 3:
        try:
            L = np.linalg.cholesky(stack)
            pivots = np.diagonal(L, axis1=1, axis2=2)
            close = pivots * pivots < PIVOT_MARGIN * np.diagonal(stack, axis1=1, axis2=2)
            undecided = np.flatnonzero(close.any(axis=1))
        except np.linalg.LinAlgError:
            pass
    for i in undecided:
        if not _positive_definite(stack[i]):
            smallest, weak = null_motion(stack[i], dof_names)
            raise SingularMassError(
                f"the mass matrix is not positive definite (smallest eigenvalue {smallest:.3g}); "
                f"the coordinates {weak} carry no inertia",
                weak,
            )


def _positive_definite(M: np.ndarray) -> bool:
    """One Cholesky factorization of M (n, n) succeeds."""
    return lapack.dpotrf(M, lower=True, clean=False)[1] == 0


def square_matrix(name: str, value) -> np.ndarray:
    """A float copy of a square matrix given to the constructor."""
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, "expected a real matrix") from None
    if a.ndim != 2 or a.shape[0] != a.shape[1]:
        raise ParameterError(name, f"expected a square matrix, got shape {a.shape}")
    return a


def copied(a) -> np.ndarray | None:
    """A float copy (None stays None)."""
    return None if a is None else np.array(a, dtype=float)


def taken(a) -> np.ndarray | None:
    """``a`` itself made read-only (None stays None): builders hand over arrays nobody else writes to."""
    if a is not None and a.flags.writeable:
        a.flags.writeable = False
    return a


def checked_basis(basis, basis_names, n: int) -> np.ndarray | None:
    """The basis of ker J_c (nv, n), checked and read-only, or None."""
    if basis is None:
        return None
    try:
        B = np.asarray(basis, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("basis", "expected a real matrix") from None
    if B.ndim != 2 or B.shape[1] != n or not np.all(np.isfinite(B)):
        raise ParameterError("basis", f"expected a finite (nv x {n}) matrix, got shape {B.shape}")
    if basis_names and len(basis_names) != B.shape[0]:
        raise ParameterError("basis_names", f"expected {B.shape[0]} names, got {len(basis_names)}")
    return taken(B)
