"""``modal_analysis``: choose a solver path, solve, and attach every error figure.

See SPEC sections 4, 5 and 9 and :mod:`pinlin.spectral.structured` for the
paths.
"""

from __future__ import annotations

import time

import numpy as np

from ..errors import ParameterError
from .accuracy import ETA_FLOOR, pair_figures
from .jordan import CLUSTER_TOL, RANK_TOL, Cluster, analyse_cluster, find_clusters
from .modes import Method, Modes
from .problem import QuadraticProblem, Scaling, as_problem, check_tolerance
from .qep import RawSpectrum, solve_general
from .qualitative import DEFINITENESS_TOL, mode_constants, structural_facts
from .stability import STABILITY_SAFETY, decide_stability
from .structured import PATHS, proportionality_defect, solve_proportional, solve_squared, solve_symmetric

__all__ = ["modal_analysis", "STRUCTURE_TOL", "EIGH_TOL"]

#: Default relative defect below which damping counts as proportional
#: (commutator D M^-1 S - S M^-1 D, and the off-diagonal part left by the modes).
STRUCTURE_TOL = 1e-10

#: Default largest backward error accepted from the symmetric path's eigh.
EIGH_TOL = 1e-14


def _choose(problem: QuadraticProblem, method: str, structure_tol: float, eigh_tol: float):
    """(path name, reason, raw spectrum or None) for the requested method."""
    sys = problem.system
    if sys is None:
        if method not in ("auto", "general"):
            raise ParameterError(
                "method", f"the structured path {method!r} needs a LinearizedSystem; a tuple (M, C, K) is general"
            )
        return "general", "tuple input: general real coefficients, scaled companion QZ (size 2n)", None
    zD, zG, zN = sys.is_zero("D"), sys.is_zero("G"), sys.is_zero("N")
    if method == "general":
        return "general", "requested: scaled companion QZ (size 2n)", None
    if method == "symmetric" or (method == "auto" and zD and zG and zN):
        if not (zD and zG and zN):
            raise ParameterError("method", f"'symmetric' needs D = G = N = 0; nonzero: {sys.nonzero}")
        return "symmetric", "D = G = N = 0: lam = +-sqrt(-mu) with (S - mu M) phi = 0 (eigh, size n)", None
    if method == "squared" or (method == "auto" and zD and zG):
        if not (zD and zG):
            raise ParameterError("method", f"'squared' needs D = G = 0; nonzero: {sys.nonzero}")
        return (
            "squared",
            "D = G = 0, N != 0: L depends on lam^2 only; QZ of (-K, M) for mu = lam^2 (size n), lam = +-sqrt(mu)",
            None,
        )
    if method == "proportional" or (method == "auto" and zG and zN):
        if not (zG and zN):
            raise ParameterError("method", f"'proportional' needs G = N = 0; nonzero: {sys.nonzero}")
        comm = proportionality_defect(problem)
        raw = None
        defect = np.inf
        how = ""
        if comm <= structure_tol:
            raw, defect, how = solve_proportional(problem, structure_tol=structure_tol, eigh_tol=eigh_tol)
        if raw is not None:
            return (
                "proportional",
                f"G = N = 0, D M^-1 S = S M^-1 D (relative commutator {comm:.1e} <= structure_tol "
                f"{structure_tol:g}): modal decoupling by one {how} of size n"
                + (" (eigh lost accuracy: M ill-conditioned)" if how == "QZ" else "")
                + ", lam^2 + d_j lam + k_j = 0 per mode",
                raw,
            )
        why = f"relative commutator {comm:.1e}"
        if np.isfinite(defect) and comm <= structure_tol:
            why += f", modal residual {defect:.1e}"
        elif how == "QZ":
            why += ", QZ modes complex"
        if method == "proportional":
            raise ParameterError("method", f"'proportional' needs D M^-1 S = S M^-1 D; {why} > {structure_tol:g}")
        return "general", f"G = N = 0 but damping not proportional ({why} > structure_tol): scaled companion QZ", None
    if method != "auto":
        raise ParameterError("method", f"expected 'auto' or one of {PATHS}, got {method!r}")
    return "general", f"nonzero {'+'.join(sys.nonzero)}: no cheaper exact path; scaled companion QZ (size 2n)", None


