"""Bad inputs the fuzzer (tests/fuzz) found: each now gets a PinlinError naming what was wrong."""

import numpy as np
import pytest

import pinlin

CHECK = pinlin.LinearizedSystem.from_matrices(
    [[1.04333333333, 0.2325], [0.2325, 0.075]], 0.1 * np.eye(2), [[15.8511, 5.00725], [2.20725, 4.20725]]
)


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning", "ignore:invalid value:RuntimeWarning")
@pytest.mark.parametrize("call", [lambda: pinlin.adjugate(CHECK, 1e300), lambda: pinlin.adjugate_eigenvectors(CHECK, 1e300j)])
def test_adjugate_at_a_huge_point(call):
    with pytest.raises(pinlin.ComputationError, match="overflows double precision"):
        call()


def test_ragged_matrices_for_modal_analysis():
    with pytest.raises(pinlin.ParameterError, match=r"C: expected a real matrix of numbers \(rectangular\)"):
        pinlin.modal_analysis((np.eye(2), [[1.0], [2.0, 3.0]], np.eye(2)))


def test_check_free_response_of_strings():
    t = np.linspace(0, 1, 6)
    with pytest.raises(pinlin.ParameterError, match="x: expected numbers"):
        pinlin.check_free_response(CHECK, t, np.zeros((6, 2)).astype(str))


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning", "ignore:invalid value:RuntimeWarning")
@pytest.mark.parametrize(
    "x0, v0, t",
    [([0.0, 1.7976931348623157e308], [0.0, 0.0], [0.0]), ([0.0, 1.0], [0.0, 0.0], [-1e300]), ([0.0, 0.0], [0.0, 1e300], [0.0])],
)
def test_free_response_that_overflows(x0, v0, t):
    """These returned NaN values with error 0, or a NaN error."""
    with pytest.raises(pinlin.ComputationError, match="overflow"):
        pinlin.free_response(CHECK, x0, v0, t)


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning", "ignore:invalid value:RuntimeWarning")
def test_energy_budget_that_overflows():
    x = np.zeros((4, 2))
    x[3, 1] = 1e300
    with pytest.raises(pinlin.ComputationError, match="overflow"):
        pinlin.energy_budget(CHECK, np.linspace(0, 1, 4), x, x)


@pytest.mark.parametrize(
    "M, C, match",
    [(np.eye(2), [[1.0], [2.0, 3.0]], r"C: expected a real matrix of numbers \(rectangular\)"),
     (np.zeros((4, 3)), np.zeros((4, 3)), r"M: expected a square matrix, got shape \(4, 3\)")],
)
def test_from_matrices_of_bad_shape(M, C, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.LinearizedSystem.from_matrices(M, C, np.eye(2))


def test_ragged_configuration():
    scene = pinlin.Scene(pinlin.load_urdf_string(pinlin.double_pendulum_urdf()))
    with pytest.raises(pinlin.ConfigurationError, match="q must be an array of numbers"):
        pinlin.linearize(scene, [[1.0], [2.0, 3.0]])
