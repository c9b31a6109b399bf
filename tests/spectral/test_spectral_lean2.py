"""M factorized once on the symmetric paths, and leaner decisions.

- :func:`pinlin.spectral.refine.mass_factor`: the Cholesky factor of M and LAPACK's
  condition estimate (exact for diagonal M, inf when M is not positive definite);
- eigh continued from that factor (dsygst, dsyevd, dtrsm) gives LAPACK's dsygvd
  results bit for bit, so the symmetric path's figures did not change;
- the verdict's decision about M is the one :func:`pinlin.numerics.definiteness`
  makes (the analysis no longer makes it for the path choice);
- the fast inertia counts of the definiteness decision and the unchecked
  determinant decision agree with hand-derived cases and the checked functions;
- the isolation test of the reflection-symmetry rule, formed in blocks of
  eigenvalues, is its one-eigenvalue-at-a-time definition.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.linalg.lapack import dsygvd

import pinlin
from pinlin.numerics.definiteness import symmetric_definiteness
from pinlin.numerics.determinant import nonsingularity, validated_nonsingularity
from pinlin.spectral.refine import mass_factor, refined_eigh
from pinlin.spectral.stability.rules import ISOLATION_FACTOR, Evidence
from spectral_cases import chain

EPS = np.finfo(float).eps


def test_mass_factor_of_a_diagonal_matrix_is_exact():
    """diag(4, 1e-6): L = diag(2, 1e-3), cond_1 = 4 / 1e-6 = 4e6 (the estimator is exact on diagonals)."""
    M = np.diag([4.0, 1e-6])
    f = mass_factor(M)
    assert np.tril(f.lower).tolist() == [[2.0, 0.0], [0.0, 1e-3]]
    assert f.condition == pytest.approx(4e6, rel=4 * EPS)


def test_mass_factor_of_a_dense_matrix_bounds_cond_2():
    """cond_2 <= cond_1 <= n cond_2 for symmetric M; LAPACK's estimate is a lower bound on cond_1."""
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.standard_normal((6, 6)))
    w = np.array([1e-3, 0.1, 1.0, 2.0, 10.0, 1e3])
    M = (Q * w) @ Q.T
    M = 0.5 * (M + M.T)
    f = mass_factor(M)
    L = np.tril(f.lower)
    np.testing.assert_allclose(L @ L.T, M, rtol=0, atol=50 * EPS * 1e3)
    cond_1 = np.abs(M).sum(axis=0).max() * np.abs(np.linalg.inv(M)).sum(axis=0).max()
    assert f.condition <= cond_1 * (1 + 1e-10)
    assert f.condition >= 1e6 / 3  # within LAPACK's usual factor 3 of cond_1 >= cond_2 = 1e6


def test_mass_factor_refuses_an_indefinite_matrix():
    f = mass_factor(np.array([[1.0, 2.0], [2.0, 1.0]]))  # eigenvalues 3 and -1
    assert f.lower is None and f.condition == np.inf


@pytest.mark.parametrize("n", [3, 20, 60])
def test_eigh_from_the_factor_is_dsygvd_bit_for_bit(n):
    sys = chain(n, 10.0 ** np.linspace(-4, 4, n))
    nS, nM = float(np.linalg.norm(sys.S)), float(np.linalg.norm(sys.M))
    w, X, info = dsygvd(sys.S, sys.M, itype=1, jobz="V", uplo="L")
    assert info == 0
    plain = refined_eigh(sys.S, sys.M, nS, nM, tol=1e-15, max_steps=0)
    shared = refined_eigh(sys.S, sys.M, nS, nM, tol=1e-15, max_steps=0, factor=mass_factor(sys.M).lower)
    for got in (plain, shared):
        assert np.array_equal(got.w, w) and np.array_equal(got.X, X)
    refined = refined_eigh(sys.S, sys.M, nS, nM, tol=1e-15, factor=mass_factor(sys.M).lower)
    assert refined.eta.max() <= 1e-15


