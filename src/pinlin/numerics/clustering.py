"""Grouping computed eigenvalues that rounding cannot tell apart (theory: spectrum).

Rounding splits an eigenvalue with Jordan chains of length p into p computed
eigenvalues about eta^(1/p) |lam| apart; a multiple eigenvalue is recognised
as a cluster of them, whose mean is accurate to about eta.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["CLUSTER_TOL", "CLUSTER_BOUND_FACTOR", "find_clusters"]

#: Default relative distance below which computed eigenvalues form one cluster.
#: Rounding moves an eigenvalue with chains of length p by about eps^(1/p)
#: (1.5e-8 for p = 2, 6e-6 for p = 3, times its condition), so 1e-5 regroups
#: double and well-conditioned triple roots.
CLUSTER_TOL = 1e-5

#: Default factor on the sum of two eigenvalues' first-order error bounds within
#: which they may be one multiple eigenvalue: the bounds are first-order
#: estimates, so a margin of one decade keeps a genuine split pair together.
CLUSTER_BOUND_FACTOR = 10.0


#: Factor on cluster_tol in the quick test of :func:`_far_apart`: the moduli and their
#: differences carry a few eps of relative rounding, so the test is widened far beyond it
#: and stays a sufficient condition for "no pair within cluster_tol".
_FAR_MARGIN = 1.0 + 1e-8


def find_clusters(
    lam,
    cluster_tol: float = CLUSTER_TOL,
    scale: float = 0.0,
    bound=None,
    factor: float = CLUSTER_BOUND_FACTOR,
    *,
    singletons: bool = False,
) -> list[tuple[int, ...]]:
    """Groups of eigenvalues that rounding cannot tell apart.

    lam_i and lam_j are linked when both

    .. math::
        |\\lambda_i - \\lambda_j| \\le \\text{cluster\\_tol}\\,\\max(|\\lambda_i|, |\\lambda_j|, \\text{scale})
        \\quad\\text{and}\\quad
        |\\lambda_i - \\lambda_j| \\le \\text{factor}\\,(r_i + r_j)

    with r the first-order error bounds (when given): close eigenvalues that
    are each well-conditioned enough to be told apart are distinct, not a
    multiple root.  (A defective eigenvalue has r = inf or, split by rounding,
    r about its own spread.)  Single linkage (connected components); ``scale``
    [rad/s] keeps the test meaningful near lam = 0 (the spectral analysis passes
    the Fan-Lin-Van Dooren gamma).

    Returns
    -------
    list of tuple of int
        The groups, sorted by their first index; only groups of two or more
        unless ``singletons``.
    """
    lam = np.asarray(lam, dtype=complex)
    k = lam.shape[0]
    if not singletons and _far_apart(lam, cluster_tol, scale):
        return []
    a = np.abs(lam)
    # candidates only: |lam_i - lam_j| >= ||lam_i| - |lam_j||, so linked eigenvalues have moduli within
    # cluster_tol max(|lam_j|, scale) of each other; sorted by modulus, each is compared with those in that window
    order = np.argsort(a, kind="stable")
    sa = a[order]
    with np.errstate(divide="ignore", invalid="ignore"):
        reach = sa + cluster_tol * np.maximum(sa, scale) / (1.0 - cluster_tol)
    hi = sa.searchsorted(reach, side="right")
    counts = np.maximum(hi - np.arange(k) - 1, 0)
    total = int(counts.sum())
    if total == 0:
        return [(i,) for i in range(k)] if singletons else []
    first = np.arange(k).repeat(counts)
    step = np.arange(total) - (counts.cumsum() - counts).repeat(counts)
    i, j = order[first], order[first + 1 + step]
    dist = np.abs(lam[i] - lam[j])
    linked = dist <= cluster_tol * np.maximum(np.maximum(a[i], a[j]), scale)
    if bound is not None:
        r = np.asarray(bound, dtype=float)
        with np.errstate(invalid="ignore"):
            linked &= dist <= factor * (r[i] + r[j])
    if not linked.any():
        return [(i,) for i in range(k)] if singletons else []
    return _components(k, i[linked], j[linked], singletons)


def _components(k: int, first: np.ndarray, second: np.ndarray, singletons: bool) -> list[tuple[int, ...]]:
    """Connected components of the graph on 0..k-1 with edges (first[e], second[e]), single linkage.

    Labels propagated along the edges (each node takes the least label of its
    edges, then the label of its label) until nothing changes: a label is always
    a node of the same component and only decreases, and at the fixed point both
    ends of every edge carry one label.  A few numpy calls per round and two or
    three rounds for a clustered spectrum, where a Python union-find spends a
    call per edge end and scipy's sparse ``connected_components`` about a
    millisecond.  Each group's members ascending, the groups sorted by their
    first member; groups of one only with ``singletons``.
    """
    label = np.arange(k)
    while True:
        low = np.minimum(label[first], label[second])
        new = label.copy()
        np.minimum.at(new, first, low)
        np.minimum.at(new, second, low)
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    if singletons:
        nodes = np.arange(k)
    else:
        linked = np.zeros(k, dtype=bool)
        linked[first] = True
        linked[second] = True
        nodes = linked.nonzero()[0]
    order = label[nodes].argsort(kind="stable")  # by label, ascending within one (nodes are ascending)
    members = nodes[order]
    lab = label[members]
    cuts = ((lab[1:] != lab[:-1]).nonzero()[0] + 1).tolist()
    flat = members.tolist()
    least = 1 if singletons else 2
    groups = [tuple(flat[a:b]) for a, b in zip([0, *cuts], [*cuts, len(flat)]) if b - a >= least]
    return sorted(groups, key=lambda g: g[0])


def _far_apart(lam: np.ndarray, cluster_tol: float, scale: float) -> bool:
    """True when no two eigenvalues can be linked by the cluster_tol test (a cheap, sufficient check).

    Reflect every eigenvalue into the closed upper half plane, w = Re lam + i |Im lam|:
    two eigenvalues are at least as far apart as their images (same half plane: equal;
    opposite halves: reflecting one across the real axis brings it closer), and an
    image's distance is at least the difference of the moduli.  A conjugate pair has one
    image and distance 2 |Im lam|.  So when (a) the sorted distinct images are farther
    apart in modulus than the tolerance and (b) every complex eigenvalue is farther than
    it from its conjugate, no pair passes ``|lam_i - lam_j| <= cluster_tol max(|lam_i|,
    |lam_j|, scale)``.  Images are taken once per pair (the Im >= 0 members); a spectrum
    whose Im < 0 members do not each follow their exact conjugate, or with a non-finite
    member, gives False (the full search decides).
    """
    im = lam.imag
    down = (im < 0).nonzero()[0]
    # each member below the axis must follow its exact conjugate (the order of a computed spectrum)
    if down.size and not (down[0] > 0 and np.count_nonzero(lam.take(down - 1) == lam.take(down).conj()) == down.size):
        return False
    w = lam[im >= 0]
    size = np.abs(w)
    a = np.sort(size)
    if a.size == 0 or not math.isfinite(a[-1]):
        return False
    limit = (cluster_tol * _FAR_MARGIN) * np.maximum(a, scale)  # at least |lam_i - lam_j| for every candidate pair
    if a.size > 1 and np.count_nonzero(a[1:] - a[:-1] <= limit[1:]) != 0:
        return False
    self_gap = 2.0 * np.abs(w.imag)
    near = (self_gap > 0) & (self_gap <= (cluster_tol * _FAR_MARGIN) * np.maximum(size, scale))
    return np.count_nonzero(near) == 0
