"""Independent coordinates of a constrained system: a basis B of ker J_c (theory: constraints).

The admissible motions at q are x = B z (joint velocities, nv) with B an
(nv x n) basis of ker J_c, n = nv - rank J_c.  Three choices, all giving the
same eigenvalues (the projected matrices are congruent):

- ``None`` (default): joints picked by a column-pivoted QR of J_c.  The pivot
  columns are the *dependent* joints (the best-conditioned set the greedy
  pivoting finds); the others are the coordinates z, so modes read in joint
  names.  With J_c P = Q [R11 R12; 0 0]:  B = P [-R11^{-1} R12; I];
- a list of joint (or degree-of-freedom) names: those are the coordinates;
  the remaining joints must be able to follow them (J_d of full rank);
- ``"orthonormal"``: the right singular vectors of J_c's null space, the
  best-conditioned basis (names ``z1``, ``z2``, ...).

The condition number of J_d (the dependent joints' columns) is reported: it
grows without bound as the chosen coordinates approach a position where they
cannot drive the mechanism (a four-bar's crank at a toggle position).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg.lapack as lapack

from ..errors import JointNotFoundError, ParameterError
from .constraint_set import ConstraintState

__all__ = ["CoordinateBasis", "coordinate_basis", "pivoted_basis", "pivoted_coordinates", "PIVOTED_METHOD"]


@dataclass(frozen=True)
class CoordinateBasis:
    """B (nv x n), the names of z, and how they were chosen.

    Attributes
    ----------
    B : (nv, n) ndarray
        Joint velocities = B @ z.
    dof_names : tuple of str
        Names of the coordinates z.
    condition : float
        The condition number of J_d, the dependent joints' columns of J_c, in the
        1-norm (LAPACK's dtrcon estimate on its triangular factor; 1 for the
        orthonormal basis).
    method : str
        ``"joints (column-pivoted QR)"``, ``"joints (given)"`` or ``"orthonormal"``.
    dependent : tuple of str
        The dependent degrees of freedom (empty for the orthonormal basis).
    """

    B: np.ndarray
    dof_names: tuple[str, ...]
    condition: float
    method: str
    dependent: tuple[str, ...]


def _named_indices(names: Sequence[str], dof_names: tuple[str, ...], robot) -> list[int]:
    """Velocity indices of the coordinates a user names (joint names expand to all their dofs)."""
    index = {name: i for i, name in enumerate(dof_names)}
    out: list[int] = []
    for name in names:
        if name in index:
            out.append(index[name])
        elif isinstance(name, str) and name in robot.joint_names:
            j = robot.joint(name)
            out.extend(range(j.idx_v, j.idx_v + j.nv))
        else:
            # a 1-DOF joint's coordinate has the joint's name: list each name once
            valid = tuple(dict.fromkeys(tuple(robot.joint_names) + dof_names))
            raise JointNotFoundError(str(name), valid, context="coordinates")
    if len(set(out)) != len(out):
        raise ParameterError("coordinates", f"names a degree of freedom twice: {list(names)}")
    return sorted(out)


def _joint_basis(J: np.ndarray, independent, dependent, X: np.ndarray) -> np.ndarray:
    """B with the identity on the independent rows and -X on the dependent ones."""
    n = len(independent)
    B = np.zeros((J.shape[1], n))
    B[independent, np.arange(n)] = 1.0
    B[dependent] = -X
    return B


def _condition(R: np.ndarray) -> float:
    """1-norm condition number of an upper-triangular R (LAPACK's dtrcon estimate)."""
    rcond = lapack.dtrcon(R, norm="1")[0]
    return float(1.0 / rcond) if rcond > 0 else float("inf")


def _follow(state, J, dependent, independent, names, dof_names) -> tuple[np.ndarray, float]:
    """X with J_d X = J_i (the dependent joints following the given ones) and cond(J_d).

    J_d (m x r) must have rank r: its column-pivoted QR's pivots are checked against
    ``rank_tol`` times J_c's largest pivot, as J_c's rank is.
    """
    r = len(dependent)
    if not r:
        return np.zeros((0, len(independent))), 1.0
    J_d = J[:, dependent]
    R, perm, tau = lapack.dgeqp3(J_d)[:3]
    d = np.abs(np.diagonal(R))
    if d[-1] <= state.rank_tol * abs(state.qr[0][0, 0]):  # relative to J_c's largest pivot, as its rank
        raise ParameterError(
            "coordinates",
            f"{names} cannot serve as coordinates here: the other joints {[dof_names[i] for i in dependent]} "
            f"cannot follow them (their constraint Jacobian J_d has rank < {r}); choose other joints or "
            f"coordinates=None",
        )
    c = lapack.dormqr("L", "T", R, tau, J[:, independent], max(1, J.shape[0] * len(independent)))[0]
    Y = lapack.dtrtrs(R[:r, :r], c[:r])[0]
    X = np.empty_like(Y)
    X[perm - 1] = Y
    return X, _condition(R[:r, :r])


def coordinate_basis(
    state: ConstraintState,
    dof_names: tuple[str, ...],
    coordinates: str | Sequence[str] | None = None,
) -> CoordinateBasis:
    """A basis of ker J_c for the chosen coordinates (see the module docstring).

    Parameters
    ----------
    state : ConstraintState
        The constraints at the operating point.
    dof_names : tuple of str
        Names of the velocity coordinates (``scene.dof_names``).
    coordinates : None, "orthonormal" or sequence of str
        The choice of z.

    Raises
    ------
    JointNotFoundError
        A named coordinate is neither a joint nor a degree of freedom.
    ParameterError
        Not nv - rank J_c coordinates, a name twice, a string other than
        ``"orthonormal"``, or coordinates the other joints cannot follow.
    """
    J, r = state.J, state.rank
    nv = J.shape[1]
    n = nv - r
    if isinstance(coordinates, str) and coordinates != "orthonormal":
        raise ParameterError(
            "coordinates", f"expected None, 'orthonormal' or a list of joint names, got {coordinates!r}"
        )
    if isinstance(coordinates, str):  # "orthonormal"
        B = state.kernel()
        return CoordinateBasis(B, tuple(f"z{i + 1}" for i in range(n)), 1.0, "orthonormal", ())
    if coordinates is None:
        return pivoted_coordinates(state, dof_names)
    independent = np.array(_named_indices(list(coordinates), dof_names, state.scene.robot), dtype=int)
    if len(independent) != n:
        raise ParameterError(
            "coordinates",
            f"{list(coordinates)} give {len(independent)} degree(s) of freedom; the constraints leave "
            f"n = nv - rank J_c = {nv} - {r} = {n}",
        )
    dependent = np.setdiff1d(np.arange(nv), independent)
    X, condition = _follow(state, J, dependent, independent, list(coordinates), dof_names)
    B = _joint_basis(J, independent, dependent, X)
    return CoordinateBasis(
        B,
        tuple(map(dof_names.__getitem__, np.asarray(independent).tolist())),
        condition,
        "joints (given)",
        tuple(map(dof_names.__getitem__, np.sort(dependent).tolist())),
    )


#: ``CoordinateBasis.method`` of the default coordinates.
PIVOTED_METHOD = "joints (column-pivoted QR)"


def pivoted_basis(state: ConstraintState, dof_names: tuple[str, ...]) -> tuple[np.ndarray, tuple[str, ...], float]:
    """(B, names of z, cond(J_d)) for the joints the column-pivoted QR of J_c leaves independent.

    ``CoordinateBasis(B, names, condition, PIVOTED_METHOD, dependent)`` is what
    :func:`coordinate_basis` returns for them (:func:`pivoted_coordinates`); the
    linearization reads the first three only, without building the dataclass.

    The condition number is LAPACK's ``dtrcon`` 1-norm estimate on R11 (1 when
    nothing depends, rank J_c = 0), as :func:`coordinate_basis` reports it.
    """
    R, perm = state.qr[:2]
    r = state.rank
    nv = R.shape[1]
    n = nv - r
    dependent, rest = perm[:r], perm[r:]
    order = rest.argsort()  # coordinates in joint order
    independent = rest[order]
    B = np.zeros((nv, n))
    B[independent, np.arange(n)] = 1.0
    condition = 1.0
    if r:
        R11 = R[:r, :r]
        B[dependent] = -lapack.dtrtrs(R11, R[:r, r:])[0][:, order]  # upper triangle only
        rcond = lapack.dtrcon(R11, norm="1")[0]
        condition = float(1.0 / rcond) if rcond > 0 else float("inf")
    return B, tuple([dof_names[i] for i in independent.tolist()]), condition


def pivoted_coordinates(state: ConstraintState, dof_names: tuple[str, ...]) -> CoordinateBasis:
    """:func:`pivoted_basis` as the :class:`~.coordinates.CoordinateBasis` it stands for (dependent joints named)."""
    B, names, condition = pivoted_basis(state, dof_names)
    dependent = state.qr[1][: state.rank].tolist()
    dependent.sort()
    return CoordinateBasis(B, names, condition, PIVOTED_METHOD, tuple([dof_names[i] for i in dependent]))
