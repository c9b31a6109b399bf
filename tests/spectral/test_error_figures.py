"""Every error figure of the spectral results, tested from both sides (theory: spectrum, stability, error figures).

A figure checked only from above ("error <= tol") passes when it is reported as
0.  Here each figure is compared with its true value -- exact residuals of the
returned vectors in mpmath, closed forms, and the eigenvalue shift of an actual
worst-case perturbation -- so that it must be positive where the truth is and
within a stated factor of it:

- backward errors eta: within eps/2 (absolute) of the exact residual of the returned pair;
- condition numbers kappa: the theory: spectrum check values, to their printed digits;
- error bounds: their slope (the sensitivity) is the shift of the worst perturbation, within 2 %;
  the defective bound is the closed-form split of a critically damped oscillator, within 1e-12;
- the stability margin times the safety factor: the first-order distance of the worst perturbation
  to a change of verdict, within 5 % (and the verdict's bound is the safety factor times the bound);
- Cluster.error, JordanChains.error, ModeConstants.residual: the definitions, evaluated exactly.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin
from pinlin.numerics import chain_residuals
from pinlin.spectral.accuracy import defective_scale
from pinlin.spectral.problem import as_problem
from pinlin.spectral.qualitative import mode_constants
from spectral_cases import A0, A1, A2, cantilever, double_pendulum

EPS = np.finfo(float).eps
CHECK_EIGENVALUES = np.array([-3.8513, -0.59217 + 0.80280j, -0.59217 - 0.80280j, 0.52326 + 0.62251j,
                             0.52326 - 0.62251j, 0.78909])
CHECK_KAPPA = np.array([2.3092, 0.70275, 0.70275, 2.7013, 2.7013, 2.0144])


def _mp(A):
    return mp.matrix([[mp.mpc(complex(z).real, complex(z).imag) for z in row] for row in np.atleast_2d(A)])


def _fro(A):
    return mp.sqrt(sum(abs(A[i, j]) ** 2 for i in range(A.rows) for j in range(A.cols)))


def mp_backward_errors(M, C, K, lam, X, dps=40) -> np.ndarray:
    """eta of the stored pairs (lam_k, X[:, k]), evaluated exactly (40 digits) from the definition."""
    with mp.workdps(dps):
        Mm, Cm, Km = _mp(M), _mp(C), _mp(K)
        nM, nC, nK = _fro(Mm), _fro(Cm), _fro(Km)
        out = []
        for k in range(len(lam)):
            z = mp.mpc(complex(lam[k]).real, complex(lam[k]).imag)
            x = _mp(X[:, k][:, None])
            r = z * z * (Mm * x) + z * (Cm * x) + Km * x
            out.append(float(_fro(r) / ((abs(z) ** 2 * nM + abs(z) * nC + nK) * _fro(x))))
        return np.array(out)


@pytest.mark.parametrize("scaling", [True, False])
def test_backward_errors_are_the_exact_residuals_of_the_returned_pairs(scaling):
    """Unscaled, the damped beam's pairs have eta up to 1e-13: reporting 0, or a bound, would fail."""
    sys = cantilever(ne=6, c=50.0)
    m = pinlin.modal_analysis(sys, scaling=scaling)
    exact = mp_backward_errors(sys.M, sys.C, sys.K, m.eigenvalues, np.asarray(m.right))
    assert np.all(np.abs(m.backward_error - exact) <= EPS / 2)
    big = exact > 100 * EPS
    assert_allclose(m.backward_error[big], exact[big], rtol=1e-3)
    if not scaling:
        assert np.sum(big) >= 4  # the comparison above is not vacuous
    assert m.error == np.max(m.backward_error) and m.error >= np.max(exact) - EPS / 2 > 0


def test_condition_numbers_of_the_result_are_the_spec_check_values():
    m = pinlin.modal_analysis((A2, A1, A0))
    order = [int(np.argmin(np.abs(m.eigenvalues - v))) for v in CHECK_EIGENVALUES]
    assert_allclose(m.eigenvalues[order], CHECK_EIGENVALUES, atol=1e-4)
    assert_allclose(m.condition[order], CHECK_KAPPA, rtol=2e-4)


