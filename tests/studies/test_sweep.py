"""pinlin.sweep: the same values with no executor, threads and processes; grid handling; errors."""

import io
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

import pinlin


def pendulum_stiffness(P, k2=2.0):
    """Stiffness and circulatory matrices of the paper's double pendulum at load P (module level: picklable)."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(
        robot, [pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", k2), pinlin.FollowerWrench("tip", force=(0, 0, P))]
    )
    sys = pinlin.linearize(scene, np.zeros(2))
    return np.stack([sys.S, sys.N])


def failing_above(P):
    if P > 1:
        raise pinlin.ParameterError("P", "too large")
    return P


def test_same_results_with_every_executor():
    grid = {"P": np.linspace(0.0, 10.0, 6), "k2": [1.0, 2.0]}
    plain = pinlin.sweep(pendulum_stiffness, grid)
    with ThreadPoolExecutor(2) as pool:
        threads = pinlin.sweep(pendulum_stiffness, grid, executor=pool)
    with ProcessPoolExecutor(2) as pool:
        processes = pinlin.sweep(pendulum_stiffness, grid, executor=pool)
    a = plain.collect()
    assert a.shape == (6, 2, 2, 2, 2)
    assert_array_equal(threads.collect(), a)
    assert_array_equal(processes.collect(), a)
    # the values themselves: N_theta[0, 1] = P l1 / 2 in URDF angles (SPEC 7.1)
    assert_allclose(a[:, 0, 1, 0, 1], np.linspace(0.0, 10.0, 6) * 0.7 / 2, rtol=1e-12, atol=1e-15)
    assert plain.points[1] == {"P": 0.0, "k2": 2.0}  # last name fastest
    assert_array_equal(plain.axes["P"], np.linspace(0.0, 10.0, 6))


def test_explicit_points_and_progress_bar():
    stream = io.StringIO()
    result = pinlin.sweep(pendulum_stiffness, [{"P": 1.0}, {"P": 2.0, "k2": 5.0}], progress=True, stream=stream)
    assert result.shape == (2,) and result.names == ("P", "k2")
    assert "2/2" in stream.getvalue()


def test_record_failures():
    result = pinlin.sweep(failing_above, {"P": [0.5, 2.0, 1.0]}, on_error="record")
    assert len(result.failures) == 1 and result.failures[0].point == {"P": 2.0}
    assert_allclose(result.collect(), [0.5, np.nan, 1.0])
    with pytest.raises(pinlin.ParameterError, match="too large"):
        pinlin.sweep(failing_above, {"P": [0.5, 2.0]})


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(function=failing_above, grid={}), "no parameters"),
        (dict(function=failing_above, grid={"P": []}), r"grid\['P'\]: has no values"),
        (dict(function=failing_above, grid={"P": 3.0}), "expected a sequence"),
        (dict(function=failing_above, grid=[1, 2]), r"grid\[0\]: expected a dict"),
        (dict(function=failing_above, grid={"P": [1]}, executor="pool"), "expected a concurrent.futures.Executor"),
        (dict(function=failing_above, grid={"P": [1]}, on_error="ignore"), "on_error"),
        (dict(function=3, grid={"P": [1]}), "expected a callable"),
    ],
)
def test_bad_arguments(kwargs, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.sweep(**kwargs)
