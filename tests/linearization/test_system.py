"""LinearizedSystem: a frozen, validated value."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import pinlin


def test_from_matrices_splits_exactly():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(4, 4))
    M = A @ A.T + 4 * np.eye(4)
    C = rng.normal(size=(4, 4))
    K = rng.normal(size=(4, 4))
    sys = pinlin.LinearizedSystem.from_matrices(M, C, K)
    assert_allclose(sys.D + sys.G, C, rtol=0, atol=1e-15)
    assert_allclose(sys.S + sys.N, K, rtol=0, atol=1e-15)
    assert_allclose(sys.D, sys.D.T, rtol=0, atol=0)
    assert_allclose(sys.G, -sys.G.T, rtol=0, atol=0)
    assert sys.n == 4 and sys.dof_names == ("x1", "x2", "x3", "x4")
    lam = 0.3 - 1.2j
    assert_allclose(sys.dynamic_stiffness(lam), lam**2 * M + lam * C + K, rtol=1e-14)
    assert sys.dynamic_stiffness(np.array([1.0, 2.0])).shape == (2, 4, 4)


def test_frozen_and_read_only():
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    with pytest.raises(ValueError, match="read-only"):
        sys.M[0, 0] = 5.0
    with pytest.raises(AttributeError):
        sys.M = np.eye(2)
    assert sys.nonzero == ("M", "S")
    assert repr(sys) == "LinearizedSystem(n=2, dofs=('x1', 'x2'), nonzero=M+S, method='matrices', error=0.0e+00)"


def test_replace_validates_again():
    sys = pinlin.LinearizedSystem.from_matrices(np.eye(2), None, np.eye(2))
    heavier = sys.replace(M=2 * np.eye(2))
    assert_allclose(heavier.M, 2 * np.eye(2))
    with pytest.raises(pinlin.SingularMassError):
        sys.replace(M=np.zeros((2, 2)))


@pytest.mark.parametrize(
    "kwargs, error, match",
    [
        (dict(M=np.eye(2), K=np.eye(3)), pinlin.ParameterError, r"K: expected shape \(2, 2\) like M"),
        (dict(M=np.ones(3)), pinlin.ParameterError, "M: expected a square matrix"),
        (dict(M=np.array([[1.0, np.nan], [np.nan, 1.0]])), pinlin.ParameterError, "M: has non-finite"),
        (dict(M=np.array([[1.0, 0.5], [0.0, 1.0]])), pinlin.ParameterError, "M: must be symmetric"),
        (dict(M=np.diag([1.0, -1.0])), pinlin.SingularMassError, "not positive definite"),
        (dict(M=np.diag([1.0, 0.0])), pinlin.SingularMassError, r"coordinates \['x2'\]"),
        (dict(M=np.eye(2), dof_names=("a",)), pinlin.ParameterError, "dof_names: expected 2 names"),
        (dict(M=np.eye(2), dof_names=("a", "a")), pinlin.ParameterError, "unique"),
        (dict(M=np.zeros((0, 0))), pinlin.ParameterError, "no coordinates"),
    ],
)
def test_from_matrices_bad_input(kwargs, error, match):
    with pytest.raises(error, match=match):
        pinlin.LinearizedSystem.from_matrices(**kwargs)


def test_direct_constructor_checks_skewness():
    I = np.eye(2)
    with pytest.raises(pinlin.ParameterError, match="G: must be skew-symmetric"):
        pinlin.LinearizedSystem(I, 0 * I, I, I, 0 * I)
    with pytest.raises(pinlin.ParameterError, match="is_zero|expected one of"):
        pinlin.LinearizedSystem.from_matrices(I).is_zero("Q")
