"""Every bad input to the spectral module raises a PinlinError subclass naming the problem."""

from __future__ import annotations

import numpy as np
import pytest

import pinlin
from pinlin import LinearizedSystem
from pinlin.errors import InputError, ParameterError, PinlinError, SingularMassError

I2, Z2 = np.eye(2), np.zeros((2, 2))


@pytest.mark.parametrize(
    "source, error, match",
    [
        ((I2, Z2), ParameterError, "expected a LinearizedSystem or a tuple \\(M, C, K\\), got 2 items"),
        ("M C K", ParameterError, "got str"),
        (I2, ParameterError, "got ndarray"),
        ((np.ones(2), Z2, I2), ParameterError, "M: expected a square matrix, got shape \\(2,\\)"),
        ((np.ones((2, 3)), Z2, I2), ParameterError, "M: expected a square matrix, got shape \\(2, 3\\)"),
        ((I2, np.zeros((3, 3)), I2), ParameterError, "C: expected shape \\(2, 2\\) like M, got \\(3, 3\\)"),
        ((I2, Z2, np.eye(3)), ParameterError, "K: expected shape \\(2, 2\\) like M"),
        ((np.zeros((0, 0)),) * 3, ParameterError, "at least one coordinate"),
        ((I2, np.array([[np.nan, 0], [0, 0]]), I2), ParameterError, "C: has non-finite entries \\(first at index \\(0, 0\\)\\)"),
        ((I2, Z2, np.array([[1, np.inf], [0, 1]])), ParameterError, "K: has non-finite entries"),
        ((I2 * (1 + 1j), Z2, I2), ParameterError, "M: expected a real matrix, got complex"),
        (([["a", "b"], ["c", "d"]], Z2, I2), ParameterError, "M: expected a real matrix of numbers"),
        ((np.array([[1.0, 1.0], [1.0, 1.0]]), Z2, I2), SingularMassError, "M is singular"),
        ((np.diag([1.0, 1e-17]), Z2, I2), SingularMassError, "mass_rcond"),
    ],
)
def test_bad_systems(source, error, match):
    with pytest.raises(error, match=match) as info:
        pinlin.modal_analysis(source)
    assert isinstance(info.value, PinlinError) and isinstance(info.value, InputError)
    with pytest.raises(error, match=match):
        pinlin.jordan_chains(source, 0.0)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"cluster_tol": 0.0}, "cluster_tol: expected a finite positive number"),
        ({"cluster_tol": -1e-3}, "cluster_tol: expected a finite positive number"),
        ({"cluster_tol": float("nan")}, "cluster_tol: expected a finite positive number"),
        ({"cluster_tol": 1.0}, "cluster_tol: expected a number below 1"),
        ({"rank_tol": "small"}, "rank_tol: expected a positive number"),
        ({"structure_tol": float("inf")}, "structure_tol: expected a finite positive number"),
        ({"uncertainty": -1e-3}, r"uncertainty: expected a relative uncertainty in \[0, 1\), got -0.001"),
        ({"uncertainty": 1.0}, r"uncertainty: expected a relative uncertainty in \[0, 1\), got 1.0"),
        ({"uncertainty": float("nan")}, r"uncertainty: expected a relative uncertainty in \[0, 1\)"),
        ({"uncertainty": "rounding"}, r"uncertainty: expected a relative uncertainty in \[0, 1\), got 'rounding'"),
        ({"eigh_tol": -1.0}, "eigh_tol"),
        ({"safety": 0.5}, "safety: expected a factor >= 1"),
        ({"safety": None}, "safety: expected a positive number"),
        ({"scaling": "yes"}, "scaling: expected True or False"),
    ],
)
def test_bad_tolerances(kwargs, match):
    sys = LinearizedSystem.from_matrices(I2, Z2, I2)
    with pytest.raises(ParameterError, match=match):
        pinlin.modal_analysis(sys, **kwargs)


def test_definiteness_tol_is_the_deprecated_name_of_uncertainty():
    sys = LinearizedSystem.from_matrices(I2, Z2, np.diag([1.0, 1e-6]))
    with pytest.warns(DeprecationWarning, match=r"definiteness_tol=\.\.\.\) is deprecated: pass uncertainty"):
        old = pinlin.modal_analysis(sys, definiteness_tol=1e-5)
    assert old.tolerances["uncertainty"] == 1e-5
    assert old.structure.stiffness == pinlin.modal_analysis(sys, uncertainty=1e-5).structure.stiffness
    assert old.structure.stiffness == "positive_semidefinite"  # 1e-6 < 1e-5 ||S||: undecided
    with pytest.raises(ParameterError, match="uncertainty: expected a relative uncertainty"):
        pinlin.spectral.stability_from_structure(sys, uncertainty=2.0)


def test_mass_rcond_is_adjustable():
    from pinlin.spectral import as_problem

    M = np.diag([1.0, 1e-10])
    assert as_problem((M, Z2, I2)).n == 2
    with pytest.raises(SingularMassError, match="mass_rcond 1e-08"):
        as_problem((M, Z2, I2), mass_rcond=1e-8)
    with pytest.raises(ParameterError, match="mass_rcond: expected a finite positive number"):
        as_problem((M, Z2, I2), mass_rcond=0)


def test_complex_input_is_refused_on_both_paths():
    """Numpy would drop the imaginary part with a ComplexWarning."""
    with pytest.raises(ParameterError, match="K: expected a real matrix, got complex entries"):
        LinearizedSystem.from_matrices(I2, Z2, I2 * (1 + 1e-3j))
    with pytest.raises(ParameterError, match="C: expected a real matrix, got complex entries"):
        LinearizedSystem.from_matrices(I2, [[0j, 0], [0, 0]], I2)
    with pytest.raises(ParameterError, match="K: expected a real matrix, got complex entries"):
        pinlin.modal_analysis((I2, Z2, I2 * 1j))


def test_tuple_input_is_the_general_problem_and_says_so():
    """A non-symmetric M: refused as a mechanical system, accepted as the general QEP of theory: spectrum."""
    M = np.array([[1.0, 0.5], [0.0, 1.0]])
    with pytest.raises(ParameterError, match="M: must be symmetric"):
        LinearizedSystem.from_matrices(M, Z2, I2)
    m = pinlin.modal_analysis((M, Z2, I2))
    assert m.method == "general" and "no symmetry required or used" in m.method.reason
    assert m.structure.damping is None and m.constants is None  # no mechanical split
    assert m.stability.theorem is None  # no theorem of theory: stability for general coefficients
    # eigenvalues of the general problem: det(lam^2 M + I) = (lam^2 + 1)^2 (M is unit upper triangular)
    assert np.allclose(np.sort_complex(m.eigenvalues), [-1j, -1j, 1j, 1j], atol=1e-7)
