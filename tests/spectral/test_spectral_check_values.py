"""theory: spectrum check values and closed-form spectra (literature / hand-derived cases).

Sources: theory: spectrum (eigenvalues and kappa of lam^2 A2 + lam A1 + A0 to
the digits given there); theory: rotating ring (rotating ring, closed form in z = x + iy);
theory: double pendulum (double pendulum matrices, eigenvalues from mpmath at 50 digits);
Euler-Bernoulli cantilever frequencies (beta L from 1 + cos cosh = 0).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from spectral_cases import (
    A0,
    A1,
    A2,
    CANTILEVER_BETA_L,
    cantilever,
    double_pendulum,
    double_pendulum_spec,
    match,
    mp_eigenvalues,
    ring,
    ring_closed_form,
)

CHECK_LAMBDA = np.array([-3.8513, -0.59217 + 0.80280j, -0.59217 - 0.80280j, 0.52326 + 0.62251j,
                        0.52326 - 0.62251j, 0.78909])
CHECK_KAPPA = np.array([2.3092, 0.70275, 0.70275, 2.7013, 2.7013, 2.0144])


@pytest.fixture(scope="module")
def check_modes():
    return pinlin.modal_analysis((A2, A1, A0))


def test_spec_check_eigenvalues_and_kappa_to_4_digits(check_modes):
    m = check_modes
    lam = match(CHECK_LAMBDA, m.eigenvalues)  # computed, in the listed order
    order = [int(np.argmin(np.abs(m.eigenvalues - x))) for x in lam]
    assert_allclose(lam, CHECK_LAMBDA, rtol=5e-5, atol=0)
    assert_allclose(m.condition[order], CHECK_KAPPA, rtol=5e-5, atol=0)


def test_spec_check_eigenvalues_against_mpmath(check_modes):
    ref = mp_eigenvalues(A2, A1, A0)
    assert_allclose(check_modes.eigenvalues, match(check_modes.eigenvalues, ref), rtol=1e-13, atol=0)
    assert check_modes.method == "general"
    assert check_modes.max_backward_error < 1e-15


def test_spec_check_kappa_bounds_the_actual_error(check_modes):
    """|lam - lam_ref| <= error_bound (first order), checked against the 50-digit reference."""
    ref = match(check_modes.eigenvalues, mp_eigenvalues(A2, A1, A0))
    err = np.abs(check_modes.eigenvalues - ref)
    assert np.all(err <= 10 * check_modes.error_bound + 1e-300)


@pytest.mark.parametrize("c, Omega", [(0.0, 1.0), (0.0, 3.0), (0.3, 1.0), (0.3, 3.0)])
def test_rotating_ring_closed_form(c, Omega):
    sys = ring(k=4.0, c=c, Omega=Omega)
    m = pinlin.modal_analysis(sys)
    ref = ring_closed_form(1.0, 4.0, c, Omega)
    assert_allclose(m.eigenvalues, match(m.eigenvalues, ref), rtol=1e-13, atol=1e-14)
    assert_allclose(m.natural_frequency, np.abs(m.eigenvalues), rtol=1e-15, atol=0)


@pytest.mark.parametrize("P, c", [(4.0, 0.0), (4.0, 0.1), (0.0, 0.1), (40.0, 0.0)])
def test_double_pendulum_against_spec_matrices_in_mpmath(P, c):
    sys = double_pendulum(P=P, c=c)
    M, S, N = double_pendulum_spec(P=P)
    D = c * np.eye(2)
    ref = mp_eigenvalues(M, D, S + N)
    m = pinlin.modal_analysis(sys)
    assert_allclose(m.eigenvalues, match(m.eigenvalues, ref), rtol=1e-10, atol=1e-12)


def test_cantilever_lowest_frequencies_converge_to_euler_bernoulli():
    E, I, rhoA, L = 2.1e11, 8.33e-10, 0.785, 2.0
    beam = cantilever(ne=40, L=L, E=E, I=I, rhoA=rhoA, c=0.0)
    m = pinlin.modal_analysis(beam)
    assert m.method == "symmetric"
    omega = np.sort(m.natural_frequency[m.eigenvalues.imag > 0])[:3]
    exact = np.array(CANTILEVER_BETA_L) ** 2 * np.sqrt(E * I / (rhoA * L**4))
    # consistent-mass Hermite elements are a Rayleigh-Ritz method: upper bounds converging
    # like h^4; with 40 elements the third frequency is within 2e-6
    assert np.all(omega >= exact * (1 - 1e-12))
    assert_allclose(omega, exact, rtol=2e-6, atol=0)
    assert_allclose(omega[0], exact[0], rtol=5e-9, atol=0)