def test_symmetric_path_leaves_the_mass_decision_to_the_verdict():
    sys = chain(12, 10.0 ** np.linspace(-3, 3, 12))
    m = pinlin.modal_analysis(sys)
    assert m.method == "symmetric" and m.verdict.mass is None
    on_M = pinlin.numerics.definiteness(sys.M)
    assert m.structure.definiteness_M.to_dict() == on_M.to_dict()
    assert m.structure.definiteness_M.kind == "positive_definite"
    assert m.error <= 1e-15


@pytest.mark.parametrize(
    "A, kind, inertia",
    [
        (np.diag([1.0, 2.0, 3.0]), "positive_definite", (0, 0, 3)),
        (-np.diag([1.0, 2.0, 3.0]), "negative_definite", (3, 0, 0)),
        (np.diag([-1.0, 0.0, 2.0]), "indefinite", (1, 1, 1)),
        (np.diag([0.0, 1.0, 5.0]), "positive_semidefinite", (0, 1, 2)),
        (np.diag([-4.0, -1.0, 0.0]), "negative_semidefinite", (2, 1, 0)),
    ],
)
def test_inertia_counts_by_hand(A, kind, inertia):
    d = symmetric_definiteness(A, 0.0)
    assert d.kind == kind and (d.negative, d.zero, d.positive) == inertia
    assert pinlin.numerics.definiteness(A).kind == kind


def test_inertia_counts_follow_the_uncertainty():
    """diag(1, 10): beyond the threshold at u = 0; u = 0.5 puts 1 within 0.5 * 10 + rho of zero."""
    d = symmetric_definiteness(np.diag([1.0, 10.0]), 0.0)
    assert (d.negative, d.zero, d.positive) == (0, 0, 2)
    wide = d.at(0.5)
    assert (wide.negative, wide.zero, wide.positive) == (0, 1, 1) and wide.kind == "positive_semidefinite"
    neg = symmetric_definiteness(-np.diag([1.0, 10.0]), 0.0).at(0.5)
    assert (neg.negative, neg.zero, neg.positive) == (1, 1, 0) and neg.kind == "negative_semidefinite"


def test_a_semidefinite_block_with_zero_rows_is_certainly_psd():
    """D with a joint without damper: the zero row is exact, the rest positive definite."""
    D = np.array([[2.0, 0.0, 1.0], [0.0, 0.0, 0.0], [1.0, 0.0, 2.0]])
    d = symmetric_definiteness(D, 0.0)
    assert d.kind == "positive_semidefinite" and d.certainly_psd
    assert d._block.kind == "positive_definite" and d._block.min_eigenvalue == pytest.approx(1.0, abs=4 * EPS)


def test_unchecked_determinant_decision_agrees_with_the_checked_one():
    swap = np.array([[0.0, 1.0], [1.0, 0.0]])  # det = -1, singular values 1, 1
    got = validated_nonsingularity(swap, 0.0)
    assert got.sign == -1 and got.margin == pytest.approx(1 - 2 * EPS, abs=EPS)
    rng = np.random.default_rng(7)
    for _ in range(20):
        A = rng.standard_normal((5, 5))
        assert validated_nonsingularity(A, 0.1) == nonsingularity(A, 0.1)
    assert validated_nonsingularity(np.zeros((3, 3)), 0.0).sign == 0
    with pytest.raises(pinlin.ParameterError, match="non-finite"):
        nonsingularity(np.array([[np.nan, 0.0], [0.0, 1.0]]))


def _isolated_by_loop(ev, idx):
    """The isolation test of the reflection-symmetry rule, one eigenvalue at a time (its definition)."""
    out = []
    for i in idx:
        others = [j for j in range(ev.lam.shape[0]) if j != i]
        out.append(not ev.clustered[i] and all(
            abs(ev.lam[j] - ev.lam[i]) > ISOLATION_FACTOR * ev.r[i] + ev.r[j] for j in others))
    return np.array(out, dtype=bool)


