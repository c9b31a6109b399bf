"""The order of a computed spectrum and the per-eigenvalue kinds (theory: conventions, docs/conventions.md).

Eigenvalues are listed by ascending |lam|; a conjugate pair is adjacent with
Im lam > 0 first; among equal |lam| the smaller real part comes first.  Both
functions work on whole arrays (no loop over eigenvalues).
"""

from __future__ import annotations

import numpy as np

from ..numerics.accuracy import residual_figures
from .accuracy import PairFigures, pair_figures
from .multiplicity import Cluster
from .problem import QuadraticProblem
from .raw import RawSpectrum

__all__ = ["order_spectrum", "spectrum_order", "mode_kinds", "mirrored_figures"]


def _pairs(lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(leaders, mates): each real eigenvalue (mate -1) and each Im > 0 member with the index of its conjugate.

    LAPACK and the structured paths store a pair adjacently (Im > 0 first); any
    other arrangement is matched by exact conjugate value.  A member whose exact
    conjugate is missing stands alone.
    """
    im = lam.imag
    pos = (im > 0).nonzero()[0]
    neg = (im < 0).nonzero()[0]
    real = (im == 0).nonzero()[0]
    adjacent = pos.size == neg.size and (
        pos.size == 0
        or (np.count_nonzero(neg - pos == 1) == pos.size and np.count_nonzero(lam.take(neg) == lam.take(pos).conj())
            == pos.size)
    )
    if adjacent:
        mates = neg
        alone = np.zeros(0, dtype=int)
    else:
        free: dict[complex, list[int]] = {}
        for i in neg:
            free.setdefault(complex(lam[i]), []).append(int(i))
        found = []
        for i in pos:
            partners = free.get(complex(np.conj(lam[i])))
            found.append(partners.pop() if partners else -1)
        mates = np.array(found, dtype=int)
        alone = np.array([i for rest in free.values() for i in rest], dtype=int)
    # (integer index arrays throughout: nonzero's, and the int arrays above)
    leaders = np.concatenate([pos, real, alone])
    mates = np.concatenate([mates, np.full(real.size + alone.size, -1)])
    return leaders, mates


def spectrum_order(lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(perm, at): ``lam[perm]`` is in the order of the module doc; ``at`` holds the new positions of the
    Im > 0 members of the conjugate pairs (their mates follow at ``at + 1``)."""
    leaders, mates = _pairs(lam)
    first = lam.take(leaders)
    keys = np.lexsort((-np.abs(first.imag), first.real, np.abs(first)))
    leaders, mates = leaders.take(keys), mates.take(keys)
    paired = mates >= 0
    sizes = 1 + paired
    start = np.cumsum(sizes) - sizes  # new position of each leader
    at = start[paired]
    perm = np.empty(lam.shape[0], dtype=int)
    perm[start] = leaders
    perm[at + 1] = mates[paired]
    return perm, at


def order_spectrum(raw: RawSpectrum) -> RawSpectrum:
    """Sort by |lam|, conjugate pairs adjacent (Im > 0 first), and make pair vectors exact conjugates.

    A spectrum its solver path already ordered (``raw.ordered``) is returned as it is.
    """
    if raw.ordered:
        return raw
    lam = raw.lam
    perm, at = spectrum_order(lam)
    P = raw.P.take(perm, axis=-1)
    P[..., at + 1] = P[..., at].conj()
    Y = None
    if raw.Y is not None:
        Y = raw.Y.take(perm, axis=-1)
        Y[:, at + 1] = Y[:, at].conj()
    block = raw.block.take(perm)
    block[at + 1] = block[at]
    eta = _permuted(raw.eta, perm, at)
    return RawSpectrum(lam=lam.take(perm), P=P, Y=Y, block=block, eta=eta, note=raw.note, second=raw.second,
                       norm_x=_permuted(raw.norm_x, perm, at), weight=_permuted(raw.weight, perm, at), ordered=True)


def _permuted(a: np.ndarray | None, perm: np.ndarray, at: np.ndarray) -> np.ndarray | None:
    """A per-pair figure in the new order, the second member of each conjugate pair given the first's value."""
    if a is None:
        return None
    out = a.take(perm)
    out[at + 1] = out[at]
    return out


def _interleave(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Columns (last axis) a_0, b_0, a_1, b_1, ..."""
    out = np.empty(a.shape[:-1] + (2 * a.shape[-1],), dtype=np.result_type(a, b))
    out[..., 0::2], out[..., 1::2] = a, b
    return out


def mirrored_figures(
    problem: QuadraticProblem, raw: RawSpectrum
) -> tuple[np.ndarray, np.ndarray, PairFigures, np.ndarray]:
    """Order a mirrored spectrum and compute its pair figures on one member of each pair (half the work).

    The structured paths give pairs (a, b) sharing one real vector x with
    |lam_b| = |lam_a| and lam_b = -lam_a (C = 0) or conj(lam_a): then L(lam_b) x
    is L(lam_a) x or its conjugate, so both have the same backward error, and
    |y^T L'(lam) x|, hence the sensitivity and the bound, agree; only L'(lam_b)
    and the normalized left vector x / (x^T L'(lam_b) x) differ, and are formed
    for b.  The pairs are sorted by the keys :func:`order_spectrum` uses, then
    (a, b) interleaved: the same order and figures as the expanded spectrum.
    The weights w(lam) are those
    of the residual figures: |lam_b| = |lam_a| exactly (negation and
    conjugation are exact), so w(lam_b) = w(lam_a).

    Returns
    -------
    lam : (2n,) complex
    block : (2n,) int
    fig : PairFigures
    weight : (2n,) float
        w(lam) = |lam|^2 ||M|| + |lam| ||C|| + ||K|| per eigenvalue.
    """
    la, lb, P, block = raw.lam, raw.second, raw.P, raw.block
    keys = np.lexsort((-np.abs(la.imag), la.real, np.abs(la)))
    la, lb, P, block = la.take(keys), lb.take(keys), P.take(keys, axis=-1), block.take(keys)
    eta, norm_x, weight = residual_figures(la, *P, problem.norms)
    half = pair_figures(problem, la, P, None, eta, norm_x, weight)
    yMx, yCx = half.products[0], half.products[1]
    deriv_b = 2 * lb * yMx + yCx
    ok = half.left_normalized
    left_b = np.where(ok, half.right / np.where(ok, deriv_b, 1.0), half.right)
    right = np.repeat(half.right.astype(complex), 2, axis=-1)
    weight = np.repeat(weight, 2)
    fig = PairFigures(
        right=right,
        left=_interleave(half.left, left_b),
        left_normalized=np.repeat(ok, 2),
        derivative=_interleave(half.derivative, deriv_b),
        backward_error=np.repeat(half.backward_error, 2),
        error_bound=np.repeat(half.error_bound, 2),
        sensitivity=np.repeat(half.sensitivity, 2),
        left_unit=right,
        products=np.repeat(half.products, 2, axis=-1),
        quadratic=np.repeat(half.quadratic, 2, axis=-1),
        weight=weight,
    )
    return _interleave(la, lb), np.repeat(block, 2), fig, weight


def mode_kinds(
    lam: np.ndarray, r: np.ndarray, clusters: tuple[Cluster, ...] | list[Cluster], undamped: bool = False
) -> tuple[str, ...]:
    """Per eigenvalue one of MODE_KINDS against its bound r; cluster members by the cluster's mean.

    "rigid_body": |lam| <= r; "unstable": Re lam > r; "underdamped": |Im lam| > r;
    "overdamped" otherwise (theory: stability).  With ``undamped`` (D = 0 and G = 0 or
    N = 0 exactly: the spectrum is symmetric in the imaginary axis) an oscillating
    eigenvalue with |Re lam| <= r is "undamped": its damping is none, not small.
    """
    typical = lam
    if clusters:
        typical = lam.copy()
        typical[[i for c in clusters for i in c.indices]] = [c.center for c in clusters for _ in c.indices]
    # codes into _KINDS, the later tests taking precedence as in theory: stability's order
    code = np.full(typical.shape[0], 2)  # "overdamped"
    code[np.abs(typical.imag) > r] = 1  # "underdamped"
    if undamped:
        code[(code == 1) & (np.abs(typical.real) <= r)] = 4  # "undamped"
    code[typical.real > r] = 3  # "unstable"
    code[np.abs(typical) <= r] = 0  # "rigid_body"
    return tuple([_KINDS[c] for c in code.tolist()])


#: The per-eigenvalue kinds by code (the order of :data:`pinlin.spectral.modes.MODE_KINDS`).
_KINDS = ("rigid_body", "underdamped", "overdamped", "unstable", "undamped")
