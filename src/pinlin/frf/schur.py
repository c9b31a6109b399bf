"""H(s) B at many points from one generalized real Schur form (theory: flexibility, responses; Laub 1981 in pencil form).

The direct method's LU of L(s) per point costs O(n^3) per point.  For many
points the pencil of the scaled first companion form (s = gamma mu, see
:class:`pinlin.numerics.Scaling`)

.. math::
    (\\mu B - A) z = \\begin{bmatrix} f \\\\ 0 \\end{bmatrix},\\quad
    A = \\begin{bmatrix} -C_s & -K_s \\\\ I & 0 \\end{bmatrix},\\;
    B = \\begin{bmatrix} M_s & 0 \\\\ 0 & I \\end{bmatrix},\\quad
    z = \\begin{bmatrix} \\mu x \\\\ x \\end{bmatrix},\\quad
    x = L_s(\\mu)^{-1} f = \\frac{1}{\\delta} H(s) f

is reduced once to real generalized Schur form, A = Q S Z^T, B = Q T Z^T
(LAPACK ``dgges`` through :func:`scipy.linalg.qz`: S quasi-triangular with
1 x 1 and 2 x 2 diagonal blocks, T triangular), in O(n^3); then every point
costs one quasi-triangular solve (mu T - S) y = Q^T (f, 0), O(n^2) per
right-hand side, and x = Z[n:] y.  Laub ("Efficient multivariable frequency
response computations", IEEE TAC 26, 1981) reduces A of a state-space model to
Hessenberg form; the pencil form needs no M^-1 and its triangular solves need
no pivoting across points.  QZ and the triangular solves are backward stable
for the (scaled) pencil; the engine still measures the relative defect of
L(s) X = B at every point when asked.

The back substitution runs over blocks of rows for all points at once: a
block's own rows one after the other, then one matrix product updates every
row above it (:data:`PANEL_ROWS` rows per block).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..linearization.system import LinearizedSystem
from ..numerics import CHUNK_BYTES, system_scaling

__all__ = ["SchurPencil", "schur_pencil", "schur_solve", "PANEL_ROWS", "schur_pays"]

#: Rows of the quasi-triangular system solved together before one matrix product updates
#: the rows above: large enough for the product to run at matrix-product speed, small
#: enough that the row-by-row work inside a panel stays a minor part.
PANEL_ROWS = 32

#: Real multiply-adds per point of a complex LU of L(s) are about this times n^3 (complex
#: LU: n^3 / 3 complex multiply-adds of four real ones each) ...
_LU_COST = 4.0 / 3.0
#: ... and of one generalized real Schur reduction of the 2n companion pencil about this
#: times (2n)^3 (Golub and Van Loan, QZ with Q and Z: about 66 n^3 flops for a pencil of size n).
_QZ_COST = 33.0


def schur_pays(n: int, points: int, columns: int) -> bool:
    """Whether one Schur reduction and per-point triangular solves cost less than an LU per point.

    .. math::  66\\,(2n)^3/2 + F\\,(2n)^2\\,m \\cdot 4 \\;<\\; F\\,(\\tfrac43 n^3 + 4 n^2 m)
    """
    N = 2 * n
    schur = _QZ_COST * N**3 + points * 4.0 * N * N * columns
    lu = points * (_LU_COST * n**3 + 4.0 * n * n * columns)
    return schur < lu


@dataclass(frozen=True, eq=False)
class SchurPencil:
    """The real generalized Schur form of a system's scaled companion pencil.

    Attributes
    ----------
    S, T : (2n, 2n) float
        Quasi-triangular and triangular factors: Q^T A Z = S, Q^T B Z = T.
    Q, Z : (2n, 2n) float
        Orthogonal factors.
    gamma, delta : float
        The Fan-Lin-Van Dooren scaling: s = gamma mu, H(s) = delta L_s(mu)^-1.
    starts : tuple of int
        First row of each diagonal block of S, top to bottom.
    sizes : tuple of int
        Their sizes (1 or 2).
    """

    S: np.ndarray
    T: np.ndarray
    Q: np.ndarray
    Z: np.ndarray
    gamma: float
    delta: float
    starts: tuple[int, ...]
    sizes: tuple[int, ...]


def schur_pencil(sys: LinearizedSystem) -> SchurPencil:
    """Reduce the scaled companion pencil of ``sys`` to real generalized Schur form (one QZ, O(n^3))."""
    n = sys.n
    sc = system_scaling(sys.M, sys.C, sys.K)
    g, d = sc.gamma, sc.delta
    A = np.zeros((2 * n, 2 * n))
    B = np.zeros((2 * n, 2 * n))
    A[:n, :n] = -(g * d) * sys.C
    A[:n, n:] = -d * sys.K
    np.fill_diagonal(A[n:, :n], 1.0)
    B[:n, :n] = (g * g * d) * sys.M
    np.fill_diagonal(B[n:, n:], 1.0)
    S, T, Q, Z = scipy.linalg.qz(A, B, output="real", check_finite=False)
    sub = np.flatnonzero(np.diagonal(S, -1) != 0)  # a nonzero subdiagonal entry opens a 2 x 2 block
    starts, sizes, i = [], [], 0
    opens = set(sub.tolist())
    while i < 2 * n:
        size = 2 if i in opens else 1
        starts.append(i)
        sizes.append(size)
        i += size
    return SchurPencil(S, T, Q, Z, float(g), float(d), tuple(starts), tuple(sizes))


def _solve_block(S, T, i: int, size: int, mu: np.ndarray, R: np.ndarray) -> np.ndarray:
    """y of one diagonal block: (mu T_ii - S_ii) y = R for every column (mu per column); pivoted 2 x 2."""
    if size == 1:
        return R[0] / (mu * T[i, i] - S[i, i])
    a = mu * T[i, i] - S[i, i]
    b = mu * T[i, i + 1] - S[i, i + 1]
    c = mu * T[i + 1, i] - S[i + 1, i]
    e = mu * T[i + 1, i + 1] - S[i + 1, i + 1]
    swap = np.abs(c) > np.abs(a)  # partial pivoting, per column
    a, c = np.where(swap, c, a), np.where(swap, a, c)
    b, e = np.where(swap, e, b), np.where(swap, b, e)
    r0, r1 = np.where(swap, R[1], R[0]), np.where(swap, R[0], R[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        f = c / a
        y1 = (r1 - f * r0) / (e - f * b)
        y0 = (r0 - b * y1) / a
    return np.stack([y0, y1])


def _back_substitute(p: SchurPencil, mu: np.ndarray, R: np.ndarray) -> np.ndarray:
    """Y with (mu_c T - S) Y[:, c] = R[:, c] for every column c; R (2n, k) complex is overwritten."""
    S, T = p.S, p.T
    Y = np.empty_like(R)
    blocks = list(zip(p.starts, p.sizes))
    top = len(blocks)
    while top > 0:
        # a panel of blocks ending at `top`, about PANEL_ROWS rows
        low = top
        while low > 0 and blocks[top - 1][0] + blocks[top - 1][1] - blocks[low - 1][0] < PANEL_ROWS:
            low -= 1
        lo = blocks[low][0]
        for j in range(top - 1, low - 1, -1):
            i, size = blocks[j]
            Y[i : i + size] = _solve_block(S, T, i, size, mu, R[i : i + size])
            if i > lo:  # the rows of the panel above this block
                yv = Y[i : i + size]
                R[lo:i] -= mu * (T[lo:i, i : i + size] @ yv) - S[lo:i, i : i + size] @ yv
        if lo > 0:  # every row above the panel, in one product per factor (real matrices on complex columns)
            hi = blocks[top - 1][0] + blocks[top - 1][1]
            yv = np.ascontiguousarray(Y[lo:hi]).view(float)
            R[:lo] -= mu * (T[:lo, lo:hi] @ yv).view(complex) - (S[:lo, lo:hi] @ yv).view(complex)
        top = low
    return Y


def schur_solve(p: SchurPencil, s: np.ndarray, B: np.ndarray, budget: int = CHUNK_BYTES) -> np.ndarray:
    """X(s) = H(s) B at every point from the Schur form: (len(s), n, m) complex (all n rows).

    Points are taken in chunks whose (2n, points m) right-hand sides fit ``budget`` bytes.
    At an eigenvalue a diagonal block is singular and X is inf or NaN there (the
    engine's amplification test reports it as a pole).
    """
    N = p.S.shape[0]
    n = N // 2
    m = B.shape[1]
    rhs = p.Q.T[:, :n] @ np.asarray(B, dtype=complex)  # Q^T (f, 0): the same for every point
    X = np.empty((s.size, n, m), dtype=complex)
    per = max(1, budget // (16 * 4 * N * m))  # R, Y and two temporaries of (2n, points m)
    Zx = p.Z[n:]
    for start in range(0, s.size, per):
        sl = slice(start, min(s.size, start + per))
        F = sl.stop - sl.start
        mu = np.repeat(s[sl] / p.gamma, m)  # one value per column (point, input)
        R = np.tile(rhs, (1, F))
        with np.errstate(over="ignore", invalid="ignore"):
            Y = _back_substitute(p, mu, R)
            Xs = (Zx @ Y.view(float)).view(complex) * p.delta  # (n, F m)
        X[sl] = Xs.reshape(n, F, m).transpose(1, 0, 2)
    return X
