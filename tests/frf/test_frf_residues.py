"""Residues of H = L^-1 at roots of any multiplicity (paper Theorem 10.2).

Closed forms derived by hand (partial fractions of adj L / p), the spectral
module's Lancaster-normalized modes, and 50-digit mpmath inverses for the
"principal part removes the pole" checks.
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import inv_mp, random_system
from pinlin.frf import Residues, principal_part_residual

SQ2 = math.sqrt(2)
JORDAN = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])
J = np.array([[1.0, 1.0], [-1.0, -1.0]])


def _remainder_norms(sys, res, hs, phase=0.7):
    """||H(s) - sum_j R_j / (s - c)^j|| at s = c + h exp(i phase), H by mpmath at 50 digits."""
    out = []
    for h in hs:
        s = res.center + h * np.exp(1j * phase)
        out.append(np.linalg.norm(inv_mp(sys, s) - res.principal_part(s)))
    return np.array(out)


def test_critically_damped_oscillator():
    """2 x'' + 4 x' + 2 x: p = 2 (s + 1)^2, H = 1 / (2 (s + 1)^2): R_2 = 1/2, R_1 = 0."""
    sys = pinlin.LinearizedSystem.from_matrices([[2.0]], [[4.0]], [[2.0]])
    res = pinlin.residues(sys, -1.0)
    assert isinstance(res, Residues) and res.multiplicity == 2 and res.order == 2 and len(res) == 2
    assert_allclose(res[1], [[0.5]], rtol=1e-14)
    assert_allclose(res[0], [[0.0]], atol=1e-14)
    # H is exactly the principal part here; what is left is the residues' rounding over h^2
    assert_allclose(_remainder_norms(sys, res, [1e-1, 1e-2, 1e-3]), 0.0, atol=1e-9)
    assert res.error < 1e-13 and res.residual < 1e-14 and res.elapsed > 0


def test_critically_damped_mode_in_a_coupled_system():
    """M = I, C = Q diag(2, 3, 1) Q^T, K = Q diag(1, 1, 5) Q^T: mode 1 is critically damped at -1.

    H = Q diag(1/(s^2 + c_i s + k_i)) Q^T, so at -1 (double): R_2 = q_1 q_1^T, R_1 = 0 (the other
    modes, (s^2 + 3 s + 1) and (s^2 + s + 5), are analytic there).
    """
    Q, _ = np.linalg.qr(np.random.default_rng(9).standard_normal((3, 3)))
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(3), Q @ np.diag([2.0, 3.0, 1.0]) @ Q.T, Q @ np.diag([1.0, 1.0, 5.0]) @ Q.T)
    res = pinlin.residues(sys, -1.0)
    assert res.multiplicity == 2
    assert_allclose(res[1], np.outer(Q[:, 0], Q[:, 0]), rtol=0, atol=1e-12)
    assert_allclose(res[0], np.zeros((3, 3)), atol=1e-10)
    assert res.residual < 1e-12


def test_jordan_chain_of_length_two_closed_form():
    """M = I, K = [[3, 1], [-1, 1]]: p = (s^2 + 2)^2, adj L = [[s^2 + 1, -1], [1, s^2 + 3]].

    With q(s) = (s + i sqrt 2)^2 and lam0 = i sqrt 2:
    R_2 = adj(lam0) / q(lam0) = J / 8,
    R_1 = adj'(lam0) / q(lam0) - adj(lam0) q'(lam0) / q(lam0)^2 = -i sqrt2/4 I + i sqrt2/16 J,
    J = [[1, 1], [-1, -1]].
    """
    lam0 = 1j * SQ2
    res = pinlin.residues(JORDAN, lam0)
    assert res.multiplicity == 2 and res.order == 2
    assert_allclose(res[1], J / 8, rtol=0, atol=1e-14)
    assert_allclose(res[0], -1j * SQ2 / 4 * np.eye(2) + 1j * SQ2 / 16 * J, rtol=0, atol=1e-14)
    assert res.residual < 1e-14 and res.error < 1e-12


def test_principal_part_removes_the_pole():
    lam0 = 1j * SQ2
    res = pinlin.residues(JORDAN, lam0)
    # (below h ~ 1e-4 the float center, which cannot hold i sqrt 2 exactly, shows: 2 |R_2| u / h^3)
    hs = [1e-1, 1e-2, 1e-3, 1e-4]
    rem = _remainder_norms(JORDAN, res, hs)
    H = np.array([np.linalg.norm(inv_mp(JORDAN, res.center + h * np.exp(0.7j))) for h in hs])
    assert H[-1] > 1e7  # H itself blows up like h^-2 ...
    assert np.all(rem < 2 * rem[0])  # ... the remainder stays bounded
    assert abs(rem[-1] - rem[-2]) < 1e-3 * rem[0]  # and converges to ||E(lam0)||
    # dropping R_1 leaves a pole of order one: the remainder then grows like 1/h
    partial = [np.linalg.norm(inv_mp(JORDAN, lam0 + h) - res[1] / h**2) * h for h in (1e-3, 1e-4)]
    assert_allclose(partial, np.linalg.norm(res[0]), rtol=1e-2)


