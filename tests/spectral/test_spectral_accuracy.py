"""Backward errors and normalizations on hard cases (theory: spectrum, error figures).

Backward errors are recomputed here from their definition (Frobenius norms),
never read from the result alone.  Cases: a 200-link hanging chain with joint
stiffnesses spread over 10 decades; a cantilever of 40 Hermite beam elements
with a single dashpot; a gyroscopic and a circulatory case.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

import pinlin
from pinlin import FollowerWrench, JointSpring, Scene
from spectral_cases import cantilever, chain, eta_reference


def left_residual(M, C, K, lam, Y):
    R = Y.T @ M * (lam**2)[:, None] + (Y.T @ C) * lam[:, None] + Y.T @ K
    w = np.abs(lam) ** 2 * np.linalg.norm(M) + np.abs(lam) * np.linalg.norm(C) + np.linalg.norm(K)
    return np.linalg.norm(R, axis=1) / (w * np.linalg.norm(Y, axis=0))


def check_pairs(m, tol=1e-13):
    M, C, K = m.matrices
    lam = m.eigenvalues
    eta = eta_reference(M, C, K, lam, m.right)
    assert np.max(eta) < tol
    assert_allclose(m.backward_error, eta, rtol=0.1, atol=4 * np.finfo(float).eps)  # residuals round at eps
    assert_allclose(np.linalg.norm(m.right, axis=0), 1.0, rtol=1e-14, atol=0)
    ok = m.left_normalized
    norm = np.einsum("ij,ij->j", m.left, (2 * M) @ m.right * lam + C @ m.right)
    # y^T L' x = 1 up to the rounding of the product: eps (2|lam| ||M|| + ||C||) ||y|| ||x||
    scale = (2 * np.abs(lam) * np.linalg.norm(M, 2) + np.linalg.norm(C, 2)) * np.linalg.norm(m.left, axis=0)
    assert np.all(np.abs(norm - 1)[ok] <= 100 * np.finfo(float).eps * scale[ok])
    assert np.max(left_residual(M, C, K, lam, m.left)) < 1e3 * tol
    return eta


@pytest.fixture(scope="module")
def long_chain():
    ks = 10.0 ** np.linspace(-5, 5, 200)
    return chain(200, ks)


def test_symmetric_path_predicts_when_eigh_cannot_meet_its_tolerance():
    """A chain with a near-massless link: eps cond(M) beyond EIGH_PREDICTION_LIMIT, so QZ is taken
    directly (no eigh run and discarded); the pairs are backward stable all the same."""
    from pinlin.spectral.refine import EIGH_PREDICTION_LIMIT

    masses = np.ones(6)
    masses[-1] = 1e-12
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(6, length=1.0, mass=masses))
    sys = pinlin.linearize(Scene(robot, [JointSpring(f"joint{i + 1}", 1.0) for i in range(6)]), robot.neutral())
    w = np.linalg.eigvalsh(sys.M)
    assert np.finfo(float).eps * w[-1] / w[0] > EIGH_PREDICTION_LIMIT
    m = pinlin.modal_analysis(sys)
    assert m.method == "symmetric" and "too ill-conditioned for eigh" in m.method.reason
    check_pairs(m, tol=1e-14)


def test_long_stiff_chain_general_path(long_chain):
    m = pinlin.modal_analysis(long_chain, method="general")
    assert m.method == "general" and m.scaling.gamma > 0
    check_pairs(m)
    assert m.stability.kind == "marginally_stable"


def test_long_stiff_chain_automatic_path(long_chain):
    m = pinlin.modal_analysis(long_chain)
    assert m.method == "symmetric"
    check_pairs(m, tol=1e-15)
    # eigh's Cholesky of this ill-conditioned M (cond ~ 6e9) loses digits; Newton steps restore them
    # (backward errors at rounding level, recomputed above), and the path says so
    assert "Newton" in m.method.reason and "QZ" not in m.method.reason
    loose = pinlin.modal_analysis(long_chain, eigh_tol=0.5)
    assert "QZ" not in loose.method.reason and "Newton" not in loose.method.reason
    assert loose.max_backward_error > 1e-13  # what plain eigh would have delivered
    # eigh's eigenvalues are off by up to 2e-6 here, but within their own (honest) error bounds
    assert np.all(np.abs(loose.eigenvalues - m.eigenvalues) <= loose.error_bound)
    assert np.max(loose.error_bound / m.error_bound) > 1e4


@pytest.fixture(scope="module")
def damped_beam():
    return cantilever(ne=40, c=50.0, at=25)


def test_damped_beam_scaled_beats_unscaled(damped_beam):
    scaled = pinlin.modal_analysis(damped_beam)
    assert scaled.method == "general"  # a single dashpot is not proportional damping
    eta_s = check_pairs(scaled)
    unscaled = pinlin.modal_analysis(damped_beam, scaling=False)
    M, C, K = unscaled.matrices
    eta_u = eta_reference(M, C, K, unscaled.eigenvalues, unscaled.right)
    assert np.max(eta_u) > 1e3 * np.max(eta_s)
    assert np.max(eta_u) > 1e-13
    assert unscaled.scaling.gamma == 1.0 and unscaled.scaling.delta == 1.0
    assert_allclose(
        np.sort_complex(unscaled.eigenvalues), np.sort_complex(scaled.eigenvalues), rtol=1e-6, atol=0
    )


def test_gyroscopic_case():
    rng = np.random.default_rng(7)
    n = 30
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    M = Q @ np.diag(10.0 ** rng.uniform(-3, 1, n)) @ Q.T
    A = rng.standard_normal((n, n))
    G = 1e2 * (A - A.T)
    Q2, _ = np.linalg.qr(rng.standard_normal((n, n)))
    S = Q2 @ np.diag(10.0 ** rng.uniform(0, 6, n)) @ Q2.T
    Z = np.zeros((n, n))
    sys = pinlin.LinearizedSystem(M, Z, G, S, Z)
    m = pinlin.modal_analysis(sys)
    assert m.method == "general"
    check_pairs(m)
    # N = 0, D = 0, S > 0: Lagrange-Dirichlet plus the Hamiltonian symmetry
    assert m.stability.kind == "marginally_stable"
    assert np.max(np.abs(m.eigenvalues.real)) < 1e-9 * np.max(np.abs(m.eigenvalues))


@pytest.fixture(scope="module")
def follower_chain():
    n = 12
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(n, length=1.0, mass=1.0))
    ks = 10.0 ** np.linspace(-2, 3, n)
    el = [JointSpring(f"joint{i + 1}", k) for i, k in enumerate(ks)] + [FollowerWrench("tip", force=(0, 0, 2.0))]
    scene = Scene(robot, el, gravity=(0, 0, -9.81))
    return pinlin.linearize(scene, robot.neutral())


def test_circulatory_case(follower_chain):
    assert "N" in follower_chain.nonzero and "D" not in follower_chain.nonzero
    for method in ("auto", "general"):
        m = pinlin.modal_analysis(follower_chain, method=method)
        check_pairs(m)
    assert pinlin.modal_analysis(follower_chain).method == "squared"


def test_tuple_with_nonsymmetric_mass_recovers_vectors_from_better_block():
    rng = np.random.default_rng(3)
    n = 8
    M = rng.standard_normal((n, n)) + 4 * np.eye(n)
    C = rng.standard_normal((n, n))
    K = 1e4 * rng.standard_normal((n, n))
    m = pinlin.modal_analysis((M, C, K))
    check_pairs(m)
    assert set(np.unique(m.block)) == {1, 2}  # both blocks are needed
    assert m.system is None and m.constants is None
    unscaled = pinlin.modal_analysis((M, C, K), scaling=False)
    assert unscaled.max_backward_error > 100 * m.max_backward_error


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 6), scale=st.floats(-3, 3))
def test_property_general_coefficients(seed, n, scale):
    """Random real (M, C, K): small eta, conjugate pairs, and Vieta's relations of p = det L.

    prod lam = det K / det M and sum lam = -trace(M^-1 C) hold for the 2n roots of
    det(lam^2 M + lam C + K) and are computed here without any eigen-solver.
    """
    rng = np.random.default_rng(seed)
    M = rng.standard_normal((n, n)) + 3 * np.eye(n)
    C = 10.0 ** (scale / 2) * rng.standard_normal((n, n))
    K = 10.0**scale * rng.standard_normal((n, n))
    m = pinlin.modal_analysis((M, C, K))
    lam = m.eigenvalues
    assert lam.shape == (2 * n,)
    eta = eta_reference(M, C, K, lam, m.right)
    assert np.max(eta) < 1e-13
    assert_allclose(np.sort_complex(np.conj(lam)), np.sort_complex(lam), rtol=1e-12, atol=1e-12 * np.abs(lam).max())
    assert_allclose(np.sum(lam).real, -np.trace(np.linalg.solve(M, C)), rtol=1e-9, atol=1e-9 * np.abs(lam).max())
    det_ratio = np.linalg.det(K) / np.linalg.det(M)
    prod = np.prod(lam)
    assert_allclose(prod.real, det_ratio, rtol=1e-8, atol=1e-12 * abs(det_ratio))
