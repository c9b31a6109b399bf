"""Grouping computed eigenvalues that rounding cannot tell apart (SPEC section 4).

Rounding splits an eigenvalue with Jordan chains of length p into p computed
eigenvalues about eta^(1/p) |lam| apart; a multiple eigenvalue is recognised
as a cluster of them, whose mean is accurate to about eta.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

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
    a = np.abs(lam)
    # candidates only: |lam_i - lam_j| >= ||lam_i| - |lam_j||, so linked eigenvalues have moduli within
    # cluster_tol max(|lam_j|, scale) of each other; sorted by modulus, each is compared with those in that window
    order = np.argsort(a, kind="stable")
    sa = a[order]
    with np.errstate(divide="ignore", invalid="ignore"):
        reach = sa + cluster_tol * np.maximum(sa, scale) / (1.0 - cluster_tol)
    hi = np.searchsorted(sa, reach, side="right")
    counts = np.maximum(hi - np.arange(k) - 1, 0)
    total = int(counts.sum())
    if total == 0:
        return [(i,) for i in range(k)] if singletons else []
    first = np.repeat(np.arange(k), counts)
    step = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    i, j = order[first], order[first + 1 + step]
    dist = np.abs(lam[i] - lam[j])
    linked = dist <= cluster_tol * np.maximum(np.maximum(a[i], a[j]), scale)
    if bound is not None:
        r = np.asarray(bound, dtype=float)
        with np.errstate(invalid="ignore"):
            linked &= dist <= factor * (r[i] + r[j])
    if not linked.any():
        return [(i,) for i in range(k)] if singletons else []
    adj = csr_matrix((np.ones(int(linked.sum())), (i[linked], j[linked])), shape=(k, k))
    _, labels = connected_components(adj, directed=False)
    groups: dict[int, list[int]] = {}
    for idx in range(k):
        groups.setdefault(int(labels[idx]), []).append(idx)
    least = 1 if singletons else 2
    return sorted((tuple(g) for g in groups.values() if len(g) >= least), key=lambda g: g[0])
