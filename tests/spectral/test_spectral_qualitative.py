"""Modal constants m, d, g, k, n and the structural facts (theory: stability, paper Sec. 11).

Hand derivation for the rotating ring (theory: rotating ring): its modes are circular,
x = (1, -+i)/sqrt(2), so m = 1, d = c, g = -+2 m Omega, k = k - m Omega^2, n = 0.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin import LinearizedSystem
from spectral_cases import double_pendulum, ring


def test_ring_mode_constants_by_hand():
    k, c, Omega = 4.0, 0.2, 1.5
    m = pinlin.modal_analysis(ring(k=k, c=c, Omega=Omega))
    q = m.constants
    assert_allclose(q.m, 1.0, rtol=1e-15, atol=0)
    assert_allclose(q.d, c, rtol=1e-13, atol=0)
    assert_allclose(np.abs(q.g), 2 * Omega, rtol=1e-13, atol=0)
    assert_allclose(q.k, k - Omega**2, rtol=1e-13, atol=0)
    assert_allclose(q.n, 0.0, rtol=0, atol=1e-15)
    assert np.max(q.residual) < 1e-14


@pytest.mark.parametrize("P, c", [(4.0, 0.0), (12.0, 0.05), (40.0, 0.0)])
def test_mode_constants_satisfy_their_scalar_equation(P, c):
    sys = double_pendulum(P=P, c=c)
    m = pinlin.modal_analysis(sys)
    q = m.constants
    lam = m.eigenvalues
    # recompute from the definition with x^H M x = 1
    X = m.right / np.sqrt(np.einsum("ij,ij->j", m.right.conj(), sys.M @ m.right).real)
    quad = lambda A: np.einsum("ij,ij->j", X.conj(), A @ X)  # noqa: E731
    assert_allclose(q.d, quad(sys.D).real, rtol=1e-12, atol=1e-14)
    assert_allclose(q.n, (-1j * quad(sys.N)).real, rtol=1e-12, atol=1e-14)
    assert_allclose(q.k, quad(sys.S).real, rtol=1e-12, atol=1e-14)
    residual = np.abs(q.m * lam**2 + (q.d + 1j * q.g) * lam + (q.k + 1j * q.n))
    assert np.max(residual / (np.abs(lam) ** 2 + np.abs(q.k) + np.abs(q.n) + np.abs(lam) * np.abs(q.d))) < 1e-13
    assert np.max(q.residual) < 1e-13
    if c > 0:
        assert np.all(q.d > 0)  # D > 0 => d > 0


def test_overdamped_modes_have_real_roots():
    # G = N = 0: d^2 > 4 m k per mode <=> real eigenvalues
    sys = LinearizedSystem.from_matrices(np.diag([1.0, 1.0, 2.0]), np.diag([5.0, 0.5, 1.0]), np.diag([4.0, 4.0, 8.0]))
    m = pinlin.modal_analysis(sys)
    q = m.constants
    real = m.eigenvalues.imag == 0
    assert_allclose(q.overdamped(), real, rtol=0, atol=0)
    assert real.sum() == 2
    assert [m.kind[i] for i in np.flatnonzero(real)] == ["overdamped", "overdamped"]


def test_structural_facts():
    m = pinlin.modal_analysis(ring(k=4.0, c=0.2, Omega=3.0))
    f = m.structure
    assert f.damping == "positive_definite"
    assert f.stiffness == "negative_definite" and f.negative_stiffness == 2
    assert f.gyroscopic and not f.circulatory and f.damped
    assert f.det_sign_M == 1 and f.det_sign_K == 1
    assert not f.reflection_symmetric
    g = pinlin.modal_analysis(double_pendulum(P=4.0)).structure
    assert g.circulatory and not g.damped and g.reflection_symmetric
    assert g.stiffness == "positive_definite" and g.negative_stiffness == 0
    t = pinlin.modal_analysis((np.eye(2), np.zeros((2, 2)), np.diag([1.0, -1.0]))).structure
    assert t.damping is None and t.det_sign_K == -1
    assert "sign det K = -1" in t.describe()
