"""Multiple eigenvalues: clusters, block Toeplitz ranks, Jordan chains (theory: spectrum).

Hand-derived cases: the critically damped oscillator (lam0 = -omega, L and L'
both vanish there: one chain of length 2); a 2-DOF example with a nontrivial
chain vector; the zero-gravity pendulum chain without springs (L = lam^2 M:
n chains of length 2 at 0); two identical uncoupled oscillators (semisimple).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin import LinearizedSystem
from pinlin.errors import NotAnEigenvalueError, ParameterError
from spectral_cases import chain


def chain_equations(M, C, K, lam0, xs):
    """Residuals of sum_j L^(j)(lam0)/j! x_{i-j} = 0, recomputed here."""
    L = [lam0**2 * M + lam0 * C + K, 2 * lam0 * M + C, M]
    out = []
    for i in range(len(xs)):
        r = sum(L[j] @ xs[i - j] for j in range(min(i, 2) + 1))
        out.append(np.linalg.norm(r))
    return np.array(out)


@pytest.mark.parametrize("method", ["auto", "general"])
def test_critically_damped_oscillator_has_one_chain_of_length_two(method):
    omega = 3.0
    sys = LinearizedSystem.from_matrices([[1.0]], [[2 * omega]], [[omega**2]])
    m = pinlin.modal_analysis(sys, method=method)
    assert len(m.clusters) == 1
    c = m.clusters[0]
    assert c.algebraic == 2 and c.geometric == 1 and c.partial == (2,)
    assert_allclose(c.center, -omega, rtol=1e-14, atol=0)
    assert not m.is_simple
    assert not np.any(m.left_normalized)
    assert np.all(np.isinf(m.condition))
    assert m.kind == ("overdamped", "overdamped")
    assert m.stability.kind == "asymptotically_stable"
    chains = pinlin.jordan_chains(sys, -omega)
    assert chains.partial == (2,) and len(chains) == 1
    x0, x1 = chains[0]
    assert_allclose(abs(x0[0]), 1.0, rtol=1e-15, atol=0)
    assert_allclose(chain_equations(sys.M, sys.C, sys.K, -omega, [x0, x1]), [0, 0], rtol=0, atol=1e-13)
    assert chains.max_residual < 1e-15


def test_hand_derived_chain_with_nontrivial_second_vector():
    # L(lam) = [[lam^2, 0], [lam, lam^2 + 1]]: det = lam^2 (lam^2 + 1); at 0: x0 = e1, and
    # L(0) x1 = -L'(0) x0 = -(0, 1) gives x1 = (a, -1) x0[0]; no chain of length 3 since
    # L(0) x2 + L'(0) x1 + M x0 has first component x0[0] != 0.
    M, C, K = np.eye(2), np.array([[0.0, 0.0], [1.0, 0.0]]), np.diag([0.0, 1.0])
    chains = pinlin.jordan_chains((M, C, K), 0.0)
    assert chains.partial == (2,)
    x0, x1 = chains[0]
    assert_allclose(abs(x0[0]), 1.0, rtol=1e-14, atol=0)
    assert_allclose(x0[1], 0.0, rtol=0, atol=1e-14)
    assert_allclose(x1[1], -x0[0], rtol=1e-13, atol=0)
    assert_allclose(chain_equations(M, C, K, 0.0, [x0, x1]), [0, 0], rtol=0, atol=1e-14)
    m = pinlin.modal_analysis((M, C, K))
    (c,) = [c for c in m.clusters if abs(c.center) < 1e-6]
    assert c.partial == (2,)
    assert not m.is_simple


def test_zero_gravity_chain_without_springs_has_rigid_body_chains():
    sys = chain(3, gravity=(0, 0, 0))
    assert sys.nonzero == ("M",)
    m = pinlin.modal_analysis(sys)
    assert_allclose(m.eigenvalues, np.zeros(6), rtol=0, atol=0)
    (c,) = m.clusters
    assert c.partial == (2, 2, 2) and c.geometric == 3 and c.algebraic == 6
    assert not m.is_simple
    assert set(m.kind) == {"rigid_body"}
    assert m.stability.kind == "divergence"
    assert "Jordan" in m.stability.reason and "rigid-body drift" in m.stability.reason
    chains = pinlin.jordan_chains(sys, 0.0)
    assert chains.partial == (2, 2, 2)
    heads = np.column_stack([c[0] for c in chains])
    assert_allclose(heads.conj().T @ heads, np.eye(3), rtol=0, atol=1e-14)
    for x0, x1 in chains:
        assert_allclose(chain_equations(sys.M, sys.C, sys.K, 0.0, [x0, x1]), [0, 0], rtol=0, atol=1e-14)
    # the general path sees the same structure
    g = pinlin.modal_analysis(sys, method="general")
    assert [c.partial for c in g.clusters] == [(2, 2, 2)]


def test_identical_uncoupled_oscillators_are_semisimple():
    sys = LinearizedSystem.from_matrices(np.diag([2.0, 2.0]), None, np.diag([8.0, 8.0]))
    for method in ("auto", "general"):
        m = pinlin.modal_analysis(sys, method=method)
        assert m.is_simple
        assert sorted(c.partial for c in m.clusters) == [(1, 1), (1, 1)]
        assert_allclose(np.sort(m.eigenvalues.imag), [-2, -2, 2, 2], rtol=1e-14, atol=0)
        assert np.all(m.left_normalized)
        for c in m.clusters:
            ii = list(c.indices)
            Lp = 2 * c.center * sys.M + sys.C
            assert_allclose(m.left[:, ii].T @ Lp @ m.right[:, ii], np.eye(2), rtol=0, atol=1e-13)
        assert m.stability.kind == "marginally_stable"
    chains = pinlin.jordan_chains(sys, 2j)
    assert chains.partial == (1, 1)


def test_cluster_tolerance_is_adjustable():
    # general QZ splits the critically damped double root by about sqrt(eps)
    sys = LinearizedSystem.from_matrices([[1.0]], [[2.0]], [[1.0]])
    m = pinlin.modal_analysis(sys, method="general")
    spread = abs(m.eigenvalues[0] - m.eigenvalues[1])
    assert m.clusters and not m.is_simple
    if spread > 0:  # with cluster_tol below the split, the pair is taken as two simple roots
        tight = pinlin.modal_analysis(sys, method="general", cluster_tol=spread / 10)
        assert tight.clusters == () and tight.is_simple
        assert tight.tolerances["cluster_tol"] == spread / 10


def test_close_but_distinct_eigenvalues_are_not_clustered():
    eps = 1e-7  # relative gap below cluster_tol, but far above the error bounds
    sys = LinearizedSystem.from_matrices(np.eye(2), None, np.diag([4.0, 4.0 * (1 + eps) ** 2]))
    m = pinlin.modal_analysis(sys)
    assert m.clusters == ()
    assert m.is_simple
    assert_allclose(np.sort(m.natural_frequency), [2, 2, 2 * (1 + eps), 2 * (1 + eps)], rtol=1e-15, atol=0)


def test_block_toeplitz_kernel_dimensions():
    sys = chain(2, gravity=(0, 0, 0))
    chains = pinlin.jordan_chains(sys, 0.0)
    # dim ker T_k = sum_i min(m_i, k) with m = (2, 2): 2, 4, 4
    assert chains.kernel_dims == (2, 4, 4)


def test_jordan_chains_at_a_regular_point_are_refused_with_the_distance():
    """Not an eigenvalue is an error (as for residues), naming the nearest eigenvalue."""
    sys = LinearizedSystem.from_matrices([[1.0]], [[0.0]], [[4.0]])  # lam = +-2i; gamma = 2
    with pytest.raises(NotAnEigenvalueError, match=r"lam0 = 1\+0j is not an eigenvalue: .* nearest eigenvalue is "
                       r"0\+2j, at distance 2\.236e\+00") as info:
        pinlin.jordan_chains(sys, 1.0)
    assert info.value.lam == 1.0 and info.value.distance == pytest.approx(np.sqrt(5) / 2, rel=1e-14)
    assert isinstance(info.value, pinlin.PinlinError) and isinstance(info.value, ValueError)
    # close, but off by more than rounding: still refused, with the small distance
    with pytest.raises(NotAnEigenvalueError, match=r"at distance 1\.000e-06"):
        pinlin.jordan_chains((np.eye(1), np.zeros((1, 1)), 4 * np.eye(1)), 2j + 1e-6)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"lam0": float("nan")}, "lam0: expected a finite number"),
        ({"lam0": "one"}, "lam0: expected a number"),
        ({"lam0": 0.0, "rank_tol": 0.0}, "rank_tol: expected a finite positive number"),
        ({"lam0": 0.0, "rank_tol": 2.0}, "rank_tol: expected a number below 1"),
        ({"lam0": 0.0, "max_length": 0}, "max_length: expected a positive integer"),
        ({"lam0": 0.0, "max_length": 1.5}, "max_length: expected a positive integer"),
    ],
)
def test_jordan_chains_bad_input(kwargs, match):
    sys = LinearizedSystem.from_matrices([[1.0]], [[2.0]], [[1.0]])
    with pytest.raises(ParameterError, match=match):
        pinlin.jordan_chains(sys, **kwargs)
