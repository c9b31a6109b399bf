"""The characteristic differential equation p(d/dt) x_i = 0 (paper Sec. 7).

Free responses are computed independently here, with scipy's matrix exponential
of the first-order state matrix A = [[0, I], [-M^-1 K, -M^-1 C]]; their exact
derivatives are A^k z(t).
"""

import numpy as np
import pytest
import scipy.linalg as sla
from numpy.testing import assert_allclose

import pinlin
from adjoint_reference import double_pendulum, random_system
from pinlin.adjoint import characteristic_differential_equation, check_free_response

JORDAN = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, [[3.0, 1.0], [-1.0, 1.0]])


def _state_matrix(sys):
    n = sys.n
    return np.block(
        [[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(sys.M, sys.K), -np.linalg.solve(sys.M, sys.C)]]
    )


def _free_response(sys, z0, t):
    """z(t_k) on a uniform grid: z_{k+1} = expm(A dt) z_k."""
    step = sla.expm(_state_matrix(sys) * (t[1] - t[0]))
    z = [np.asarray(z0, dtype=float)]
    for _ in t[1:]:
        z.append(step @ z[-1])
    return np.array(z)


@pytest.mark.parametrize("which", ["double_pendulum", "random", "jordan"])
def test_free_response_satisfies_the_equation(which):
    sys = {"double_pendulum": double_pendulum(), "random": random_system(np.random.default_rng(5), 3), "jordan": JORDAN}[which]
    rng = np.random.default_rng(6)
    t = np.linspace(0.0, 4.0, 241)
    z = _free_response(sys, rng.standard_normal(2 * sys.n), t)
    result = pinlin.check_free_response(sys, t, z[:, : sys.n])
    assert result.passed and result.max_defect < 1e-9
    with_modes = check_free_response(sys, t, z[:, : sys.n], roots=pinlin.modal_analysis(sys).eigenvalues)
    assert with_modes.max_defect < 1e-9 and with_modes.roots_source == "given"
    if which == "jordan":  # p = (lam^2 + 2)^2: basis exp(+-i sqrt2 t), t exp(+-i sqrt2 t)
        assert sorted(result.multiplicities) == [2, 2]


def test_velocity_also_satisfies_it():
    sys = double_pendulum()
    t = np.linspace(0.0, 3.0, 181)
    z = _free_response(sys, np.array([0.1, -0.2, 0.0, 0.3]), t)
    assert check_free_response(sys, t, z[:, 2:]).passed


def test_other_trajectories_fail():
    sys = double_pendulum()
    t = np.linspace(0.0, 4.0, 241)
    forced = np.column_stack([np.sin(2.0 * t), np.cos(0.5 * t)])
    bad = check_free_response(sys, t, forced)
    assert not bad.passed and bad.max_defect > 1e-2
    other = random_system(np.random.default_rng(7), 2)
    z = _free_response(other, np.array([1.0, 0.0, 0.0, 1.0]), t)
    assert check_free_response(sys, t, z[:, :2]).max_defect > 1e-3


def test_exact_derivatives_annihilated():
    """p(d/dt) x = [I 0] p(A) z = 0 by Cayley-Hamilton, since det(lam I - A) = p(lam) / det M."""
    sys = random_system(np.random.default_rng(8), 3)
    cde = characteristic_differential_equation(sys)
    assert cde.order == 6 and cde.coefficients.shape == (7,)
    A = _state_matrix(sys)
    t = np.linspace(0.0, 2.0, 11)
    z = _free_response(sys, np.arange(1.0, 7.0), t)
    derivatives = np.array([(np.linalg.matrix_power(A, k) @ z.T)[:3] for k in range(7)])
    assert np.max(cde.defect(derivatives)) < 1e-12
    # a function that is not an expol of these roots: x = t^7 (derivatives by hand, at t = 1)
    d7 = np.array([np.prod(np.arange(8 - k, 8)) for k in range(7)], dtype=float)  # 7!/(7-k)!
    assert cde.defect(d7) > 1e-3
    assert_allclose(cde.apply(d7), np.dot(cde.coefficients, d7), rtol=1e-15)


def test_bad_input():
    sys = double_pendulum()
    t = np.linspace(0.0, 1.0, 20)
    x = np.zeros((20, 2))
    with pytest.raises(pinlin.ParameterError, match="shape"):
        check_free_response(sys, t, np.zeros((20, 3)))
    with pytest.raises(pinlin.ParameterError, match="1-D"):
        check_free_response(sys, np.zeros((20, 1)), x)
    with pytest.raises(pinlin.ParameterError, match="increasing"):
        check_free_response(sys, t[::-1], x)
    with pytest.raises(pinlin.ParameterError, match="more than 2n"):
        check_free_response(sys, t[:4], x[:4])
    with pytest.raises(pinlin.ParameterError, match="finite"):
        check_free_response(sys, t, np.full((20, 2), np.nan))
    with pytest.raises(pinlin.ParameterError, match="4 finite roots"):
        check_free_response(sys, t, x, roots=[1.0, 2.0])
    with pytest.raises(pinlin.ParameterError, match="tol"):
        check_free_response(sys, t, x, defect_tol=-1.0)
    cde = characteristic_differential_equation(sys)
    with pytest.raises(pinlin.ParameterError, match="orders 0 ... 4"):
        cde.apply(np.zeros((3, 2)))
    with pytest.raises(pinlin.ParameterError, match="finite"):
        cde.defect(np.full(5, np.inf))


def test_tol_is_the_deprecated_spelling_of_defect_tol():
    sys = double_pendulum()
    t = np.linspace(0.0, 3.0, 181)
    z = _free_response(sys, np.array([0.1, -0.2, 0.0, 0.3]), t)
    new = check_free_response(sys, t, z[:, :2], defect_tol=1e-6)
    with pytest.warns(DeprecationWarning, match=r"check_free_response\(tol=\.\.\.\) is deprecated .* defect_tol"):
        old = check_free_response(sys, t, z[:, :2], tol=1e-6)
    assert old.passed and old.max_defect == new.max_defect and old.tol == new.tol == 1e-6