def _order(raw: RawSpectrum) -> RawSpectrum:
    """Sort by |lam|, conjugate pairs adjacent (Im > 0 first), and make pair vectors exact conjugates."""
    lam = raw.lam
    neg: dict[complex, list[int]] = {}
    for i in np.flatnonzero(lam.imag < 0):
        neg.setdefault(complex(lam[i]), []).append(int(i))
    groups = []
    for i in np.flatnonzero(lam.imag > 0):
        partners = neg.get(complex(np.conj(lam[i])))
        if partners:
            groups.append((int(i), partners.pop()))
        else:
            groups.append((int(i),))
    groups += [(int(i),) for i in np.flatnonzero(lam.imag == 0)]
    groups += [(i,) for rest in neg.values() for i in rest]
    first = np.array([g[0] for g in groups])
    keys = np.lexsort((-np.abs(lam[first].imag), lam[first].real, np.abs(lam[first])))
    perm = np.array([i for g in keys for i in groups[g]], dtype=int)
    arrays = [a[:, perm] for a in (raw.X, raw.Y, raw.MX, raw.CX, raw.KX)]
    block = raw.block[perm].copy()
    pos = 0
    for g in keys:
        if len(groups[g]) == 2:
            for a in arrays:
                a[:, pos + 1] = np.conj(a[:, pos])
            block[pos + 1] = block[pos]
        pos += len(groups[g])
    return RawSpectrum(lam[perm], *arrays, block)


