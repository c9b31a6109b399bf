"""``modal_analysis``: choose a solver path, solve, and attach every error figure.

See theory: spectrum, stability, conventions, :mod:`pinlin.spectral.paths` for the choice of
path and :mod:`pinlin.spectral.structured` for the paths themselves.
"""

from __future__ import annotations

import functools
import time
import warnings

import numpy as np

from ..errors import ComputationError, ParameterError
from ..numerics.checks import check_tolerance, check_uncertainty
from ..numerics.clustering import CLUSTER_TOL
from ..numerics.definiteness import DEFAULT_UNCERTAINTY
from ..numerics.rank import JORDAN_RANK_TOL
from ..numerics.threads import small_kernels
from .accuracy import PairFigures, pair_figures
from .clusters import BIORTHOGONAL_RCOND, analyse_clusters, cluster_figures
from .deferred import DeferredFigures, DeferredVerdict
from .modes import Method, Modes
from .ordering import mirrored_figures, mode_kinds, order_spectrum
from .paths import EIGH_TOL, STRUCTURE_TOL, choose_path, solve_path
from .problem import QuadraticProblem, as_problem
from .stability import STABILITY_SAFETY
from .structured import PATHS

__all__ = ["modal_analysis", "STRUCTURE_TOL", "EIGH_TOL", "BIORTHOGONAL_RCOND"]

#: Solver paths whose pencil is symmetric definite (M positive definite, K symmetric, C = 0 or
#: proportional): their multiple eigenvalues are semisimple unless a pair's two roots coincide.
SYMMETRIC_DEFINITE_PATHS = ("symmetric", "proportional")

#: The smallest positive normal double.
TINY = float(np.finfo(float).tiny)


