"""The clusters of a computed spectrum: their Jordan structure and their left vectors (theory: spectrum).

:func:`analyse_clusters` groups the computed eigenvalues that rounding cannot
tell apart and decides each group's partial multiplicities
(:func:`~pinlin.spectral.multiplicity.analyse_cluster`); :func:`cluster_figures`
then biorthogonalizes the left vectors of the semisimple clusters and gives the
defective ones their error model.

The coefficients are real, so L(conj lam) = conj L(lam): the eigenvalue conj lam
has the Jordan structure of lam, its vectors are the conjugates.  A cluster
whose members are exactly the conjugates of the previous cluster's (the
order of the spectrum puts conjugate groups next to each other) takes that
cluster's structure, and, when its vectors are exactly the conjugates too, its
biorthogonalized left vectors, without computing them again: the same numbers
to the last bit, since every operation of that computation commutes exactly
with conjugation (IEEE rounding is symmetric under negation).
"""

from __future__ import annotations

import time
from itertools import accumulate

import numpy as np

from ..numerics.accuracy import ETA_FLOOR
from ..numerics.clustering import find_clusters
from ..numerics.floating import EPS
from ..numerics.norms import column_norms
from .accuracy import DefectiveBound, ErrorModel, PairFigures, defective_scale
from .multiplicity import Cluster, ClusterEvidence, analyse_cluster
from .problem import QuadraticProblem

__all__ = ["BIORTHOGONAL_RCOND", "analyse_clusters", "cluster_figures"]

#: The left vectors of a semisimple cluster are biorthogonalized (Y^T L' X = I)
#: only when sigma_min / sigma_max of Y^T L' X exceeds this: a thousand times the
#: rounding level of that SVD, so that the inverse keeps three digits or more.
BIORTHOGONAL_RCOND = 1e3 * EPS

_CONJUGATE_METHOD = " (taken from the conjugate cluster: L(conj lam) = conj L(lam), real coefficients)"


def _taken_from(partner: Cluster, indices: tuple[int, ...]) -> Cluster | None:
    """The cluster at ``indices`` as the conjugate of ``partner``, its members known to be exactly the conjugates of
    partner's (bit for bit), or None when partner is real (its own conjugate) or of another size.  The center is
    the conjugate of partner's (the mean of conjugates is the conjugate of the mean, to the last bit), the
    spread and the structure are partner's."""
    if len(indices) != partner.algebraic or partner.center.imag == 0:
        return None
    t0 = time.perf_counter()
    method = partner.method if partner.method.endswith(_CONJUGATE_METHOD) else partner.method + _CONJUGATE_METHOD
    p = partner
    return Cluster(
        indices=tuple(indices), center=p.center.conjugate(), algebraic=p.algebraic, geometric=p.geometric,
        partial=p.partial, consistent=p.consistent, kernel_dims=p.kernel_dims, note=p.note, error=p.error,
        method=method, elapsed=time.perf_counter() - t0,
    )


