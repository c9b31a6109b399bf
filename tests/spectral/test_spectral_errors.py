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
        ({"definiteness_tol": 0}, "definiteness_tol"),
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


def test_mass_rcond_is_adjustable():
    from pinlin.spectral import as_problem

    M = np.diag([1.0, 1e-10])
    assert as_problem((M, Z2, I2)).n == 2
    with pytest.raises(SingularMassError, match="mass_rcond 1e-08"):
        as_problem((M, Z2, I2), mass_rcond=1e-8)
    with pytest.raises(ParameterError, match="mass_rcond: expected a finite positive number"):
        as_problem((M, Z2, I2), mass_rcond=0)