def test_jordan_chain_of_length_three_closed_form():
    """M = I, C = 0, K = 4 I + Nil (Nil the 3 x 3 shift): L = (s^2 + 4) I + Nil, p = (s^2 + 4)^3.

    H = I/q - Nil/q^2 + Nil^2/q^3 with q = u (u + b), u = s - 2i, b = 4i; expanding (1 + u/b)^-k:
    R_3 = Nil^2 / b^3, R_2 = -Nil / b^2 - 3 Nil^2 / b^4, R_1 = I / b + 2 Nil / b^3 + 6 Nil^2 / b^5.
    """
    nil = np.diag([1.0, 1.0], k=1)
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(3), None, 4 * np.eye(3) + nil)
    b = 4j
    res = pinlin.residues(sys, 2j)
    assert res.multiplicity == 3 and res.order == 3
    assert_allclose(res[2], nil @ nil / b**3, rtol=0, atol=1e-14)
    assert_allclose(res[1], -nil / b**2 - 3 * nil @ nil / b**4, rtol=0, atol=1e-14)
    assert_allclose(res[0], np.eye(3) / b + 2 * nil / b**3 + 6 * nil @ nil / b**5, rtol=0, atol=1e-14)
    assert res.residual < 1e-14


def test_jordan_root_given_inaccurately_is_recentred():
    res = pinlin.residues(JORDAN, 1j * SQ2 * (1 + 3e-8))
    assert abs(res.center - 1j * SQ2) < 1e-14
    assert_allclose(res[1], J / 8, rtol=0, atol=1e-13)


def test_simple_root_oscillator_closed_form():
    """x'' + 0.2 x' + 4 x: R_1 = 1 / (lam_1 - lam_2) at lam_1 = -0.1 + i sqrt(3.99)."""
    sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[0.2]], [[4.0]])
    lam1 = complex(-0.1, math.sqrt(3.99))
    res = pinlin.residues(sys, lam1)
    assert res.multiplicity == 1 and len(res) == 1
    assert_allclose(res[0][0, 0], 1 / (lam1 - lam1.conjugate()), rtol=1e-13)


def test_simple_roots_against_lancaster_modes():
    sys = random_system(np.random.default_rng(12), 4)
    modes = pinlin.modal_analysis(sys)
    for k in range(0, 8, 3):
        res = pinlin.residues(sys, modes.eigenvalues[k])
        ref = np.outer(modes.right[:, k], modes.left[:, k])
        assert_allclose(res[0], ref, rtol=0, atol=1e-11 * np.linalg.norm(ref))


def test_rigid_body_double_zero():
    """Two masses (1, 3) joined by a spring 2 and a damper 0.5: lam = 0 is double (rigid body).

    adj L(s) = [[3 s^2 + b, b], [b, s^2 + b]] with b = 0.5 s + 2, p = s^2 (3 s^2 + 4 b):
    R_2 = adj(0) / 8 = [[1, 1], [1, 1]] / 4, R_1 = d/ds [adj / (3 s^2 + 4 b)] at 0 = 0.
    """
    B = np.array([[1.0, -1.0], [-1.0, 1.0]])
    sys = pinlin.LinearizedSystem.from_matrices(np.diag([1.0, 3.0]), 0.5 * B, 2.0 * B)
    res = pinlin.residues(sys, 0.0)
    assert res.multiplicity == 2 and res.order == 2
    assert_allclose(res[1], np.ones((2, 2)) / 4, rtol=0, atol=1e-14)
    assert_allclose(res[0], np.zeros((2, 2)), atol=1e-13)


