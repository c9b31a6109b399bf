"""Multi-blade (Coleman) transform of a lag-hinged rotor on a hub (Coleman-Feingold ground resonance,
theory: Floquet): the transformed system is time-invariant for N >= 3 identical blades, isotropic or
anisotropic hub alike, and its eigenvalues equal the blade-coordinate Floquet exponents modulo i Omega;
N = 2 and dissimilar blades are refused."""

from __future__ import annotations

import numpy as np
import pytest
from floquet_cases import lag_rotor, residues_modulo
from numpy.testing import assert_allclose

from pinlin.errors import ParameterError, PinlinError
from pinlin.errors.periodic import MultibladeNotExactError
from pinlin.periodic import floquet_analysis_matrices, multiblade_transform_matrices


def _eigenvalues(system):
    M, D, G, S, N = system.M, system.D, system.G, system.S, system.N
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, S + N), -np.linalg.solve(M, D + G)]])
    return np.linalg.eigvals(A)


def _rotor_sizes(N):
    return list(range(2, N + 2))


@pytest.mark.parametrize("N, hub", [
    (3, (10.0, 40.0, 40.0, 0.4, 0.4)),          # isotropic hub
    (3, (10.0, 40.0, 60.0, 0.4, 0.9)),          # anisotropic hub: still exact (the support is in the fixed frame)
    (4, (10.0, 30.0, 55.0, 0.3, 0.6)),          # even N: a differential coordinate
    (5, (10.0, 40.0, 60.0, 0.4, 0.4)),
])
def test_floquet_exponents_equal_multiblade_eigenvalues(N, hub):
    Omega = 3.0
    (M, C, K), T = lag_rotor(N, Omega=Omega, hub=hub)
    system = multiblade_transform_matrices(M, C, K, _rotor_sizes(N), Omega)
    lam = _eigenvalues(system)
    res = floquet_analysis_matrices(M, C, K, T)
    assert residues_modulo(res.exponents, lam, Omega) < 1e-10        # measured: about 1e-13
    assert residues_modulo(lam, res.exponents, Omega) < 1e-10
    assert system.dof_names[2:5] == ("blade_collective", "blade_cos1", "blade_sin1")
    if N == 4:
        assert system.dof_names[-1] == "blade_differential"
    assert_allclose(system.M, system.M.T, rtol=0, atol=0)          # T^T M T stays symmetric


def test_ground_resonance_instability_seen_both_ways():
    # soft, lightly damped lag and hub: an unstable ground-resonance window (Coleman-Feingold)
    Omega = 4.0
    (M, C, K), T = lag_rotor(3, Omega=Omega, hub=(5.0, 30.0, 30.0, 0.05, 0.05), lag=(0.5, 0.005))
    lam = _eigenvalues(multiblade_transform_matrices(M, C, K, [2, 3, 4], Omega))
    res = floquet_analysis_matrices(M, C, K, T)
    assert lam.real.max() > 1e-3
    assert_allclose(res.exponents.real.max(), lam.real.max(), rtol=1e-9)
    assert res.stability.unstable


@pytest.mark.parametrize("N, changes, match", [
    (2, None, "not exact here"),
    (3, {1: 1.3}, "not exact here"),
])
def test_refused_when_not_exact(N, changes, match):
    (M, C, K), _ = lag_rotor(N, blade_changes=changes)
    with pytest.raises(MultibladeNotExactError, match=match) as info:
        multiblade_transform_matrices(M, C, K, _rotor_sizes(N), 3.0)
    assert isinstance(info.value, PinlinError) and info.value.variation > 1e-3


def test_bad_arguments():
    (M, C, K), _ = lag_rotor(3)
    with pytest.raises(ParameterError, match="blades"):
        multiblade_transform_matrices(M, C, K, [2, 2, 3], 3.0)
    with pytest.raises(ParameterError, match="blades"):
        multiblade_transform_matrices(M, C, K, [2, 3, 9], 3.0)
    with pytest.raises(ParameterError, match="omega"):
        multiblade_transform_matrices(M, C, K, [2, 3, 4], 0.0)
    with pytest.raises(ParameterError, match="dof_names"):
        multiblade_transform_matrices(M, C, K, [2, 3, 4], 3.0, dof_names=["a"])


def test_undamped_rotor_is_lagrangian_with_time_varying_mass():
    """The blade-coordinate rotor has M(t) varying and D = M' (a Lagrangian variational equation): detected as
    conservative from the sampled coefficients' derivatives, so a stable undamped rotor is "marginally_stable";
    evaluated at the nodes (no derivatives) it is "undecided" unless the caller asserts conservative=True
    (checked against the symplecticity of the monodromy)."""
    Omega = 3.0
    (M, C, K), T = lag_rotor(3, Omega=Omega, hub=(10.0, 40.0, 60.0, 0.0, 0.0), lag=(2.0, 0.0))
    t, h = 0.37, 1e-6
    Mdot = (M(t + h) - M(t - h)) / (2 * h)
    assert_allclose((C(t) + C(t).T) / 2, Mdot, rtol=0, atol=1e-8)
    lam = _eigenvalues(multiblade_transform_matrices(M, C, K, [2, 3, 4], Omega))
    assert np.max(np.abs(lam.real)) < 1e-12               # the transformed system: every root on the axis
    sampled = floquet_analysis_matrices(M, C, K, T)
    assert sampled.conservative and sampled.stability.kind == "marginally_stable", sampled.stability
    plain = floquet_analysis_matrices(M, C, K, T, sampling="nodes")
    assert not plain.conservative and plain.stability.kind == "undecided"
    asserted = floquet_analysis_matrices(M, C, K, T, conservative=True, sampling="nodes")
    assert asserted.conservative and asserted.stability.kind == "marginally_stable", asserted.stability
    damped, _ = lag_rotor(3, Omega=Omega)
    with pytest.raises(ParameterError, match="conservative: the monodromy is not symplectic"):
        floquet_analysis_matrices(*damped, T, conservative=True)


def test_variation_tol_decides_and_tolerance_is_its_deprecated_spelling():
    (M, C, K), _ = lag_rotor(3, blade_changes={1: 1.0 + 1e-6})     # blades dissimilar by 1e-6 (relative)
    with pytest.raises(MultibladeNotExactError, match=r"variation_tol 1e-10") as info:
        multiblade_transform_matrices(M, C, K, [2, 3, 4], 3.0)
    variation = info.value.variation
    assert 1e-8 < variation < 1e-5
    loose = multiblade_transform_matrices(M, C, K, [2, 3, 4], 3.0, variation_tol=10 * variation)
    with pytest.warns(DeprecationWarning, match=r"multiblade_transform_matrices\(tolerance=...\) .* use variation_tol="):
        old = multiblade_transform_matrices(M, C, K, [2, 3, 4], 3.0, tolerance=10 * variation)
    assert_allclose(old.M, loose.M, rtol=0, atol=0)
    with pytest.raises(MultibladeNotExactError):
        multiblade_transform_matrices(M, C, K, [2, 3, 4], 3.0, variation_tol=0.5 * variation)