def modal_analysis(
    sys,
    *,
    method: str = "auto",
    scaling: bool = True,
    cluster_tol: float = CLUSTER_TOL,
    rank_tol: float = RANK_TOL,
    structure_tol: float = STRUCTURE_TOL,
    definiteness_tol: float = DEFINITENESS_TOL,
    safety: float = STABILITY_SAFETY,
    eigh_tol: float = EIGH_TOL,
) -> Modes:
    """Eigenvalues, eigenvectors, error figures and a stability verdict (SPEC sections 4, 5, 9).

    Solves L(lam) x = 0, y^T L(lam) = 0 with L(lam) = lam^2 M + lam C + K for
    all 2n eigentriples by the cheapest exact path the structure allows
    (``modes.method`` says which and why), then computes for every pair its
    backward error eta and condition number kappa, groups multiple eigenvalues
    and finds their Jordan structure from block Toeplitz ranks, evaluates the
    modal constants m, d, g, k, n, and decides stability honestly.

    Parameters
    ----------
    sys : LinearizedSystem or tuple (M, C, K)
        A tuple holds general real square matrices (M nonsingular, not
        necessarily symmetric) and always takes the general path.
    method : {"auto", "symmetric", "squared", "proportional", "general"}
        "auto" picks the cheapest applicable path; naming one forces it
        (ParameterError if it does not apply).
    scaling : bool
        Fan-Lin-Van Dooren scaling for the general path (default True;
        plus the tropical scalings, two more QZ runs, when ||C|| > 10 sqrt(||M|| ||K||),
        see :mod:`pinlin.spectral.qep`); False runs QZ on the unscaled pencil
        (for comparison).
    cluster_tol : float
        Relative distance under which computed eigenvalues are grouped as one
        multiple eigenvalue (see :data:`~pinlin.spectral.jordan.CLUSTER_TOL`).
    rank_tol : float
        Relative singular value threshold of the Jordan rank decisions.
    structure_tol : float
        Relative defect under which damping counts as proportional.
    definiteness_tol : float
        Relative eigenvalue threshold of the definiteness tests of D and S.
    safety : float
        Factor (>= 1) on the first-order error bounds in the stability verdict
        and the per-mode kinds.
    eigh_tol : float
        Largest backward error accepted from the Cholesky-based ``eigh`` of the
        symmetric path (its error grows like eps cond(M)); above it the same
        n-size problem is solved by QZ, which is backward stable.

    Returns
    -------
    Modes

    Raises
    ------
    ParameterError
        Bad matrices (shape, non-finite, complex), a bad tolerance, or a
        method that does not apply.
    SingularMassError
        M of a tuple is singular.
    ComputationError
        QZ failed.
    """
    t0 = time.perf_counter()
    problem = as_problem(sys)
    cluster_tol = check_tolerance("cluster_tol", cluster_tol)
    rank_tol = check_tolerance("rank_tol", rank_tol)
    structure_tol = check_tolerance("structure_tol", structure_tol)
    definiteness_tol = check_tolerance("definiteness_tol", definiteness_tol)
    eigh_tol = check_tolerance("eigh_tol", eigh_tol)
    safety = check_tolerance("safety", safety, upper=None)
    if safety < 1:
        raise ParameterError("safety", f"expected a factor >= 1, got {safety:g}")
    if not isinstance(method, str):
        raise ParameterError("method", f"expected a string, got {method!r}")
    if not isinstance(scaling, (bool, np.bool_)):
        raise ParameterError("scaling", f"expected True or False, got {scaling!r}")
    if method not in ("auto",) + PATHS:
        raise ParameterError("method", f"expected 'auto' or one of {PATHS}, got {method!r}")

    name, reason, raw = _choose(problem, method, structure_tol, eigh_tol)
    used_scaling: Scaling | None = None
    if name == "general":
        used_scaling = problem.scaling if scaling else Scaling(1.0, 1.0)
        raw = solve_general(problem, scaling=None if scaling else used_scaling)
        if not scaling:
            reason += " (unscaled, as requested)"
        if raw.note:
            reason += f"; {raw.note}"
    elif name == "symmetric":
        raw, worst = solve_symmetric(problem)
        if worst > eigh_tol:
            raw = solve_squared(problem)
            reason += (
                f"; eigh's Cholesky lost accuracy (max eta {worst:.1e} > eigh_tol {eigh_tol:g}, M ill-conditioned), "
                f"so (S - mu M) was solved by QZ (size n) instead"
            )
    elif name == "squared":
        raw = solve_squared(problem)
    raw = _order(raw)
    lam = raw.lam
    fig = pair_figures(problem, lam, raw.X, raw.Y, raw.MX, raw.CX, raw.KX)
    left = fig.left.copy()
    left_ok = fig.left_normalized.copy()
    condition = fig.condition.copy()
    bound = fig.error_bound.copy()
    notes: list[str] = []

    # multiple eigenvalues
    gamma = problem.scaling.gamma
    clusters: list[Cluster] = []
    for idx in find_clusters(lam, cluster_tol, gamma, fig.error_bound, safety):
        c = analyse_cluster(problem, lam, idx, rank_tol)
        if c.geometric == 0:
            notes.append(
                f"eigenvalues {[i + 1 for i in idx]} are within cluster_tol but L is nonsingular at their mean "
                f"(rank_tol {rank_tol:g}): treated as distinct"
            )
            continue
        if not c.consistent:
            notes.append(c.note)
        clusters.append(c)
        ii = list(c.indices)
        if c.semisimple or c.index == 1:
            Lp = 2 * c.center * problem.M + problem.C
            Y = fig.left_unit[:, ii]
            P = Y.T @ Lp @ fig.right[:, ii]
            try:
                sv = np.linalg.svd(P, compute_uv=False)
                if sv[-1] <= 1e3 * np.finfo(float).eps * sv[0] or sv[0] == 0:
                    raise np.linalg.LinAlgError
                Yn = np.linalg.solve(P, Y.T).T  # Yn^T Lp X = I
                left[:, ii] = Yn
                left_ok[ii] = True
                eta_b = np.maximum(fig.backward_error[ii], ETA_FLOOR)
                bound[ii] = eta_b * problem.weight(lam[ii]) * np.linalg.norm(Yn, axis=0)
            except np.linalg.LinAlgError:
                notes.append(f"cluster at {c.center:.6g}: left vectors could not be biorthogonalized")
        else:
            left[:, ii] = fig.left_unit[:, ii]
            left_ok[ii] = False
            condition[ii] = np.inf
            spread = float(np.max(np.abs(lam[ii] - c.center)))
            eta = max(float(np.max(fig.backward_error[ii])), ETA_FLOOR)
            bound[ii] = spread + max(abs(c.center), gamma) * eta ** (1.0 / c.index)
    multiplicity = np.ones(lam.shape[0], dtype=int)
    for c in clusters:
        multiplicity[list(c.indices)] = c.algebraic
    is_simple = all(c.semisimple for c in clusters)

    freq = np.abs(lam)
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = np.where(freq > 0, -lam.real / np.where(freq > 0, freq, 1.0), np.nan)
    r = safety * bound
    # members of a cluster are classified by its mean, the accurate value
    typical = lam.copy()
    for c in clusters:
        typical[list(c.indices)] = c.center
    kinds = []
    for i in range(lam.shape[0]):
        if abs(typical[i]) <= r[i]:
            kinds.append("rigid_body")
        elif typical[i].real > r[i]:
            kinds.append("unstable")
        elif abs(typical[i].imag) > r[i]:
            kinds.append("underdamped")
        else:
            kinds.append("overdamped")

    constants = mode_constants(lam, fig.right, *fig.products) if problem.mechanical else None
    facts = structural_facts(problem, definiteness_tol)
    K_zero = not np.any(problem.K)
    # a coordinate on which neither K nor C acts drifts exactly: x(t) = t e_j
    drift = bool(np.any(~np.any(problem.K, axis=0) & ~np.any(problem.C, axis=0)))
    stability = decide_stability(
        facts, lam, bound, clusters, K_is_zero=K_zero, exact_drift=drift, safety=safety
    )
    return Modes(
        eigenvalues=lam,
        right=fig.right,
        left=left,
        left_normalized=left_ok,
        backward_error=fig.backward_error,
        condition=condition,
        error_bound=bound,
        natural_frequency=freq,
        damping_ratio=zeta,
        kind=tuple(kinds),
        multiplicity=multiplicity,
        clusters=tuple(clusters),
        is_simple=is_simple,
        constants=constants,
        structure=facts,
        stability=stability,
        method=Method(name, reason),
        scaling=used_scaling,
        block=raw.block,
        tolerances={
            "cluster_tol": cluster_tol,
            "rank_tol": rank_tol,
            "structure_tol": structure_tol,
            "definiteness_tol": definiteness_tol,
            "safety": safety,
            "eigh_tol": eigh_tol,
        },
        system=problem.system,
        matrices=(problem.M, problem.C, problem.K),
        elapsed=time.perf_counter() - t0,
        notes=tuple(notes),
    )