def test_semisimple_double_root_has_a_simple_pole():
    """M = K = I: H = I / (s^2 + 1), so at i: multiplicity 2, pole order 1, R_1 = I / 2i."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    res = pinlin.residues(sys, 1j)
    assert res.multiplicity == 2 and res.order == 1 and len(res) == 1
    assert_allclose(res[0], np.eye(2) / 2j, rtol=0, atol=1e-14)


def test_given_radius_agrees_with_automatic():
    auto = pinlin.residues(JORDAN, 1j * SQ2)
    fixed = pinlin.residues(JORDAN, 1j * SQ2, radius=0.3, n_points=128)
    assert fixed.radius == pytest.approx(0.3, rel=0.3)
    for a, b in zip(auto, fixed):
        assert_allclose(a, b, rtol=0, atol=1e-13)


def test_principal_part_residual_detects_wrong_residues():
    assert principal_part_residual(JORDAN, 1j * SQ2, [np.eye(2), J / 8]) > 0.1
    good = pinlin.residues(JORDAN, 1j * SQ2)
    assert principal_part_residual(JORDAN, good.center, list(good)) < 1e-14


def test_errors():
    with pytest.raises(pinlin.NotAnEigenvalueError, match="not an eigenvalue") as info:
        pinlin.residues(JORDAN, 0.5 + 1j)
    assert info.value.lam == 0.5 + 1j
    close = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.diag([1.0, (1 + 3e-5) ** 2]))
    with pytest.raises(pinlin.EigenvalueNotIsolatedError, match="not isolated") as info:
        pinlin.residues(close, 1j)
    assert info.value.outer < 1e-4
    merged = pinlin.residues(close, 1j + 1.5e-5j, cluster_tol=1e-4)  # a larger cluster takes both
    assert merged.multiplicity == 2
    assert_allclose(merged[0], np.eye(2) / 2j, rtol=0, atol=1e-4)  # the two simple poles' residues
    with pytest.raises(pinlin.NotAnEigenvalueError, match="no eigenvalue inside"):
        pinlin.residues(JORDAN, 0.5 + 1j, radius=0.1)
    with pytest.raises(pinlin.ParameterError, match="lam0"):
        pinlin.residues(JORDAN, complex(np.inf, 0))
    with pytest.raises(pinlin.ParameterError, match="n_points"):
        pinlin.residues(JORDAN, 1j * SQ2, n_points=63)
    with pytest.raises(pinlin.ParameterError, match="cluster_tol"):
        pinlin.residues(JORDAN, 1j * SQ2, cluster_tol=0.0)
    with pytest.raises(pinlin.ParameterError, match="radius"):
        pinlin.residues(JORDAN, 1j * SQ2, radius=-1.0)
    res = pinlin.residues(JORDAN, 1j * SQ2)
    with pytest.raises(pinlin.ParameterError, match="pole"):
        res.principal_part(res.center)


# ------------------------------------------------------------------ the error bound from both sides

#: x'' + x = 0: H(s) = 1 / (s^2 + 1), residue 1 / (2i) at lam = i; the other pole, -i, lies at distance 2.
OSCILLATOR = pinlin.LinearizedSystem.from_matrices(np.eye(1), None, np.eye(1))


@pytest.mark.parametrize("N", [8, 16])
@pytest.mark.parametrize("radius", [0.5, 1.0, 1.5])
def test_residue_error_bound_is_the_true_error_from_both_sides(N, radius):
    """The N-point rule's true error is |R_1 - 1/(2i)|; the reported bound is at least that and at most 1 %
    above it plus the rounding term (closed form: the error is (1/2) q^N / (1 - q^N), q = r/2, exactly
    q^(N/2) times the difference of the N/2- and N-point rules)."""
    res = pinlin.residues(OSCILLATOR, 1j, n_points=N, radius=radius)
    true = abs(res[0][0, 0] - 1 / 2j)
    # (the circle may be moved off a radius where the count is not yet an integer: RADIUS_FACTORS)
    q = res.radius / 2
    assert abs(res.radius / radius - 1) < 0.3
    assert true == pytest.approx(0.5 * q**N / (1 - q**N), rel=1e-9, abs=1e-15)
    rounding = np.finfo(float).eps * N**0.5 * res.radius * 10  # the rounding term's size for this tiny system
    assert res.errors[0] >= true
    assert res.errors[0] <= 1.01 * true + rounding
    assert "computed eigenvalues" in res.method


def test_eight_point_rule_of_issue_16_is_bounded():
    """Issue 16's counterexample: with 8 points on the automatic contour the former estimate fell below the
    true error; the bound does not."""
    res = pinlin.residues(OSCILLATOR, 1j, n_points=8)
    true = abs(res[0][0, 0] - 1 / 2j)
    assert res.errors[0] >= true and res.errors[0] <= 1.01 * true + 1e-15


def test_residue_bound_from_the_counts_when_the_eigenvalues_disagree(monkeypatch):
    """Without usable eigenvalues the geometry comes from the contour's counts: still a bound (looser)."""
    import importlib

    import pinlin.spectral as spectral

    module = importlib.import_module("pinlin.frf.residues")

    class NoEigenvalues:
        eigenvalues = np.array([5j, -5j])  # deliberately wrong: the count inside disagrees
        error_bound = np.zeros(2)

    monkeypatch.setattr(spectral, "modal_analysis", lambda sys: NoEigenvalues())
    res = pinlin.residues(OSCILLATOR, 1j, n_points=8)
    true = abs(res[0][0, 0] - 1 / 2j)
    assert "argument-principle counts" in res.method and res.errors[0] >= true
    x, how = module.aliasing_ratio(OSCILLATOR, 1j, res.radius, 8, 1, res.inner, res.radius * 2)
    assert "counts" in how and 0 < x <= 1