def analyse_clusters(
    problem: QuadraticProblem, lam, fig: PairFigures, tolerances, mirrored: bool = False
) -> tuple[list[Cluster], list[str], dict[int, int]]:
    """Multiple eigenvalues: clusters of computed ones with their Jordan structure, notes, and the conjugate mates
    of :func:`cluster_figures` found on the way.

    The computed vectors and figures go along as the evidence of
    :func:`~pinlin.spectral.multiplicity.semisimple_certificate` (semisimple
    clusters without an SVD); ``mirrored``: the eigenvalues are pairs of a
    symmetric definite pencil sharing one vector.

    The members and vectors of each group are compared with those of the group before it
    once, for all groups together (:func:`_conjugate_groups`): the structure of a group of
    exact conjugates is taken from its partner, and a cluster whose vectors are exact
    conjugates too gets its partner's left vectors in :func:`cluster_figures` (``mates``,
    {k: k - 1} by position in the returned list).
    """
    notes: list[str] = []
    clusters: list[Cluster] = []
    groups = find_clusters(
        lam, tolerances["cluster_tol"], problem.scaling.gamma, fig.error_bound, tolerances["safety"]
    )
    if not groups:
        return clusters, notes, {}
    weight = fig.weight
    if weight is None:
        with np.errstate(over="ignore", invalid="ignore"):
            weight = problem.weight(lam)
    evidence = ClusterEvidence(
        right=fig.right, sensitivity=fig.sensitivity, bound=fig.error_bound,
        backward_error=fig.backward_error, weight=weight, mirrored=mirrored,
    )
    same_lam, same_all = _conjugate_groups(lam, fig, groups)
    c = None
    origin: list[int] = []
    for g, idx in enumerate(groups):
        c = _taken_from(c, idx) if c is not None and same_lam[g] else None
        if c is None:
            c = analyse_cluster(problem, lam, idx, tolerances["rank_tol"], evidence)
        if c.geometric == 0:
            notes.append(
                f"eigenvalues {[i + 1 for i in idx]} are within cluster_tol but L is nonsingular at their mean "
                f"(rank_tol {tolerances['rank_tol']:g}): treated as distinct"
            )
            continue
        if not c.consistent:
            notes.append(c.note)
        clusters.append(c)
        origin.append(g)
    mates: dict[int, int] = {}
    for k in range(1, len(clusters)):
        g = origin[k]
        if (origin[k - 1] == g - 1 and same_all[g] and clusters[k].index == 1 and clusters[k - 1].index == 1
                and k - 1 not in mates):
            mates[k] = k - 1
    return clusters, notes, mates


def _conjugate_groups(lam: np.ndarray, fig: PairFigures, groups) -> tuple[np.ndarray, np.ndarray]:
    """(same_lam, same_all), one flag per group: its members are exactly (bit for bit, member by member) the
    conjugates of those of the group before it of the same size; same_all: their right and unit left vectors too.

    One comparison of each array for all groups together (a clustered spectrum of a real problem has its
    clusters in conjugate pairs next to each other).
    """
    same_lam = np.zeros(len(groups), dtype=bool)
    same_all = np.zeros(len(groups), dtype=bool)
    cand = [g for g in range(1, len(groups)) if len(groups[g]) == len(groups[g - 1])]
    if not cand:
        return same_lam, same_all
    ii = [i for g in cand for i in groups[g]]
    pp = [i for g in cand for i in groups[g - 1]]
    m = len(ii)
    both = ii + pp  # one gather of each array: the candidates' members, then their partners'
    z = lam.take(both)
    same = z[:m] == z[m:].conj()
    starts = list(accumulate([len(groups[g]) for g in cand[:-1]], initial=0))
    same_lam[cand] = np.logical_and.reduceat(same, starts)
    for vectors in (fig.right, fig.left_unit):
        V = vectors.take(both, axis=1)
        same &= np.logical_and.reduce(V[:, :m] == V[:, m:].conj(), axis=0)
    same_all[cand] = np.logical_and.reduceat(same, starts)
    return same_lam, same_all


def cluster_figures(problem: QuadraticProblem, lam, fig: PairFigures, clusters, mates: dict[int, int]):
    """Left vectors and the error model corrected for the clusters (defective members: kappa = inf, see Modes).

    A semisimple cluster gets left vectors biorthogonalized at its mean
    (Y^T L'(lam_c) X = I) and sensitivities w(lam) ||y||; a defective one unit
    left vectors, kappa = inf and the bound spread + scale eta^(1/p)
    (:class:`~pinlin.spectral.accuracy.DefectiveBound`, :func:`defective_scale`).
    A semisimple cluster whose members and vectors are exactly the conjugates of
    the previous cluster's takes the conjugates of its biorthogonalized vectors
    (``mates`` as :func:`analyse_clusters` found them).
    """
    eta = np.maximum(fig.backward_error, ETA_FLOOR)
    if not clusters:  # the figures' own arrays (fresh from pair_figures, owned by this analysis)
        return fig.left, fig.left_normalized, _model(eta, fig.sensitivity, ()), []
    left = fig.left.copy()
    left_ok = fig.left_normalized.copy()
    sens = fig.sensitivity.copy()
    defective = []
    notes: list[str] = []
    done = set()  # the clusters biorthogonalized here
    for k, c in enumerate(clusters):
        if k in mates:
            continue
        ii = np.array(c.indices, dtype=np.intp)  # one index array for all the gathers and writes below
        if c.index == 1:  # semisimple, or chains of length one that do not add up (inconsistent ranks)
            if _biorthogonalize(problem, lam, fig, c, ii, left, left_ok, sens):
                done.add(k)
            else:
                notes.append(f"cluster at {c.center:.6g}: left vectors could not be biorthogonalized")
        else:
            left[:, ii] = fig.left_unit[:, ii]
            left_ok[ii] = False
            sens[ii] = np.inf
            spread = float(np.max(np.abs(lam[ii] - c.center)))
            scale = defective_scale(problem, c.center, c.index)
            defective.append(DefectiveBound(
                indices=tuple(c.indices), spread=spread, scale=scale, eta=float(np.max(eta[ii])),
                index=c.index,
            ))
    if mates:
        _take_mates(problem, lam, fig, clusters, mates, done, (left, left_ok, sens), notes)
    return left, left_ok, _model(eta, sens, tuple(defective)), notes