def _worst_perturbation(sys, lam, x, y, delta, direction=1.0):
    """The complex (M, C, K) + (dM, dC, dK) with ||dA|| = delta ||A|| that moves lam the most to first order.

    With E = t conj(y) x^H / (||y|| ||x||) and phases making lam^2 dM + lam dC + dK = delta w(lam) E (w the
    weight of eta): y^T dL x = t delta w ||x|| ||y||, so d lam = -y^T dL x / y^T L' x has modulus
    delta * sensitivity (theory: spectrum); the phase t = -direction y^T L' x / |y^T L' x| points it along
    ``direction``.
    """
    deriv = y @ ((2 * lam * sys.M + sys.C) @ x)
    t = -direction * deriv / abs(deriv)
    E = t * np.outer(np.conj(y), np.conj(x)) / (np.linalg.norm(y) * np.linalg.norm(x))
    ph = lam / abs(lam) if lam != 0 else 1.0
    dM = delta * np.linalg.norm(sys.M) * np.conj(ph) ** 2 * E
    dC = delta * np.linalg.norm(sys.C) * np.conj(ph) * E
    dK = delta * np.linalg.norm(sys.K) * E
    return sys.M + dM, sys.C + dC, sys.K + dK


def _eigenvalues(M, C, K):
    n = M.shape[0]
    Mi = np.linalg.inv(M)
    return np.linalg.eigvals(np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ K, -Mi @ C]]))


def _sensitivity(m):
    """The slope of the error bound: error_bound = max(eta, eps) * sensitivity (simple eigenvalues)."""
    return m.error_bound / np.maximum(m.backward_error, EPS)


def test_error_bound_slope_is_the_shift_of_the_worst_perturbation():
    sys = double_pendulum(P=4.0, c=0.1)
    m = pinlin.modal_analysis(sys)
    assert m.is_simple
    sens = _sensitivity(m)
    delta = 1e-9
    for k in range(len(m)):
        lam = m.eigenvalues[k]
        # the sign of the shift: d lam = -y^T dL x / y^T L' x, pushed both ways; take the larger move
        shifted = _eigenvalues(*_worst_perturbation(sys, lam, m.right[:, k], m.left[:, k], delta))
        move = np.min(np.abs(shifted - lam))
        assert 0.98 * delta * sens[k] <= move <= 1.02 * delta * sens[k]


def test_defective_bound_is_the_split_of_the_critically_damped_oscillator():
    """lam^2 + 2 w lam + w^2: K -> K (1 + d) splits the double root -w into -w +- i w sqrt(d); that change
    has the normwise backward error eta = w^2 d / w(-w) = d / 4, and the bound scale * eta^(1/2) is the split."""
    w = 3.0
    sys = pinlin.LinearizedSystem.from_matrices([[1.0]], [[2 * w]], [[w * w]])
    problem = as_problem(sys)
    scale = defective_scale(problem, -w, 2)
    for d in (1e-12, 1e-8, 1e-4):
        eta = w * w * d / (w * w + 2 * w * w + w * w)
        assert_allclose(scale * np.sqrt(eta), w * np.sqrt(d), rtol=1e-12)
        perturbed = pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices([[1.0]], [[2 * w]], [[w * w * (1 + d)]]))
        assert_allclose(np.abs(perturbed.eigenvalues + w), w * np.sqrt(d), rtol=1e-3)
    m = pinlin.modal_analysis(sys)
    (c,) = m.clusters
    # the reported bound: the members' spread plus scale * sqrt(max(eta, eps)); covers their true error
    spread = np.max(np.abs(m.eigenvalues - c.center))
    assert_allclose(m.error_bound, spread + scale * np.sqrt(max(np.max(m.backward_error), EPS)), rtol=1e-12)
    assert np.all(np.abs(m.eigenvalues + w) <= m.error_bound)


def test_the_verdict_uses_the_safety_factor_it_reports():
    sys = double_pendulum(P=4.0, c=0.1)
    for safety in (1.0, 10.0, 1e3):
        m = pinlin.modal_analysis(sys, safety=safety)
        v = m.stability
        k = int(np.flatnonzero(m.eigenvalues == v.eigenvalue)[0])
        assert v.safety == safety and v.error_bound == safety * m.error_bound[k]
    # and it decides with it: a safety factor that brings the bounds to the axis leaves the verdict undecided
    re = np.abs(m.eigenvalues.real)
    huge = 2 * np.max(re / m.error_bound)
    assert pinlin.modal_analysis(sys, safety=huge).stability.kind == "undecided"
    assert pinlin.modal_analysis(sys, safety=0.5 * np.min(re / m.error_bound)).stability.kind != "undecided"


