"""Numerics shared by the analyses, each written once.

- :mod:`.checks` -- input checks: ``check_tolerance(value, label, upper=None)``,
  ``check_uncertainty``, ``check_integer``, ``check_radii``, ``complex_scalar``, ``complex_points``,
  ``dof_indices``;
- :mod:`.arrays` -- ``readonly`` (read-only copies), ``check_times``, ``check_vector``, ``check_samples``:
  time grids, coordinate vectors and sampled signals;
- :mod:`.floating` -- ``EPS``, ``LOG_MAX``, ``LOG_TINY`` and ``checked_exp`` (back from logarithms);
- :mod:`.stacks` -- ``chunks``: stacks of (n, n) matrices in pieces of bounded memory;
- :mod:`.norms` -- ``fro`` (the fast Frobenius norm), ``frobenius`` and ``column_norms`` (without over- or
  underflow), ``coefficient_norms``;
- :mod:`.scaling` -- Fan-Lin-Van Dooren ``Scaling`` (gamma, delta, in logarithms), ``natural_scale``,
  ``eigenvalue_bounds``;
- :mod:`.accuracy` -- backward error eta, condition number kappa, the Jordan-chain residual;
- :mod:`.clustering` -- ``find_clusters``: eigenvalues that rounding cannot tell apart;
- :mod:`.definiteness` -- ``definiteness`` (one decision for modes, stability and the report,
  against the rounding bound c n eps ||A|| and a data uncertainty; Cholesky certificate);
- :mod:`.determinant` -- ``nonsingularity`` and ``det_sign``, decided the same way;
- :mod:`.rank` -- the two rank tolerances (Jordan structure, adjugate rank one) and rank helpers;
- :mod:`.threads` -- ``small_kernels``: one BLAS thread for the dense kernels of a small problem;

"""

from .accuracy import (
    ETA_FLOOR,
    backward_error,
    backward_errors,
    chain_residuals,
    condition_number,
    condition_numbers,
    eigen_weight,
    homogeneous,
)
from .arrays import check_samples, check_times, check_vector
from .checks import (
    check_integer,
    check_radii,
    check_tolerance,
    check_uncertainty,
    complex_points,
    complex_scalar,
    dof_indices,
)
from .clustering import CLUSTER_BOUND_FACTOR, CLUSTER_TOL, find_clusters
from .definiteness import (
    DEFAULT_UNCERTAINTY,
    DEFINITENESS_KINDS,
    DEFINITENESS_TOL,
    EIGENVALUE_ROUNDING,
    Definiteness,
    cholesky_lower_bound,
    definiteness,
    rounding_bound,
)
from .determinant import Nonsingularity, det_sign, nonsingularity
from .floating import EPS, LOG_MAX, LOG_TINY, checked_exp
from .norms import coefficient_norms, column_norms, fro, frobenius
from .rank import ADJUGATE_RANK_TOL, JORDAN_RANK_TOL, kernel_dimension, null_basis
from .scaling import (
    INVERTIBLE_K_FACTOR,
    RANGE_MARGIN,
    Scaling,
    eigenvalue_bounds,
    fan_lin_van_dooren,
    natural_scale,
    system_scaling,
)
from .stacks import CHUNK_BYTES, chunks

__all__ = [
    "check_times",
    "check_vector",
    "check_samples",
    # checks
    "check_tolerance",
    "check_uncertainty",
    "check_integer",
    "check_radii",
    "complex_scalar",
    "complex_points",
    "dof_indices",
    # floating point
    "EPS",
    "LOG_MAX",
    "LOG_TINY",
    "checked_exp",
    "CHUNK_BYTES",
    "chunks",
    # scaling
    "Scaling",
    "coefficient_norms",
    "column_norms",
    "fro",
    "frobenius",
    "fan_lin_van_dooren",
    "system_scaling",
    "natural_scale",
    "eigenvalue_bounds",
    "INVERTIBLE_K_FACTOR",
    "RANGE_MARGIN",
    # accuracy
    "ETA_FLOOR",
    "homogeneous",
    "eigen_weight",
    "backward_errors",
    "condition_numbers",
    "backward_error",
    "condition_number",
    "chain_residuals",
    # clusters, definiteness, rank
    "CLUSTER_TOL",
    "CLUSTER_BOUND_FACTOR",
    "find_clusters",
    "EIGENVALUE_ROUNDING",
    "DEFAULT_UNCERTAINTY",
    "DEFINITENESS_TOL",
    "DEFINITENESS_KINDS",
    "Definiteness",
    "definiteness",
    "rounding_bound",
    "cholesky_lower_bound",
    "Nonsingularity",
    "nonsingularity",
    "det_sign",
    "JORDAN_RANK_TOL",
    "ADJUGATE_RANK_TOL",
    "kernel_dimension",
    "null_basis",
]