def modal_analysis(
    sys,
    *,
    method: str = "auto",
    scaling: bool = True,
    cluster_tol: float = CLUSTER_TOL,
    rank_tol: float = JORDAN_RANK_TOL,
    structure_tol: float = STRUCTURE_TOL,
    uncertainty: float = DEFAULT_UNCERTAINTY,
    safety: float = STABILITY_SAFETY,
    eigh_tol: float = EIGH_TOL,
    definiteness_tol: float | None = None,
) -> Modes:
    """Eigenvalues, eigenvectors, error figures and a stability verdict (theory: spectrum, stability, conventions).

    Solves L(lam) x = 0, y^T L(lam) = 0 with L(lam) = lam^2 M + lam C + K for
    all 2n eigentriples by the cheapest exact path the structure allows
    (``modes.method`` says which and why), then computes for every pair its
    backward error eta and condition number kappa, groups multiple eigenvalues
    and finds their Jordan structure from block Toeplitz ranks, evaluates the
    modal constants m, d, g, k, n, and decides stability honestly.

    Parameters
    ----------
    sys : LinearizedSystem or tuple (M, C, K)
        A LinearizedSystem is mechanical: M symmetric positive definite, D, S
        symmetric, G, N skew (checked by its constructor and
        :meth:`~pinlin.LinearizedSystem.from_matrices`).  A tuple is a *general*
        quadratic eigenproblem (theory: spectrum): real square matrices of one
        size, M nonsingular and not necessarily symmetric; it always takes the
        general path and no theorem of theory: stability is applied to it.
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
        multiple eigenvalue (see :data:`~pinlin.numerics.CLUSTER_TOL`).
    rank_tol : float
        Relative singular value threshold of the Jordan rank decisions.
    structure_tol : float
        Relative defect under which damping counts as proportional.
    uncertainty : float
        Relative uncertainty of the data in [0, 1) (default 0: the matrices as
        stored, only their rounding).  The definiteness decisions hold for every
        matrix within it (:func:`pinlin.numerics.definiteness`) and the
        eigenvalue bounds of the verdict cover it: ``(eta + uncertainty) *
        sensitivity``.  The verdict then holds for every system within that
        uncertainty; ``stability.margin`` says how large a perturbation it survives.
    safety : float
        Factor (>= 1) on the first-order error bounds in the stability verdict
        and the per-mode kinds.
    eigh_tol : float
        Largest backward error accepted from the Cholesky-based ``eigh`` of the
        symmetric and proportional paths (its error grows like eps cond(M)):
        pairs above it get Newton steps (:mod:`pinlin.spectral.refine`); when
        cond(M) predicts that they cannot reach it, or they stay above it, the
        same n-size problem is solved by QZ, which is backward stable.
    definiteness_tol : float, optional
        The name of pinlin 0.2 for ``uncertainty`` (deprecated; a relative
        eigenvalue threshold then, the same role now).

    Returns
    -------
    Modes
        The structural facts, the verdict and the notes, the condition numbers,
        the modal constants and the participation are formed on first access
        (:mod:`pinlin.spectral.deferred`); everything that can raise is checked here.

    Raises
    ------
    ParameterError
        Bad matrices (shape, non-finite, complex), a bad tolerance, or a
        method that does not apply.
    SingularMassError
        M of a tuple is singular.
    ComputationError
        QZ failed, or the problem's eigenvalue scale or an eigenvalue is outside
        the double range its error figures need.

    Examples
    --------
    Two equal masses coupled by springs, lightly damped:

    >>> sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), 0.1 * np.eye(2), [[2.0, -1.0], [-1.0, 2.0]])
    >>> modes = pinlin.modal_analysis(sys)
    >>> np.round(modes.eigenvalues, 6)
    array([-0.05+0.998749j, -0.05-0.998749j, -0.05+1.731329j, -0.05-1.731329j])
    >>> modes.stability.kind
    'asymptotically_stable'
    """
    t0 = time.perf_counter()
    problem = as_problem(sys)
    if definiteness_tol is not None:
        warnings.warn(
            "modal_analysis(definiteness_tol=...) is deprecated: pass uncertainty=... (the relative data "
            "uncertainty the definiteness decisions hold against)", DeprecationWarning, stacklevel=2,
        )
        uncertainty = definiteness_tol
    with small_kernels(problem.n):  # one BLAS thread for a small problem's kernels
        tolerances = _check_options(
            method, scaling, cluster_tol=cluster_tol, rank_tol=rank_tol, structure_tol=structure_tol,
            uncertainty=uncertainty, safety=safety, eigh_tol=eigh_tol,
        )
        name, reason, raw = choose_path(problem, method, tolerances["structure_tol"], tolerances["eigh_tol"])
        raw, reason, used_scaling = solve_path(problem, name, reason, raw, scaling, tolerances["eigh_tol"])
        # pairs of a symmetric definite pencil sharing one real vector: their clusters are semisimple by theorem
        mirrored = raw.second is not None and name in SYMMETRIC_DEFINITE_PATHS
        lam, block, fig = _figures(problem, raw)
        clusters, notes, mates = analyse_clusters(problem, lam, fig, tolerances, mirrored)
        left, left_ok, model, more = cluster_figures(problem, lam, fig, clusters, mates)
        notes += more
        multiplicity = np.ones(lam.shape[0], dtype=int)
        if clusters:
            multiplicity[[i for c in clusters for i in c.indices]] = [c.algebraic for c in clusters for _ in c.indices]
        freq, zeta = _frequency_damping(lam)
        bound = model.bound(0.0)
        # bounds and backward errors are >= 0 or NaN: a sum is NaN exactly when some term is
        if np.isnan(np.sum(bound) + np.sum(fig.backward_error)):
            raise ComputationError(
                "an eigenvalue error figure is not a number: the coefficients (norms "
                f"{problem.norm_M:.3g}, {problem.norm_C:.3g}, {problem.norm_K:.3g}) span more of double range than the "
                "figures can be formed in; rescale the system (units)"
            )
        r = model.bound(tolerances["uncertainty"]) if tolerances["uncertainty"] else bound
        # (+ 0.0: a real or imaginary part that is an exact zero is exported as 0, never -0; values unchanged)
        lam, bound = _owned(lam + 0.0), _owned(bound)
        right, left, left_ok = _owned(fig.right + 0.0), _owned(left + 0.0), _owned(left_ok)
        clusters = tuple(clusters)
        return Modes(
            eigenvalues=lam,
            right=right,
            left=left,
            left_normalized=left_ok,
            backward_error=_owned(fig.backward_error),
            error_bound=bound,
            natural_frequency=_owned(freq),
            damping_ratio=_owned(zeta),
            kind=mode_kinds(lam, tolerances["safety"] * r, clusters, _undamped(problem)),
            multiplicity=_owned(multiplicity),
            clusters=clusters,
            is_simple=all(c.semisimple for c in clusters),
            method=Method(name, reason),
            scaling=used_scaling,
            block=_owned(block),
            tolerances=tolerances,
            system=problem.system,
            matrices=(problem.M, problem.C, problem.K),
            elapsed=time.perf_counter() - t0,
            deferred=DeferredFigures(
                fig.products, fig.quadratic, problem.norms, tuple(i for d in model.defective for i in d.indices)
            ),
            verdict=DeferredVerdict(
                problem, lam, model, clusters, bound, tolerances["uncertainty"], tolerances["safety"], None, tuple(notes),
                (right, left, left_ok),
            ),
        )


def _figures(problem: QuadraticProblem, raw) -> tuple[np.ndarray, np.ndarray, PairFigures]:
    """(eigenvalues in the result's order, their companion blocks, the pairs' figures), range-checked."""
    if raw.second is not None:  # pairs sharing a real vector: figures on one member of each
        lam, block, fig, weight = mirrored_figures(problem, raw)
        _check_range(problem, lam, weight)
        return lam, block, fig
    raw = order_spectrum(raw)
    _check_range(problem, raw.lam, raw.weight)
    return raw.lam, raw.block, pair_figures(problem, raw.lam, raw.P, raw.Y, raw.eta, raw.norm_x, raw.weight)


