"""The asymmetric shaft (theory: Floquet): in inertial coordinates K(t) = R(Omega t) diag(k1, k2) R^T is
pi / Omega-periodic; its Floquet exponents equal the rotating-frame eigenvalues modulo i Omega, and the
undamped shaft is unstable exactly for sqrt(k1/m) < Omega < sqrt(k2/m), marginally stable (by structure)
outside."""

from __future__ import annotations

import numpy as np
import pytest
from floquet_cases import residues_modulo, shaft_inertial, shaft_rotating_eigenvalues
from numpy.testing import assert_allclose

from pinlin.periodic import floquet_analysis_matrices

MASS, K1, K2 = 2.0, 2.0, 4.5            # sqrt(k1/m) = 1, sqrt(k2/m) = 1.5 [rad/s]


@pytest.mark.parametrize("Omega, damping", [(0.6, 0.0), (1.2, 0.0), (2.3, 0.0), (1.2, 0.05), (0.8, 0.1)])
def test_exponents_equal_rotating_frame_eigenvalues_modulo_i_omega(Omega, damping):
    (M, C, K), T = shaft_inertial(MASS, K1, K2, Omega, damping)
    res = floquet_analysis_matrices(M, C, K, T)
    lam = shaft_rotating_eigenvalues(MASS, K1, K2, Omega, damping)
    assert residues_modulo(res.exponents, lam, Omega) < 1e-10       # measured: 2e-14
    assert residues_modulo(lam, res.exponents, Omega) < 1e-10       # and every eigenvalue is matched


@pytest.mark.parametrize("Omega, kind", [
    (0.5, "marginally_stable"), (0.999, "marginally_stable"), (1.001, "flutter"), (1.25, "flutter"),
    (1.499, "flutter"), (1.501, "marginally_stable"), (3.0, "marginally_stable")])
def test_undamped_verdict_switches_exactly_at_the_two_critical_speeds(Omega, kind):
    (M, C, K), T = shaft_inertial(MASS, K1, K2, Omega)
    res = floquet_analysis_matrices(M, C, K, T)
    assert res.conservative
    assert res.stability.kind == kind, res.stability
    if kind == "flutter":
        # the rotating frame's real root lam shows as mu = exp((lam + i Omega) T) = -exp(lam T): negative real
        assert "period doubling" in res.stability.reason


def test_monodromy_is_symplectic_for_the_energy_form():
    (M, C, K), T = shaft_inertial(MASS, K1, K2, 0.8)
    res = floquet_analysis_matrices(M, C, K, T)
    Omega_form = np.block([[np.zeros((2, 2)), MASS * np.eye(2)], [-MASS * np.eye(2), np.zeros((2, 2))]])
    P = res.monodromy
    assert_allclose(P.T @ Omega_form @ P, Omega_form, rtol=0, atol=1e-12)
    assert_allclose(np.abs(res.multipliers), 1.0, rtol=0, atol=1e-12)