def _take_mates(
    problem: QuadraticProblem, lam, fig: PairFigures, clusters, mates, done, out, notes: list[str]
) -> None:
    """The mates' left vectors and sensitivities: the conjugates of their partners' where those have
    normalized left vectors (one gather for all of them), computed afresh otherwise; written into ``out``.

    ``done``: the clusters whose left vectors were biorthogonalized (all normalized then).
    """
    left, left_ok, sens = out
    ks = list(mates)
    ii = [i for k in ks for i in clusters[k].indices]
    pp = [i for k in ks for i in clusters[mates[k]].indices]
    if all(mates[k] in done for k in ks):
        ok = None
    else:
        starts = list(accumulate([clusters[k].algebraic for k in ks[:-1]], initial=0))
        ok = np.logical_and.reduceat(left_ok.take(pp), starts)
    if ok is None or ok.all():
        left[:, ii] = left.take(pp, axis=1).conj()
        left_ok[ii] = True
        sens[ii] = sens.take(pp)
        return
    for k, fine in zip(ks, ok.tolist()):
        kk, pk = list(clusters[k].indices), list(clusters[mates[k]].indices)
        if fine:
            left[:, kk] = left[:, pk].conj()
            left_ok[kk] = True
            sens[kk] = sens[pk]
        elif not _biorthogonalize(problem, lam, fig, clusters[k], kk, left, left_ok, sens):
            notes.append(f"cluster at {clusters[k].center:.6g}: left vectors could not be biorthogonalized")


def _biorthogonalize(problem: QuadraticProblem, lam, fig: PairFigures, c: Cluster, ii, left, left_ok, sens) -> bool:
    """Left vectors of a semisimple cluster scaled so that Y^T L'(center) X = I, written into the arrays given.

    False (nothing written) when Y^T L' X is numerically singular (:data:`BIORTHOGONAL_RCOND`).
    """
    Y = fig.left_unit[:, ii]
    P = Y.T @ (2 * c.center * problem.M + problem.C) @ fig.right[:, ii]
    try:
        sv = np.linalg.svd(P, compute_uv=False)
        if sv[0] == 0 or sv[-1] <= BIORTHOGONAL_RCOND * sv[0]:
            return False
        Yn = np.linalg.solve(P, Y.T).T  # Yn^T Lp X = I
    except np.linalg.LinAlgError:
        return False
    left[:, ii] = Yn
    left_ok[ii] = True
    weight = problem.weight(lam[ii]) if fig.weight is None else fig.weight.take(ii)
    sens[ii] = weight * column_norms(Yn)
    return True


def _model(eta: np.ndarray, sensitivity: np.ndarray, defective: tuple) -> ErrorModel:
    """The error model with its arrays made read-only (the verdict formed later reads them; nobody writes them)."""
    eta.flags.writeable = False
    sensitivity.flags.writeable = False
    return ErrorModel(eta=eta, sensitivity=sensitivity, defective=defective)