def test_stability_margin_is_the_distance_of_the_worst_perturbation():
    """The lightly damped double pendulum with its follower load, decided by its eigenvalues: the margin
    times the safety factor is (to first order) the smallest worst-case perturbation that brings an
    eigenvalue to the axis; a perturbation 5 % larger does, 5 % smaller does not."""
    sys = double_pendulum(P=4.0, c=0.001)
    m = pinlin.modal_analysis(sys)
    v = m.stability
    assert v.kind == "asymptotically_stable" and v.theorem is None
    sens = _sensitivity(m)
    eta = np.maximum(m.backward_error, EPS)
    each = np.abs(m.eigenvalues.real) / (v.safety * sens) - eta  # where (eta + delta) sens safety = |Re lam|
    assert each.min() * (1 - 1e-4) <= v.margin <= each.min()
    k = int(np.argmin(each))
    lam = m.eigenvalues[k]
    distance = abs(lam.real) / sens[k]  # the first-order worst-case distance to the axis
    assert_allclose(v.safety * (v.margin + eta[k]), distance, rtol=1e-4)
    for factor, crosses in ((1.05, True), (0.95, False)):
        shifted = _eigenvalues(*_worst_perturbation(sys, lam, m.right[:, k], m.left[:, k], factor * distance))
        image = shifted[np.argmin(np.abs(shifted - (lam + factor * abs(lam.real))))]  # pushed towards +Re
        assert abs(image - (lam + factor * abs(lam.real))) <= 0.01 * abs(lam.real)  # first order holds
        assert (image.real >= 0) == crosses


def test_cluster_error_is_positive_where_the_members_differ():
    """The double root i sqrt 2 of M = I, K = [[3, 1], [-1, 1]] (one chain of length 2): the general
    path splits it by rounding into members about 1e-11 apart; the squared path finds it exactly."""
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])
    for method, split in (("general", True), ("squared", False)):
        m = pinlin.modal_analysis(sys, method=method)
        gamma = m.scaling.gamma if m.scaling is not None else pinlin.spectral.as_problem(sys).scaling.gamma
        for c in m.clusters:
            members = m.eigenvalues[list(c.indices)]
            true = np.max(np.abs(members - c.center)) / max(abs(c.center), gamma)
            assert c.error == true and (c.error > 0) == split == (np.ptp(members.real) > 0)


def test_chain_residuals_are_the_exact_residuals_from_both_sides():
    """chain_residuals (behind JordanChains.error and AdjugateChain.error) on a deliberately wrong chain,
    against the residuals of the same vectors evaluated exactly."""
    K = np.array([[3.0, 1.0], [-1.0, 1.0]])  # lam = i sqrt 2: one chain of length 2
    lam0 = 1j * np.sqrt(2.0)
    ch = pinlin.jordan_chains((np.eye(2), np.zeros((2, 2)), K), lam0)
    x0, x1 = ch[0]
    rng = np.random.default_rng(5)
    bad = [x0 + 1e-7 * rng.standard_normal(2), x1 + 1e-6 * rng.standard_normal(2)]
    got = chain_residuals(np.eye(2), np.zeros((2, 2)), K, lam0, bad)
    with mp.workdps(40):
        z = mp.mpc(lam0.real, lam0.imag)
        L = z * z * mp.eye(2) + _mp(K)
        dL = 2 * z * mp.eye(2)
        v0, v1 = _mp(bad[0][:, None]), _mp(bad[1][:, None])
        w0 = abs(z) ** 2 * mp.sqrt(2) + _fro(_mp(K))
        w1 = 2 * abs(z) * mp.sqrt(2)
        exact = [float(_fro(L * v0) / (w0 * _fro(v0))),
                 float(_fro(L * v1 + dL * v0) / (w0 * _fro(v1) + w1 * _fro(v0)))]
    assert_allclose(got, exact, rtol=1e-8)
    # the returned chain's own figure: its exact residual, to the rounding of the evaluation
    with mp.workdps(40):
        v0 = _mp(x0[:, None])
        exact0 = float(_fro(L * v0) / (w0 * _fro(v0)))
    assert abs(ch.residuals[0][0] - exact0) <= EPS and ch.error == max(ch.residuals[0])


def test_mode_constants_residual_from_both_sides():
    """m lam^2 + (d + i g) lam + (k + i n) = 0 (theory: stability), residual of a deliberately shifted lam."""
    sys = double_pendulum(P=4.0, c=0.1)
    m = pinlin.modal_analysis(sys)
    X = np.asarray(m.right)
    lam = m.eigenvalues + 1e-6
    mc = mode_constants(lam, X, sys.M @ X, sys.C @ X, sys.K @ X)
    exact = []
    with mp.workdps(40):
        for k in range(len(lam)):
            x = _mp(X[:, k][:, None])
            xh = x.H
            mm = (xh * _mp(sys.M) * x)[0].real
            c = (xh * _mp(sys.C) * x)[0] / mm
            kk = (xh * _mp(sys.K) * x)[0] / mm
            z = mp.mpc(lam[k].real, lam[k].imag)
            num = abs(z * z + c * z + kk)
            den = abs(z) ** 2 + abs(z) * (abs(c.real) + abs(c.imag)) + abs(kk.real) + abs(kk.imag)
            exact.append(float(num / den))
    assert_allclose(mc.residual, exact, rtol=1e-6)
    assert np.all(mc.residual > 0)
