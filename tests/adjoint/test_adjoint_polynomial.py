"""Characteristic polynomial p(lam) = det L(lam) (theory: adjoint).

References: mpmath determinants at 50 digits, and det M prod (lam - lam_k) with
the eigenvalues of the 50-digit companion matrix (not interpolation) or of the
spectral module (a structured QEP solver).
"""

import numpy as np
import pytest
from numpy.polynomial import Polynomial
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import chain, det_mp, double_pendulum, poly_coefficients_mp, random_system
from pinlin.adjoint import CharacteristicPolynomial, characteristic_polynomial


def test_is_a_polynomial_of_degree_2n_with_error_figures():
    sys = double_pendulum()
    p = pinlin.characteristic_polynomial(sys)
    assert isinstance(p, Polynomial) and isinstance(p, CharacteristicPolynomial)
    assert p.degree() == 2 * sys.n
    assert p.coef_error.shape == (2 * sys.n + 1,)
    assert 0 < p.error < 1e-13
    assert p.elapsed > 0 and p.evaluations > 0 and "FFT" in p.method
    # Polynomial arithmetic works and derived polynomials carry no (stale) error figures
    dp = p.deriv()
    assert isinstance(dp, Polynomial) and dp.coef_error is None
    assert_allclose((p - p).coef, [0.0], atol=0)


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_value_equals_determinant_at_random_points(n):
    rng = np.random.default_rng(100 + n)
    sys = random_system(rng, n)
    p = characteristic_polynomial(sys)
    pts = rng.standard_normal(5) + 1j * rng.standard_normal(5)
    for s in pts:
        ref = det_mp(sys, s)
        bound = p.error_at(s)
        assert abs(p(s) - ref) <= bound
        assert_allclose(p(s), ref, rtol=1e-12)


def test_leading_and_constant_coefficients_are_det_m_and_det_k():
    rng = np.random.default_rng(7)
    sys = random_system(rng, 4)
    p = characteristic_polynomial(sys)
    assert_allclose(p.coef[-1], det_mp(sys, 1e30) / 1e240, rtol=1e-13)  # det(lam^2 M)/lam^8
    assert_allclose(p.coef[0], det_mp(sys, 0.0).real, rtol=1e-13)


def test_double_pendulum_closed_form():
    """theory: double pendulum: D = G = 0, so p(lam) = det M lam^4 + b lam^2 + det K with b from the 2 x 2 entries."""
    sys = double_pendulum()
    M, K = sys.M, sys.K
    b = M[0, 0] * K[1, 1] + M[1, 1] * K[0, 0] - M[0, 1] * K[1, 0] - M[1, 0] * K[0, 1]
    p = characteristic_polynomial(sys)
    assert_allclose(p.coef, [np.linalg.det(K), 0.0, b, 0.0, np.linalg.det(M)], rtol=1e-13, atol=1e-13 * abs(b))


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_coefficients_match_det_m_times_product_over_spectral_eigenvalues(n):
    rng = np.random.default_rng(200 + n)
    sys = random_system(rng, n)
    modes = pinlin.modal_analysis(sys)
    prod = Polynomial.fromroots(modes.eigenvalues).coef * np.linalg.det(sys.M)
    assert_allclose(prod.imag, 0.0, atol=1e-12 * np.max(np.abs(prod)))
    p = characteristic_polynomial(sys)
    assert_allclose(p.coef, prod.real, rtol=1e-11, atol=1e-12 * np.max(np.abs(prod)))


@pytest.mark.parametrize("n", [2, 6])
def test_coefficients_match_50_digit_reference_within_reported_error(n):
    rng = np.random.default_rng(300 + n)
    sys = random_system(rng, n)
    ref = poly_coefficients_mp(sys)
    p = characteristic_polynomial(sys)
    assert np.all(np.abs(p.coef - ref) <= p.coef_error)
    assert_allclose(p.coef, ref, rtol=1e-12)


