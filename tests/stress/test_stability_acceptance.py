"""Stability acceptance: stability decided wherever the floating-point data decide it (theory: stability).

- spring chains of 10 and 30 unit masses, springs alternating 1 and 1e10 / 1e12 / 1e14, dashpots 0.01,
  the ground spring 1, -1e-3 or -0.5 (acceptance numbers; truth from mpmath's eigenvalues of the stored S);
- property tests: random M > 0, D > 0, S > 0, N = 0 with condition numbers up to 1e12 (and beyond, to
  exercise the undecidable side), checked against mpmath: never wrong, never undecided where the data
  decide by a factor 10;
- the NLEVP damped beam: bounded, asymptotic or marginal stability undecidable;
- D = 0 with G != 0 and N != 0 (closed form: always flutter), N down to 1e-15: never "marginally stable".
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pinlin
from pinlin import LinearizedSystem
from spectral_cases import nlevp_damped_beam
from stress_cases import spring_chain

EPS = np.finfo(float).eps


def mp_eigvalsh(A, dps=40) -> np.ndarray:
    """Eigenvalues of the stored symmetric matrix A (exact binary numbers) at ``dps`` digits, ascending."""
    with mp.workdps(dps):
        w = mp.eigsy(mp.matrix(np.asarray(A, dtype=float).tolist()), eigvals_only=True)
        return np.sort(np.array([float(x) for x in w]))


@pytest.mark.parametrize("n", [10, 30])
@pytest.mark.parametrize("big", [1e10, 1e12])
def test_stiff_spring_chains_are_asymptotically_stable(n, big):
    sys = spring_chain(n, big)
    exact = mp_eigvalsh(sys.S)
    assert exact[0] > 0 and exact[0] / exact[-1] < 1e-10  # pinlin 0.2's ratio test called S singular
    m = pinlin.modal_analysis(sys)
    v = m.stability
    assert v.kind == "asymptotically_stable" and v.theorem == "Thomson-Tait-Chetaev" and v.bounded is True
    assert m.structure.stiffness == "positive_definite" and m.structure.damping == "positive_definite"
    # the margin is that of S > 0 (the tightest of M, D, S): certified, and within a factor 2 of the truth
    assert 0 < v.margin <= exact[0] / exact[-1] <= 2 * v.margin
    assert f"margin {v.margin:.1e}" in v.reason and v.error == EPS / v.margin
    certificate = m.structure.definiteness_S.certificate
    assert certificate == ("Cholesky" if (n, big) == (30, 1e12) else "eigenvalues")


@pytest.mark.parametrize("n", [10, 30])
@pytest.mark.parametrize("big", [1e10, 1e12, 1e14])
def test_chain_with_a_slightly_negative_ground_spring_is_never_called_stable(n, big):
    sys = spring_chain(n, big, ground=-1e-3)
    v = pinlin.modal_analysis(sys).stability
    assert not v.stable
    exact = mp_eigvalsh(sys.S)
    if exact[0] < -10 * n * EPS * exact[-1]:  # decidable: S certainly indefinite, D > 0 (Kelvin-Tait-Chetaev)
        assert v.kind == "divergence"
    if (n, big) == (10, 1e12):  # lambda_min = -9.8e-5 against n eps ||S|| = 4.4e-3: undecidable
        assert v.kind == "undecided"


@pytest.mark.parametrize("n", [10, 30])
@pytest.mark.parametrize("big", [1e10, 1e12])
def test_chain_with_a_negative_ground_spring_diverges(n, big):
    sys = spring_chain(n, big, ground=-0.5)
    exact = mp_eigvalsh(sys.S)
    assert exact[0] < -0.08
    v = pinlin.modal_analysis(sys).stability
    assert v.kind == "divergence" and v.bounded is False and v.margin > 0
    assert v.eigenvalue.imag == 0 and v.eigenvalue.real > 0


@pytest.mark.parametrize("n", [10, 30])
def test_chain_beyond_double_precision_is_never_called_unstable(n):
    """Springs 1e14: lambda_min(S) = 0.044 against n eps ||S|| = 0.44, honestly undecidable."""
    v = pinlin.modal_analysis(spring_chain(n, 1e14)).stability
    assert not v.unstable
    assert v.kind == "undecided" and v.margin == 0.0 and v.error == 1.0


def test_uncertainty_makes_the_verdict_hold_for_every_nearby_system():
    sys = spring_chain(10, 1e10)
    base = pinlin.modal_analysis(sys).stability
    exact = mp_eigvalsh(sys.S)
    rel = exact[0] / exact[-1]  # 2e-12: the relative perturbation of S that makes it singular
    assert pinlin.modal_analysis(sys, uncertainty=0.5 * rel).stability.kind == "asymptotically_stable"
    v = pinlin.modal_analysis(sys, uncertainty=2 * rel).stability
    assert v.kind != "asymptotically_stable" or v.theorem != "Thomson-Tait-Chetaev"
    # and indeed a perturbation of that size makes the system unstable: S - 2 lambda_min v v^T
    w, V = np.linalg.eigh(sys.S)
    S2 = sys.S - 2 * exact[0] * np.outer(V[:, 0], V[:, 0])
    perturbed = LinearizedSystem(sys.M, sys.D, sys.G, (S2 + S2.T) / 2, sys.N)
    assert np.linalg.norm(perturbed.S - sys.S, 2) <= 2.01 * rel * exact[-1]
    assert pinlin.modal_analysis(perturbed).stability.kind == "divergence"
    assert base.margin <= rel


def test_nlevp_damped_beam_is_bounded_but_undecided():
    """NLEVP damped_beam (n = 200): half of its modes are undamped in exact arithmetic, only within
    rounding in floating point; D >= 0 (one dashpot, exact zeros elsewhere), S > 0: bounded."""
    sys = nlevp_damped_beam(200)
    m = pinlin.modal_analysis(sys)
    v = m.stability
    assert v.kind == "undecided" and v.theorem == "Lagrange-Dirichlet" and v.bounded is True
    assert "asymptotic or marginal stability cannot be told apart" in v.reason
    assert m.structure.definiteness_D.certainly_psd and m.structure.stiffness == "positive_definite"
    assert abs(v.eigenvalue.real) <= v.error_bound
    # about half of the eigenvalues lie within their bounds of the axis
    near = np.abs(m.eigenvalues.real) <= m.tolerances["safety"] * m.error_bound
    assert 0.45 <= np.mean(near) <= 0.55


def gyroscopic_circulatory(Omega, s, nu):
    """A particle in a rotating frame (theory: rotating ring without damping) with a circulatory force nu J.

    With z = x + i y: z'' + 2 i Omega z' + (s - i nu) z = 0, so lam = -i Omega +- sqrt(-Omega^2 - s + i nu)
    and their conjugates: for nu != 0 one root of each pair has Re lam = +-nu / (2 sqrt(Omega^2 + s)) > 0.
    """
    J = np.array([[0.0, 1.0], [-1.0, 0.0]])
    sys = LinearizedSystem(np.eye(2), np.zeros((2, 2)), -2 * Omega * J, s * np.eye(2), nu * J)
    root = np.sqrt(complex(-Omega**2 - s, nu))
    lam = np.array([-1j * Omega + root, -1j * Omega - root])
    return sys, np.concatenate([lam, lam.conj()])


@pytest.mark.parametrize("nu", [1e-1, 1e-3, 1e-8, 1e-12, 1e-15])
def test_undamped_gyroscopic_with_circulatory_forces_is_never_marginally_stable(nu):
    sys, exact = gyroscopic_circulatory(Omega=1.5, s=2.0, nu=nu)
    assert sys.nonzero == ("M", "G", "S", "N") and np.max(exact.real) > 0  # the truth: flutter
    m = pinlin.modal_analysis(sys)
    assert not m.structure.reflection_symmetric
    assert m.stability.kind in ("flutter", "undecided")
    if np.max(exact.real) > 1e3 * np.max(m.error_bound):
        assert m.stability.kind == "flutter"


def _spd(rng, n, log_cond):
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    A = Q @ np.diag(np.geomspace(1.0, 10.0**-log_cond, n) * 10.0 ** rng.uniform(-2, 2)) @ Q.T
    return (A + A.T) / 2


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 6),
    log_cond=st.tuples(st.floats(0, 12), st.floats(0, 12), st.floats(0, 16)),
    gyro=st.booleans(),
)
def test_property_dissipative_stiff_systems_never_wrong_and_decided_where_the_data_decide(seed, n, log_cond, gyro):
    """M > 0, D > 0, S > 0 (as built), N = 0, condition numbers up to 1e12 for M and D and 1e16 for S."""
    rng = np.random.default_rng(seed)
    M, D, S = (_spd(rng, n, c) for c in log_cond)
    A = rng.standard_normal((n, n))
    G = (A - A.T) if gyro else np.zeros((n, n))
    sys = LinearizedSystem(M, D, G, S, np.zeros((n, n)))
    v = pinlin.modal_analysis(sys).stability
    # the truth of the stored matrices, from mpmath; the bound c n eps ||A||_2 with mpmath's norm
    margins = []
    for X in (sys.M, sys.D, sys.S):
        w = mp_eigvalsh(X)
        margins.append(w[0] / (10 * n * EPS * np.max(np.abs(w))))
    truly_pd = min(w[0] for w in map(mp_eigvalsh, (sys.M, sys.D, sys.S))) > 0
    if truly_pd:  # Thomson-Tait-Chetaev holds for the stored data: asymptotically stable
        assert v.kind in ("asymptotically_stable", "undecided")
    else:  # S indefinite as stored (D > 0): Kelvin-Tait-Chetaev, unstable
        assert v.kind in ("divergence", "flutter", "undecided")
    if min(margins) > 1:  # every lambda_min 10 times beyond its rounding bound: the data decide
        assert v.kind == "asymptotically_stable" and v.theorem == "Thomson-Tait-Chetaev"
