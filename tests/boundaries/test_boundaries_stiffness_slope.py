"""The divergence tracker's slope when M depends on the parameter (theory: boundaries).

For the largest real eigenvalue mu of the pencil (-K, M), (K + mu M) x = 0 gives
d mu / dp = -y^T (dK + mu dM) x / (y^T M x).  With M = diag(exp(3p), 1), K = diag(1 - p, 2) (divergence at
p = 1, where mu = -(1 - p) exp(-3p) crosses zero) the correct slope takes Newton to the root in 13 modal
analyses from the bracket (0, 3); a slope with the sign of the mu dM term flipped still converges (the
bracket safeguards it) but needs 56.  The count is asserted: a wrong slope costs, it does not err.
"""

import numpy as np

import pinlin


def _family(p):
    M = np.diag([np.exp(3.0 * p), 1.0])
    K = np.diag([1.0 - p, 2.0])
    return pinlin.LinearizedSystem.from_matrices(M, 0.1 * np.eye(2), K)


def test_divergence_with_a_parameter_dependent_mass_converges_fast():
    r = pinlin.critical_parameter(_family, (0.0, 3.0))
    assert r.kind == "divergence" and r.mechanism == "crossing"
    assert abs(r.value - 1.0) <= r.error_bound
    assert r.evaluations <= 15, r.steps
