"""Eigenvalue sensitivities d lambda / dp (theory: boundaries).

References: the double pendulum's quadratic in mu = lam^2 (closed form, boundary_cases); a symmetric pencil
with a double eigenvalue (closed form lam = i sqrt(1 + p kappa_j)); central differences of eigenvalues on the
UR5 with an equilibrium that moves with a joint stiffness.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from boundary_cases import DP, double_pendulum, double_pendulum_dlam, double_pendulum_theta, undamped_loads
from numpy.testing import assert_allclose

import pinlin

T = np.array([[1.0, 0.0], [1.0, 1.0]])


def dp_derivative(P):
    """Exact dK/dP of the double pendulum in joint angles: K_phi(P) is affine with slope [[-l1, l1], [0, 0]]."""
    l1 = DP["l1"]
    dK = T.T @ np.array([[-l1, l1], [0.0, 0.0]]) @ T
    return np.zeros((2, 2)), np.zeros((2, 2)), dK


@pytest.mark.parametrize("P", [0.0, 4.0, 10.0, 15.0])
def test_double_pendulum_against_closed_form(P):
    """theory: double pendulum: d lam / dP from d mu / dP = -(b' mu + det K') / (2 det M mu + b), to 1e-10."""
    r = pinlin.eigenvalue_sensitivity(double_pendulum(), P, step=0.1)
    reference = np.array([double_pendulum_dlam(P, lam) for lam in r.eigenvalues])
    assert np.all(r.differentiable) and r.status == ("simple",) * 4
    assert_allclose(r.derivatives, reference, rtol=1e-10)
    # the reported errors are honest: they bound the actual ones
    assert np.all(np.abs(r.derivatives - reference) <= r.derivative_error)
    assert r.evaluations == 1 + 2 * pinlin.boundaries.RICHARDSON_LEVELS and r.analyses == 1


def test_exact_derivative_is_used_as_given():
    r = pinlin.eigenvalue_sensitivity(double_pendulum(), 10.0, derivative=dp_derivative)
    reference = np.array([double_pendulum_dlam(10.0, lam) for lam in r.eigenvalues])
    assert_allclose(r.derivatives, reference, rtol=1e-12)
    assert r.evaluations == 1 and "exact" in r.method
    assert_allclose(r.matrix_derivatives[2], dp_derivative(10.0)[2], rtol=0, atol=0)
    assert np.all(r.matrix_error <= 1e-15 * np.linalg.norm(dp_derivative(10.0)[2]))


def test_differences_of_an_affine_family_are_exact_to_rounding():
    """K affine in P: the first central difference is already exact, and the estimate says so."""
    r = pinlin.eigenvalue_sensitivity(double_pendulum(), 4.0)
    assert_allclose(r.matrix_derivatives[2], dp_derivative(4.0)[2], rtol=0, atol=1e-12)
    assert r.matrix_error[2] < 1e-11 and r.matrix_error[0] < 1e-12


def test_semisimple_double_eigenvalue():
    """M = I, K = I + p B: lam = +-i sqrt(1 + p kappa_j), kappa_j the eigenvalues of B; at p = 0 the double
    eigenvalues +-i are semisimple and d lam / dp = +-i kappa_j / 2 (the eigenvalues of the projected problem)."""
    B = np.array([[2.0, 1.0], [1.0, -1.0]])
    kappa = np.linalg.eigvalsh(B)

    def func(p):
        return pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2) + p * B)

    r = pinlin.eigenvalue_sensitivity(func, 0.0)  # p = 0: the default step is STEP_FRACTION in p's unit
    assert np.all(r.differentiable)
    assert all(s.startswith("semisimple (multiplicity 2)") for s in r.status)
    for sign in (1, -1):
        d = r.derivatives[sign * r.eigenvalues.imag > 0]
        assert_allclose(d[np.argsort(d.imag)], np.sort(sign * 0.5 * kappa) * 1j, rtol=1e-10, atol=1e-14)
    assert any("p = 0" in note for note in r.notes)  # the default step's unit is stated


def test_defective_eigenvalue_is_not_differentiable():
    """At the flutter load the double eigenvalue i omega_f is defective: no derivative, a Puiseux series
    lam - lam0 ~ +-c sqrt(P - P_f) with |c| = sqrt(|Delta'(P_f)|) / (4 det M omega_f) from the quadratic in mu."""
    P_f = undamped_loads(double_pendulum_theta)[0]
    r = pinlin.eigenvalue_sensitivity(double_pendulum(), P_f)
    assert not np.any(r.differentiable)
    assert np.all(np.isnan(r.derivatives))
    assert all("not differentiable (Puiseux" in s for s in r.status)
    assert np.isinf(r.error)
    assert len(r.puiseux) == 2 and all(entry["order"] == 2 for entry in r.puiseux)
    # closed form of the coefficient
    h = 1e-6
    import mpmath as mp

    def disc(P):
        M, K = double_pendulum_theta(mp.mpf(P))
        b = M[0, 0] * K[1, 1] + M[1, 1] * K[0, 0] - M[0, 1] * K[1, 0] - M[1, 0] * K[0, 1]
        return b**2 - 4 * (M[0, 0] * M[1, 1] - M[0, 1] ** 2) * (K[0, 0] * K[1, 1] - K[0, 1] * K[1, 0])

    M, _ = double_pendulum_theta(mp.mpf(P_f))
    det_M = float(M[0, 0] * M[1, 1] - M[0, 1] ** 2)
    slope = float((disc(P_f + h) - disc(P_f - h)) / (2 * h))  # Delta is quadratic in P: exact
    omega_f = abs(r.puiseux[0]["center"])
    expected = np.sqrt(abs(slope)) / (4 * det_M * omega_f)
    assert_allclose(abs(r.puiseux[0]["coefficient"]), expected, rtol=1e-6)
    # beyond P_f the eigenvalues leave the axis sideways: c real, Re lam ~ c sqrt(P - P_f)
    assert abs(r.puiseux[0]["coefficient"].imag) < 1e-6 * abs(r.puiseux[0]["coefficient"])
    dP = 1e-8
    lam = pinlin.modal_analysis(double_pendulum()(P_f + dP)).eigenvalues
    assert_allclose(lam.real.max(), expected * np.sqrt(dP), rtol=1e-3)


# ----------------------------------------------------------------------------- UR5: an equilibrium that moves

UR5_STIFFNESS = np.array([3e3, 3e3, 1.5e3, 3e2, 3e2, 3e2])  # soft enough for gravity to move the equilibrium
UR5_POSE = np.array([0.0, -np.pi / 4, np.pi / 2, 0.0, np.pi / 2, 0.0])


@pytest.fixture(scope="module")
def ur5():
    robot = pinlin.load_example("ur5")
    joints = robot.joint_names

    def scene(k2):
        k = UR5_STIFFNESS.copy()
        k[1] = k2
        elements = [pinlin.JointSpring(j, kj, rest=qj) for j, kj, qj in zip(joints, k, UR5_POSE)]
        elements += [pinlin.JointDamper(j, 1e-3 * kj) for j, kj in zip(joints, k)]
        return pinlin.Scene(robot, elements, gravity=(0.0, 0.0, -9.81))

    def func(k2):
        sc = scene(k2)
        return pinlin.linearize(sc, pinlin.find_equilibrium(sc, UR5_POSE).q)

    return scene, func


def test_ur5_against_central_differences_of_eigenvalues(ur5):
    """d lam / dk of the shoulder stiffness k against (lam(k + h) - lam(k - h)) / 2h, the equilibrium found
    again at each k (it sags less as k grows): agreement to 1e-6 of the largest derivative."""
    scene, func = ur5
    k0, h = UR5_STIFFNESS[1], 1e-4 * UR5_STIFFNESS[1]
    r = pinlin.eigenvalue_sensitivity(func, k0)
    plus, minus = (pinlin.modal_analysis(func(k0 + s)).eigenvalues for s in (h, -h))
    fd = (plus - minus) / (2 * h)
    scale = np.abs(r.derivatives).max()
    assert_allclose(r.derivatives, fd, rtol=1e-6, atol=1e-6 * scale)
    assert r.error < 1e-6


def test_ur5_equilibrium_shift_is_included(ur5):
    """K dq/dk = -dr/dk (theory: boundaries): the shift predicted from the residual equals the finite difference of the
    equilibria, and leaving it out (matrices at the fixed q0, balanced) changes the derivatives measurably."""
    scene, func = ur5
    k0, h = UR5_STIFFNESS[1], 1e-3 * UR5_STIFFNESS[1]
    q0 = pinlin.find_equilibrium(scene(k0), UR5_POSE).q
    sys = func(k0)
    dr = np.zeros(6)
    dr[1] = q0[1] - UR5_POSE[1]  # r = tau - Q_e, Q_e = -k (q - rest): dr/dk = q - rest on the shoulder
    dq = np.linalg.solve(sys.K, -dr)
    qp, qm = (pinlin.find_equilibrium(scene(k0 + s), UR5_POSE).q for s in (h, -h))
    # rtol: the difference's truncation (h/k)^2 = 1e-6 and the equilibria's own tolerance (1e-12 / h)
    assert_allclose((qp - qm) / (2 * h), dq, rtol=1e-5, atol=1e-9 * np.abs(dq).max())
    assert np.abs(dq).max() > 1e-7  # the equilibrium does move

    full = pinlin.eigenvalue_sensitivity(func, k0)
    fixed = pinlin.eigenvalue_sensitivity(lambda k: pinlin.linearize(scene(k), q0, balancing=True), k0)
    scale = np.abs(full.derivatives).max()
    assert np.abs(full.derivatives - fixed.derivatives).max() > 1e-4 * scale


# ----------------------------------------------------------------------------- result convention, bad input


def test_result_convention():
    r = pinlin.eigenvalue_sensitivity(double_pendulum(), 4.0)
    data = r.to_dict()
    assert list(data)[:4] == ["type", "method", "error", "elapsed"]
    assert "modes" not in data
    json.dumps(data, allow_nan=False)
    assert "EigenvalueSensitivity(p=4" in repr(r) and len(repr(r)) < 300
    assert isinstance(r.error, float) and 0 <= r.error < 1e-8
    assert not r.derivatives.flags.writeable


def _two(p):
    return pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.diag([1.0 + p, 2.0]))


