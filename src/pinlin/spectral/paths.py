"""Which solver path a modal analysis takes, and running it (theory: spectrum).

:func:`choose_path` picks the cheapest exact path the structure of the system
allows (or the one requested, refusing one that does not apply) and says why;
:func:`solve_path` runs it.  The paths are in :mod:`pinlin.spectral.structured`
and :mod:`pinlin.spectral.qep`.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..numerics.floating import EPS
from ..numerics.scaling import Scaling
from .problem import QuadraticProblem
from .qep import solve_general
from .refine import EIGH_PREDICTION_LIMIT, eigh_predicted_ok, mass_factor
from .structured import PATHS, proportionality_defect, solve_proportional, solve_squared, solve_symmetric

__all__ = ["choose_path", "solve_path", "STRUCTURE_TOL", "EIGH_TOL"]

#: Default relative defect below which damping counts as proportional
#: (commutator D M^-1 S - S M^-1 D, and the off-diagonal part left by the modes):
#: a proportional system built in floating point meets it with orders to spare.
STRUCTURE_TOL = 1e-10

#: Default largest backward error accepted from the symmetric path's eigh: a
#: backward stable solver reaches a few eps (1e-15 is 4.5 eps); more means M is
#: ill-conditioned and Newton steps follow (one step left up to 4e-15 on
#: chains of 200 links, where a second reaches 8e-17).
EIGH_TOL = 1e-15


def choose_path(problem: QuadraticProblem, method: str, structure_tol: float, eigh_tol: float):
    """(path name, reason, raw spectrum or None) for the requested method.

    The proportional path factorizes M once (:func:`pinlin.spectral.refine.mass_factor`): the
    condition estimate predicts whether eigh can meet ``eigh_tol``
    (:func:`pinlin.spectral.refine.eigh_predicted_ok`), and eigh continues from the factor.

    Raises
    ------
    ParameterError
        A structured path was requested that does not apply.
    """
    sys = problem.system
    if sys is None:
        if method not in ("auto", "general"):
            raise ParameterError(
                "method", f"the structured path {method!r} needs a LinearizedSystem; a tuple (M, C, K) is general"
            )
        return (
            "general",
            "tuple input: a general quadratic eigenproblem (real coefficients, M nonsingular, no symmetry "
            "required or used; LinearizedSystem.from_matrices checks a mechanical system), scaled companion "
            "QZ (size 2n)",
            None,
        )
    zD, zG, zN = problem.zero["D"], problem.zero["G"], problem.zero["N"]
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
        cond_M = 1.0
        if comm <= structure_tol:
            mass = mass_factor(problem.M)
            cond_M = mass.condition
            raw, defect, how = solve_proportional(
                problem, structure_tol=structure_tol, eigh_tol=eigh_tol, eigh_ok=eigh_predicted_ok(cond_M),
                factor=mass.lower,
            )
        if raw is not None:
            return (
                "proportional",
                f"G = N = 0, D M^-1 S = S M^-1 D (relative commutator {comm:.1e} <= structure_tol "
                f"{structure_tol:g}): modal decoupling by one {how} of size n"
                + (f" (eigh cannot meet eigh_tol: M ill-conditioned, cond {cond_M:.1e})" if how == "QZ" else "")
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
    nonzero = [name for name in ("D", "G") if not problem.zero[name]]
    nonzero = ["M", *nonzero, *(["S"] if np.any(sys.S) else []), *(["N"] if not zN else [])]
    return "general", f"nonzero {'+'.join(nonzero)}: no cheaper exact path; scaled companion QZ (size 2n)", None


def solve_path(problem: QuadraticProblem, name: str, reason: str, raw, scaling: bool, eigh_tol: float):
    """Run the chosen path: (raw spectrum, reason completed, scaling used or None).

    The symmetric path takes eigh with Newton refinement when eps cond(M) lets
    it reach ``eigh_tol`` (:mod:`pinlin.spectral.refine`), and otherwise -- predicted
    from LAPACK's estimate of cond(M) from one Cholesky factorization of M
    (:func:`~pinlin.spectral.refine.mass_factor`), or measured after refinement --
    QZ of the same n-size pencil; eigh continues from that factor.

    Raises
    ------
    ComputationError
        QZ failed.
    """
    used_scaling: Scaling | None = None
    if name == "general":
        used_scaling = problem.scaling if scaling else Scaling(1.0, 1.0)
        raw = solve_general(problem, scaling=None if scaling else used_scaling)
        if not scaling:
            reason += " (unscaled, as requested)"
        if raw.note:
            reason += f"; {raw.note}"
    elif name == "symmetric":
        mass = mass_factor(problem.M)
        cond_M = mass.condition
        if not eigh_predicted_ok(cond_M):
            raw = solve_squared(problem)
            reason += (
                f"; M is too ill-conditioned for eigh (eps cond(M) = {EPS * cond_M:.1e}, LAPACK's estimate, > "
                f"{EIGH_PREDICTION_LIMIT:g}), so (S - mu M) was solved by QZ (size n, right vectors only)"
            )
        else:
            raw, pencil = solve_symmetric(problem, eigh_tol, mass.lower)
            worst = float(pencil.eta.max())
            if worst > eigh_tol:
                raw = solve_squared(problem)
                reason += (
                    f"; eigh with {pencil.steps} Newton step(s) stayed above eigh_tol (max eta {worst:.1e} > "
                    f"{eigh_tol:g}), so (S - mu M) was solved by QZ (size n) instead"
                )
            elif pencil.steps:
                reason += f"; eigh refined by {pencil.steps} Newton step(s) to max eta {worst:.1e}"
    elif name == "squared":
        raw = solve_squared(problem)
    return raw, reason, used_scaling