def _frequency_damping(lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """|lam| and the damping ratio -Re(lam) / |lam| (NaN exactly where lam = 0: undefined)."""
    freq = np.abs(lam)
    # (0.0 - Re: an undamped mode's ratio is 0, never -0.)
    if np.count_nonzero(freq) == freq.size:
        return freq, (0.0 - lam.real) / freq
    with np.errstate(divide="ignore", invalid="ignore"):
        return freq, (0.0 - lam.real) / freq


def _undamped(problem: QuadraticProblem) -> bool:
    """D = 0 and (G = 0 or N = 0) exactly (for a tuple: C = 0): the spectrum is symmetric in the imaginary axis."""
    sys = problem.system
    if sys is None:
        return not np.count_nonzero(problem.C)
    zero = problem.zero  # which of D, G, N are exactly zero (decided once per problem)
    return zero["D"] and (zero["G"] or zero["N"])


def _owned(a: np.ndarray) -> np.ndarray:
    """``a`` (a fresh array of this call) made read-only in place: Modes keeps it without a copy."""
    if not (a.flags.owndata or a.base is None):
        a = a.copy()
    a.flags.writeable = False
    return a


def _check_range(problem: QuadraticProblem, lam: np.ndarray, weight: np.ndarray | None = None) -> None:
    """Every eigenvalue finite, with |lam|^2 ||M|| + |lam| ||C|| + ||K|| representable (theory: spectrum's weight).

    ``weight``: that weight when the solver path formed it already.

    Raises
    ------
    ComputationError
        Otherwise: a heavily damped problem of extreme scales has eigenvalues
        beyond the range in which its residuals and error figures exist.
    """
    if weight is None:
        with np.errstate(over="ignore", invalid="ignore"):
            weight = problem.weight(lam)
    # w(lam) is finite only where lam is (a NaN or an infinite lam gives NaN or inf)
    if np.count_nonzero(np.isfinite(weight)) == weight.size:
        return
    bad = ~(np.isfinite(lam) & np.isfinite(weight))
    k = int(np.flatnonzero(bad)[0])
    raise ComputationError(
        f"the eigenvalue {complex(lam[k]):.3g} is beyond double range for its error figures "
        f"(|lam|^2 ||M|| + |lam| ||C|| + ||K|| overflows; norms {problem.norm_M:.3g}, {problem.norm_C:.3g}, "
        f"{problem.norm_K:.3g}); rescale the system (units)"
    )


def _check_options(method, scaling, **tolerances) -> dict[str, float]:
    """The validated tolerances of :func:`modal_analysis` (method and scaling checked too), a fresh dict.

    Options of plain types (str, bool, float) are validated once per distinct value
    (:func:`_checked_options`); others (numpy scalars, anything unhashable) every time.
    """
    key = (method, scaling, *sorted(tolerances.items()))
    if all(type(v) in (str, bool, float) for v in (method, scaling, *tolerances.values())):
        return dict(_checked_options(key))
    return _validated_options(method, scaling, **tolerances)


@functools.lru_cache(maxsize=16)
def _checked_options(key: tuple) -> tuple[tuple[str, float], ...]:
    """:func:`_validated_options` of a hashable key (method, scaling, *sorted tolerance items), as items."""
    method, scaling, *items = key
    return tuple(_validated_options(method, scaling, **dict(items)).items())


def _validated_options(method, scaling, **tolerances) -> dict[str, float]:
    """The validated tolerances of :func:`modal_analysis` (method and scaling checked too).

    Raises
    ------
    ParameterError
        A tolerance not in (0, 1), an uncertainty not in [0, 1), a safety factor below 1, an
        unknown method, a non-bool scaling.
    """
    out = {
        name: check_tolerance(tolerances[name], name, upper=1.0)
        for name in ("cluster_tol", "rank_tol", "structure_tol")
    }
    out["uncertainty"] = check_uncertainty(tolerances["uncertainty"])
    out["safety"] = check_tolerance(tolerances["safety"], "safety")
    if out["safety"] < 1:
        raise ParameterError("safety", f"expected a factor >= 1, got {out['safety']:g}")
    out["eigh_tol"] = check_tolerance(tolerances["eigh_tol"], "eigh_tol", upper=1.0)
    if not isinstance(method, str):
        raise ParameterError("method", f"expected a string, got {method!r}")
    if not isinstance(scaling, (bool, np.bool_)):
        raise ParameterError("scaling", f"expected True or False, got {scaling!r}")
    if method not in ("auto",) + PATHS:
        raise ParameterError("method", f"expected 'auto' or one of {PATHS}, got {method!r}")
    return out