def test_bad_input():
    with pytest.raises(pinlin.SystemFunctionError, match=r"func\(1\.0\) raised ZeroDivisionError") as info:
        pinlin.eigenvalue_sensitivity(lambda p: 1 / 0, 1.0)
    assert info.value.p == 1.0 and isinstance(info.value.__cause__, ZeroDivisionError)
    with pytest.raises(pinlin.SystemFunctionError, match="returned tuple; expected a pinlin.LinearizedSystem"):
        pinlin.eigenvalue_sensitivity(lambda p: (np.eye(2), None, np.eye(2)), 1.0)
    with pytest.raises(pinlin.SystemFunctionError, match="different sizes"):
        pinlin.eigenvalue_sensitivity(
            lambda p: _two(p) if p == 1.0 else pinlin.LinearizedSystem.from_matrices(np.eye(3)), 1.0)
    with pytest.raises(pinlin.SystemFunctionError, match=r"returned shape \(3, 3, 3\)"):
        pinlin.eigenvalue_sensitivity(_two, 1.0, derivative=lambda p: (np.eye(3),) * 3)
    with pytest.raises(pinlin.SystemFunctionError, match=r"derivative\(1\.0\) raised KeyError"):
        pinlin.eigenvalue_sensitivity(_two, 1.0, derivative=lambda p: {}["x"])
    with pytest.raises(pinlin.ParameterError, match="p: expected a finite number"):
        pinlin.eigenvalue_sensitivity(_two, np.nan)
    with pytest.raises(pinlin.ParameterError, match="step: expected a positive finite step"):
        pinlin.eigenvalue_sensitivity(_two, 1.0, step=-1.0)
    with pytest.raises(pinlin.ParameterError, match="levels: expected an integer >= 2"):
        pinlin.eigenvalue_sensitivity(_two, 1.0, levels=1)
    with pytest.raises(pinlin.ParameterError, match="func: expected a callable"):
        pinlin.eigenvalue_sensitivity("not a function", 1.0)
