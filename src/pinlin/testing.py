"""High-precision references and test problems for checking pinlin's results (SPEC section 8).

Errors in pinlin's tests and benchmarks are measured against references that
do not share the method; these are the multiprecision ones, computed with
mpmath (``pip install 'pinlin[test]'`` or ``'pinlin[bench]'``): the eigenvalues
of the first-order companion matrix and the characteristic polynomial's
coefficients, both formed and solved at ``dps`` decimal digits from the
(exactly representable) double-precision matrices.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment

from .errors import MissingDependencyError, ParameterError

__all__ = ["mp_eigenvalues", "mp_characteristic_coefficients", "paired", "cantilever_beam"]


def _mpmath():
    try:
        import mpmath
    except ImportError as exc:  # pragma: no cover - exercised only without the extra
        raise MissingDependencyError("pinlin.testing needs mpmath: pip install 'pinlin[test]'") from exc
    return mpmath


def _matrices(system) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    if isinstance(system, Sequence) and len(system) == 3:
        M, C, K = (np.asarray(a, dtype=float) for a in system)
    else:
        M, C, K = system.M, system.C, system.K
    if M.ndim != 2 or M.shape[0] != M.shape[1] or C.shape != M.shape or K.shape != M.shape:
        raise ParameterError("system", f"expected three square matrices of one size, got {M.shape}, {C.shape}, {K.shape}")
    return M, C, K


def _companion_eigenvalues(mp, M, C, K) -> list:
    """Eigenvalues of [[0, I], [-M^-1 K, -M^-1 C]] in the current mpmath precision."""
    n = M.shape[0]
    Mi = mp.inverse(mp.matrix(M.tolist()))
    B0 = -Mi * mp.matrix(K.tolist())
    B1 = -Mi * mp.matrix(C.tolist())
    A = mp.zeros(2 * n, 2 * n)
    for i in range(n):
        A[i, n + i] = 1
        for j in range(n):
            A[n + i, j] = B0[i, j]
            A[n + i, n + j] = B1[i, j]
    return list(mp.eig(A, left=False, right=False))


def mp_eigenvalues(system, *, dps: int = 50) -> np.ndarray:
    """The 2n eigenvalues of L(lam) = lam^2 M + lam C + K at ``dps`` digits, rounded to complex.

    Parameters
    ----------
    system : LinearizedSystem or (M, C, K)
        M must be nonsingular.
    dps : int
        Working precision in decimal digits.
    """
    mp = _mpmath()
    M, C, K = _matrices(system)
    with mp.workdps(dps):
        return np.array([complex(x) for x in _companion_eigenvalues(mp, M, C, K)])


def mp_characteristic_coefficients(system, *, dps: int = 50) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients of p(lam) = det L(lam) = det M prod_k (lam - lam_k), ascending powers, and the lam_k.

    Returns
    -------
    coefficients : (2n + 1,) ndarray
        Real parts of the 2n + 1 coefficients (p has real coefficients).
    eigenvalues : (2n,) complex ndarray
    """
    mp = _mpmath()
    M, C, K = _matrices(system)
    with mp.workdps(dps):
        ev = _companion_eigenvalues(mp, M, C, K)
        c = [mp.mpc(1)]
        for lam in ev:  # multiply by (x - lam); c holds ascending powers
            c = [(c[k - 1] if k > 0 else 0) - lam * (c[k] if k < len(c) else 0) for k in range(len(c) + 1)]
        det_m = mp.det(mp.matrix(M.tolist()))
        return np.array([float(mp.re(det_m * x)) for x in c]), np.array([complex(x) for x in ev])


def paired(computed, reference) -> np.ndarray:
    """``reference`` reordered to match ``computed`` one to one (optimal assignment on distance)."""
    computed = np.asarray(computed)
    reference = np.asarray(reference)
    if computed.shape != reference.shape or computed.ndim != 1:
        raise ParameterError("reference", f"expected shape {computed.shape} like computed, got {reference.shape}")
    i, j = linear_sum_assignment(np.abs(computed[:, None] - reference[None, :]))
    out = np.empty_like(reference)
    out[i] = reference[j]
    return out


def cantilever_beam(
    ne: int = 40,
    L: float = 2.0,
    E: float = 2.1e11,
    I: float = 8.33e-10,
    rhoA: float = 0.785,
    c: float = 50.0,
    at: int | None = None,
):
    """A clamped-free Euler-Bernoulli beam of Hermite cubic elements with one dashpot.

    The textbook element matrices

    .. math::
        k_e = \\frac{EI}{l^3}\\begin{bmatrix}12 & 6l & -12 & 6l\\\\ 6l & 4l^2 & -6l & 2l^2\\\\
              -12 & -6l & 12 & -6l\\\\ 6l & 2l^2 & -6l & 4l^2\\end{bmatrix},\\quad
        m_e = \\frac{\\rho A\\, l}{420}\\begin{bmatrix}156 & 22l & 54 & -13l\\\\ 22l & 4l^2 & 13l & -3l^2\\\\
              54 & 13l & 156 & -22l\\\\ -13l & -3l^2 & -22l & 4l^2\\end{bmatrix}

    are assembled over ``ne`` elements of length l = L / ne; coordinates
    (w_i [m], theta_i [rad]), i = 1..ne, after clamping node 0.  Defaults: a
    2 m steel strip.  Deflections and rotations mix in one vector, so K spans
    many decades: the badly scaled damped beam of SPEC section 4.

    Parameters
    ----------
    ne : int
        Number of elements (n = 2 ne coordinates).
    L, E, I, rhoA : float
        Length [m], Young's modulus [Pa], second moment of area [m^4], mass per length [kg/m].
    c : float
        Dashpot [N s/m] on the transverse displacement of node ``at`` (default the tip).
    at : int, optional
        Node 1..ne carrying the dashpot.

    Returns
    -------
    LinearizedSystem
    """
    from .linearization.system import LinearizedSystem

    if not isinstance(ne, (int, np.integer)) or ne < 1:
        raise ParameterError("ne", f"expected an integer >= 1, got {ne!r}")
    node = ne if at is None else at
    if not isinstance(node, (int, np.integer)) or not 1 <= node <= ne:
        raise ParameterError("at", f"expected a node in 1..{ne}, got {at!r}")
    l = L / ne
    k = E * I / l**3 * np.array(
        [[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l], [-12, -6 * l, 12, -6 * l],
         [6 * l, 2 * l * l, -6 * l, 4 * l * l]]
    )
    m = rhoA * l / 420 * np.array(
        [[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l], [54, 13 * l, 156, -22 * l],
         [-13 * l, -3 * l * l, -22 * l, 4 * l * l]]
    )
    nd = 2 * (ne + 1)
    K = np.zeros((nd, nd))
    M = np.zeros((nd, nd))
    for e in range(ne):
        ix = np.ix_(range(2 * e, 2 * e + 4), range(2 * e, 2 * e + 4))
        K[ix] += k
        M[ix] += m
    K, M = K[2:, 2:], M[2:, 2:]
    D = np.zeros_like(K)
    j = 2 * (node - 1)
    D[j, j] = c
    Z = np.zeros_like(K)
    return LinearizedSystem(M, D, Z, K, Z)