def test_degradation_with_n_is_recorded_and_bounded(record_property):
    """Pendulum chains: relative coefficient error against the 50-digit reference as n grows.

    Records (n, max relative coefficient error, normwise error, reported bound).
    The FFT on several circles keeps every coefficient accurate relative to
    itself (about 1e-15 n^2 here), and the reported bound always covers the error.
    """
    rows = []
    for n in (1, 2, 4, 6, 8):
        sys = chain(n)
        p = characteristic_polynomial(sys)
        ref = poly_coefficients_mp(sys)
        rel = float(np.max(np.abs(p.coef - ref) / np.abs(ref)))
        normwise = float(np.linalg.norm(p.coef - ref) / np.linalg.norm(ref))
        rows.append((n, rel, normwise, float(np.max(p.relative_coef_error))))
        assert np.all(np.abs(p.coef - ref) <= p.coef_error), n
        assert rel < 1e-13 * n * n + 1e-15
    record_property("characteristic_polynomial_degradation", rows)
    # errors grow with n (not a method that is exact by construction)
    assert rows[-1][1] > rows[0][1]


def test_zero_roots_give_zero_constant_term():
    """A free rigid-body mode (K singular, no damping on it): lam = 0 is a double root."""
    M = np.diag([1.0, 2.0])
    K = np.array([[1.0, -1.0], [-1.0, 1.0]])
    sys = pinlin.LinearizedSystem.from_matrices(M, None, K)
    p = characteristic_polynomial(sys)
    # p = lam^2 (2 lam^2 + 3): by hand
    assert_allclose(p.coef, [0.0, 0.0, 3.0, 0.0, 2.0], atol=1e-14)
    assert p.coef_error[0] < 1e-14


def test_coefficients_that_overflow_or_underflow_raise():
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(60) * 1e12, None, np.eye(60) * 1e14)
    with pytest.raises(pinlin.ComputationError, match="overflows"):
        characteristic_polynomial(sys)
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(60) * 1e-12, None, np.eye(60) * 1e-10)
    with pytest.raises(pinlin.ComputationError, match="underflows"):
        characteristic_polynomial(sys)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"radii": [1.0, -2.0]}, "radii"),
        ({"radii": []}, "radii"),
        ({"n_points": 3}, "n_points"),
        ({"radius_ratio": 1.0}, "radius_ratio"),
        ({"radius_ratio": float("nan")}, "radius_ratio"),
    ],
)
def test_bad_arguments(kwargs, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        characteristic_polynomial(double_pendulum(), **kwargs)


def test_bad_system_and_points():
    with pytest.raises(pinlin.ParameterError, match="LinearizedSystem"):
        characteristic_polynomial(np.eye(2))
    p = characteristic_polynomial(double_pendulum())
    with pytest.raises(pinlin.ParameterError, match="finite"):
        p.error_at(np.inf)
    with pytest.raises(AttributeError, match="no error figures"):
        p.deriv().error_at(1.0)


def test_mp_reference_closed_form_oscillator():
    """pinlin.testing's 50-digit reference itself, on m lam^2 + c lam + k: roots and coefficients exact."""
    from pinlin.testing import mp_characteristic_coefficients, mp_eigenvalues, paired

    m, c, k = 2.0, 0.6, 5.0
    sys = pinlin.LinearizedSystem.from_matrices([[m]], [[c]], [[k]])
    roots = (-c + np.array([1, -1]) * np.sqrt(complex(c * c - 4 * m * k))) / (2 * m)
    assert_allclose(paired(roots, mp_eigenvalues(sys)), roots, rtol=1e-15)
    coef, _ = mp_characteristic_coefficients(sys)
    assert_allclose(coef, [k, c, m], rtol=1e-15)
    with pytest.raises(pinlin.ParameterError, match="three square matrices"):
        mp_eigenvalues((np.eye(2), np.eye(3), np.eye(2)))


def test_cantilever_beam_test_problem():
    """pinlin.testing.cantilever_beam: static tip deflection of the FE beam is exact (cubic elements): P L^3 / 3EI."""
    from pinlin.testing import cantilever_beam

    L, E, I = 2.0, 2.1e11, 8.33e-10
    beam = cantilever_beam(8, L=L, E=E, I=I)
    f = np.zeros(beam.n)
    f[-2] = 1.0  # unit tip force on the last transverse displacement
    assert_allclose(np.linalg.solve(beam.K, f)[-2], L**3 / (3 * E * I), rtol=1e-10)
    assert beam.D[-2, -2] == 50.0 and np.count_nonzero(beam.D) == 1
    with pytest.raises(pinlin.ParameterError, match="at: expected a node in 1..8"):
        cantilever_beam(8, at=9)
    with pytest.raises(pinlin.ParameterError, match="ne: expected an integer"):
        cantilever_beam(0)