@pytest.mark.parametrize("seed", range(5))
def test_isolation_test_is_the_definition(seed):
    """Random spectra with near neighbours, a cluster, and more eigenvalues than one block of rows."""
    rng = np.random.default_rng(seed)
    k = 300 if seed == 4 else 12
    lam = rng.standard_normal(k) * 1e-3 + 1j * rng.uniform(0, 5, k)
    lam[1] = lam[0] + 1e-5  # closer than 3 r_0 + r_1 >= 4e-5 to lam_0
    r = rng.uniform(1e-5, 1e-4, k)
    m = pinlin.modal_analysis(chain(3, np.ones(3)))
    ev = Evidence.of(m.structure, lam, r, (), K_is_zero=False, exact_drift=False, safety=1.0)
    clustered = np.zeros(k, dtype=bool)
    clustered[5] = True
    ev = dataclasses.replace(ev, clustered=clustered)
    idx = np.arange(k)[rng.permutation(k)][: k - 2]
    assert np.array_equal(ev.isolated(idx), _isolated_by_loop(ev, idx))
    assert not ev.isolated(np.array([0, 1, 5])).any()


def _gyroscopic_blocks(blocks: int) -> pinlin.LinearizedSystem:
    """Uncoupled 2-DOF rotors, M = I, S = -diag(s1, s2) < 0 and G = [[0, g], [-g, 0]] with g > sqrt(s1) + sqrt(s2):
    det L = lam^4 + (g^2 + s1 + s2) lam^2 + s1 s2 has two negative roots in lam^2, so all eigenvalues are
    imaginary and simple (gyroscopic stabilization), decided by reflection symmetry (D = N = 0)."""
    n = 2 * blocks
    G, S = np.zeros((n, n)), np.zeros((n, n))
    for b in range(blocks):
        i = 2 * b
        G[i, i + 1], G[i + 1, i] = 3.0 + 0.37 * b, -(3.0 + 0.37 * b)
        S[i, i], S[i + 1, i + 1] = -1.0 - 0.1 * b, -1.0 - 0.05 * b
    return pinlin.LinearizedSystem(M=np.eye(n), D=np.zeros((n, n)), G=G, S=S, N=np.zeros((n, n)))


@pytest.mark.parametrize("blocks", [3, 150])
def test_gyroscopic_stabilization_is_marginally_stable_by_reflection_symmetry(blocks):
    m = pinlin.modal_analysis(_gyroscopic_blocks(blocks))
    assert np.abs(m.eigenvalues.real).max() <= m.error_bound.max()
    assert m.stability.kind == "marginally_stable" and m.stability.theorem == "reflection symmetry"
    assert f"each of the {4 * blocks} eigenvalue(s)" in m.stability.reason


def test_instability_kind_picks_the_rightmost_certainly_real_eigenvalue():
    """Real eigenvalues 2.0 and 2.0 + 1e-6 are not certainly real (within r_i + r_j = 2e-6 of each other): the
    rightmost certainly real one, 1.5, decides "divergence"; without it a complex pair decides "flutter"."""
    m = pinlin.modal_analysis(chain(3, np.ones(3)))
    lam = np.array([2.0, 2.0 + 1e-6, 1.5, 0.5 + 3j, 0.5 - 3j, -1.0], dtype=complex)
    ev = Evidence.of(m.structure, lam, np.full(6, 1e-6), (), K_is_zero=False, exact_drift=False, safety=1.0)
    assert [ev.certainly_real(i) for i in range(6)] == [False, False, True, False, False, True]
    assert ev.instability(np.array([0, 1, 2, 3, 4])) == ("divergence", 2, "real")
    assert ev.instability(np.array([0, 1, 3, 4]))[:2] == ("flutter", 3)
