"""The honest stability verdict (theory: stability, conventions).

Reference cases: the paper's damped double pendulum (theory: double pendulum), the rotating
ring (theory: rotating ring: undamped marginally stable for Omega != sqrt(k/m), damped
stable iff m Omega^2 < k), Ziegler's paradox on the follower-loaded double
pendulum.  Property tests check the theorems on random systems against an
independent computation (state-space eigenvalues, or a sign change of
det L(t) on the positive real axis).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pinlin
from pinlin import LinearizedSystem
from pinlin.spectral import KINDS
from spectral_cases import double_pendulum, ring


def state_matrix_eigs(sys):
    n = sys.n
    Mi = np.linalg.inv(sys.M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ sys.K, -Mi @ sys.C]])
    return np.linalg.eigvals(A)


def test_paper_damped_double_pendulum_hanging_is_asymptotically_stable():
    m = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.1))
    assert m.stability.kind == "asymptotically_stable"
    assert m.stability.bounded is True
    # decided from the eigenvalues (N != 0: no theorem); the reason names the eigenvalue and its bound
    assert m.stability.theorem is None
    lam = m.stability.eigenvalue
    assert lam.real == max(m.eigenvalues.real)
    assert f"{lam.real:.6g}" in m.stability.reason and "error bound" in m.stability.reason
    assert lam.real < -m.stability.error_bound


def test_damped_double_pendulum_without_load_is_decided_by_theorem():
    m = pinlin.modal_analysis(double_pendulum(P=0.0, c=0.1))
    assert m.stability.kind == "asymptotically_stable"
    assert m.stability.theorem == "Thomson-Tait-Chetaev"


@pytest.mark.parametrize("Omega", [0.5, 1.0, 3.0, 5.0])
def test_undamped_rotating_ring_is_marginally_stable(Omega):
    m = pinlin.modal_analysis(ring(k=4.0, c=0.0, Omega=Omega))
    assert m.stability.kind == "marginally_stable"
    if Omega < 2.0:  # S > 0: Lagrange-Dirichlet; above: gyroscopic stabilization, decided by symmetry
        assert "Lagrange-Dirichlet" in m.stability.theorem
    else:
        assert m.stability.theorem == "reflection symmetry"
        assert m.structure.negative_stiffness == 2


@pytest.mark.parametrize("Omega, kind", [(1.0, "asymptotically_stable"), (1.9, "asymptotically_stable"),
                                         (2.1, "flutter"), (3.0, "flutter")])
def test_damped_rotating_ring_is_stable_iff_below_critical_speed(Omega, kind):
    m = pinlin.modal_analysis(ring(k=4.0, c=0.2, Omega=Omega))
    assert m.stability.kind == kind
    if kind == "flutter":
        assert m.stability.theorem == "Kelvin-Tait-Chetaev"
        assert m.stability.bounded is False
        assert max(state_matrix_eigs(m.system).real) > 0


def test_ziegler_paradox_damping_lowers_the_flutter_load():
    undamped = pinlin.modal_analysis(double_pendulum(P=12.0))
    damped = pinlin.modal_analysis(double_pendulum(P=12.0, c=0.05))
    assert undamped.stability.kind == "marginally_stable"
    assert undamped.stability.theorem == "reflection symmetry"
    assert damped.stability.kind == "flutter"
    lam = damped.stability.eigenvalue
    assert lam.real > 0 and abs(lam.imag) > 0
    assert pinlin.modal_analysis(double_pendulum(P=20.0)).stability.kind == "flutter"
    assert pinlin.modal_analysis(double_pendulum(P=40.0)).stability.kind == "divergence"


def test_undecided_when_bounds_cannot_tell():
    # the tuple form has no mechanical structure: a pair of roots exactly on the axis
    # (lam^2 + 1 = 0 coupled weakly) can only be reported as undecided
    M = np.array([[1.0, 0.1], [0.0, 1.0]])
    K = np.array([[1.0, 0.0], [0.3, 4.0]])
    m = pinlin.modal_analysis((M, np.zeros((2, 2)), K))
    assert m.stability.kind == "undecided"
    assert "error bound" in m.stability.reason
    assert m.stability.bounded is None


def test_verdict_kinds_and_strings():
    m = pinlin.modal_analysis(double_pendulum(P=4.0, c=0.1))
    assert m.stability.kind in KINDS
    assert str(m.stability).startswith("asymptotically stable: ")
    assert m.stability.stable and not m.stability.unstable


def _spd(rng, n, lo, hi):
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    return Q @ np.diag(10.0 ** rng.uniform(lo, hi, n)) @ Q.T


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 5), rank_D=st.integers(0, 5), gyro=st.booleans())
def test_property_dissipative_conservative_systems_are_never_unstable(seed, n, rank_D, gyro):
    rng = np.random.default_rng(seed)
    M = _spd(rng, n, -1, 1)
    S = _spd(rng, n, -1, 2)
    B = rng.standard_normal((n, min(rank_D, n)))
    D = B @ B.T
    A = rng.standard_normal((n, n))
    G = (A - A.T) if gyro else np.zeros((n, n))
    sys = LinearizedSystem(M, D, G, S, np.zeros((n, n)))
    m = pinlin.modal_analysis(sys)
    assert m.stability.kind not in ("divergence", "flutter")
    assert m.stability.bounded is True
    # independent: the first-order state matrix has no eigenvalue clearly in Re > 0
    lam = state_matrix_eigs(sys)
    assert max(lam.real) < 1e-6 * max(1.0, max(abs(lam)))


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 5), damped=st.booleans(), gyro=st.booleans())
def test_property_negative_det_stiffness_always_diverges(seed, n, damped, gyro):
    rng = np.random.default_rng(seed)
    M = _spd(rng, n, -1, 1)
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    s = 10.0 ** rng.uniform(-1, 2, n)
    neg = 2 * int(rng.integers(0, (n + 1) // 2)) + 1  # an odd number of negative eigenvalues
    s[:neg] *= -1
    S = Q @ np.diag(s) @ Q.T
    B = rng.standard_normal((n, n))
    D = B @ B.T if damped else np.zeros((n, n))
    A = rng.standard_normal((n, n))
    G = 3 * (A - A.T) if gyro else np.zeros((n, n))
    sys = LinearizedSystem(M, D, G, S, np.zeros((n, n)))
    m = pinlin.modal_analysis(sys)
    assert m.stability.kind == "divergence"
    # independent: det L(t) changes sign on (0, R) for a large R (leading coefficient det M > 0)
    R = 10 * (1 + np.linalg.norm(np.linalg.solve(M, np.hstack([sys.C, sys.K])), 2))
    t = np.concatenate([[0.0], np.geomspace(1e-6, R, 400)])
    dets = np.array([np.linalg.det(x * x * M + x * sys.C + sys.K) for x in t])
    assert dets[0] < 0 < dets[-1]
    # and the reported real positive eigenvalue is a root of det L
    lam = m.stability.eigenvalue
    assert lam.imag == 0 and lam.real > 0


def test_theorems_decide_without_the_spectrum():
    from pinlin.spectral import stability_from_structure

    v = stability_from_structure(ring(k=4.0, c=0.2, Omega=1.0))
    assert v.kind == "asymptotically_stable" and v.theorem == "Thomson-Tait-Chetaev" and v.eigenvalue is None
    v = stability_from_structure(ring(k=4.0, c=0.0, Omega=1.0))
    assert v.kind == "marginally_stable" and v.bounded is True
    v = stability_from_structure((np.eye(3), np.zeros((3, 3)), -np.eye(3)))
    assert v.kind == "divergence" and "det K" in v.reason
    # circulatory: no theorem decides; gyroscopic stabilization (S < 0, D = 0): none either
    assert stability_from_structure(double_pendulum(P=4.0)) is None
    assert stability_from_structure(ring(k=4.0, c=0.0, Omega=3.0)) is None


def test_mass_matrix_positive_definite_only_within_rounding_is_said_in_figures_and_verdict():
    """M = [[1, 1], [1, 1 + 4 eps]] is positive definite as stored, but a perturbation
    of its rounding size makes it singular: one eigenvalue is about -1.9e14, with a bound beyond it."""
    eps = np.finfo(float).eps
    M = np.array([[1.0, 1.0], [1.0, 1.0 + 4 * eps]])
    sys = LinearizedSystem.from_matrices(M, 0.1 * np.eye(2), np.diag([1.0, 2.0]))
    m = pinlin.modal_analysis(sys)
    assert m.structure.mass == "positive_semidefinite" and not m.structure.definiteness_M.decided
    v = m.stability
    assert v.kind == "undecided" and v.bounded is None and v.margin == 0.0 and v.error == 1.0
    assert "M is positive definite only within rounding" in v.reason
    big = int(np.argmax(np.abs(m.eigenvalues)))
    assert abs(m.eigenvalues[big]) > 1e13 and m.error_bound[big] >= abs(m.eigenvalues[big])  # meaningless, said
    assert v.eigenvalue == m.eigenvalues[big]
    assert any("M is positive definite only within rounding" in note and "1 of the 4 eigenvalues" in note
               for note in m.notes)
    # the structure alone says the same, without the spectrum
    assert pinlin.spectral.stability_from_structure(sys).kind == "undecided"
    # a mass matrix of a near-massless link is positive definite beyond doubt relative to its diagonal
    tiny = LinearizedSystem.from_matrices(np.diag([1.0, 1e-17]), 0.1 * np.eye(2), np.diag([1.0, 2.0]))
    assert pinlin.modal_analysis(tiny).stability.kind == "asymptotically_stable"
