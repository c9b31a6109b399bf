"""pinlin.sweep: the same values and figures with no executor, threads and processes; grid handling; errors."""

import io
import json
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
    # the values themselves: N_theta[0, 1] = P l1 / 2 in URDF angles (theory: double pendulum)
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


def tracked_rotation(angle):
    """Module level (picklable): two steps whose shapes turn by ``angle``; MAC = cos(angle)^2 (a pinlin result)."""
    c, s = np.cos(angle), np.sin(angle)
    lam = np.array([[1j, 2j], [1j, 2j]])
    shapes = np.array([np.eye(2), [[c, -s], [s, c]]], dtype=complex)
    return pinlin.studies.track_modes(lam, shapes)


def test_error_method_and_figures_do_not_depend_on_the_executor():
    """sweep.error is the largest headline error of the values: here 1 - MAC = sin(angle)^2 (closed form)."""
    grid = {"angle": [0.0, 0.3, 0.1]}
    plain = pinlin.sweep(tracked_rotation, grid)
    assert_allclose(plain.point_errors, np.sin([0.0, 0.3, 0.1]) ** 2, rtol=1e-12, atol=1e-15)
    assert_allclose(plain.error, np.sin(0.3) ** 2, rtol=1e-12)
    assert "tracked_rotation" in plain.method and "3 points" in plain.method and "in this process" in plain.method
    assert len(plain.point_elapsed) == 3 and all(e >= 0 for e in plain.point_elapsed)
    with ThreadPoolExecutor(2) as pool:
        threads = pinlin.sweep(tracked_rotation, grid, executor=pool)
    with ProcessPoolExecutor(2) as pool:
        processes = pinlin.sweep(tracked_rotation, grid, executor=pool)
    for other, where in [(threads, "ThreadPoolExecutor"), (processes, "ProcessPoolExecutor")]:
        assert other.point_errors == plain.point_errors and other.error == plain.error
        assert where in other.method
        assert_array_equal(other.collect(lambda r: r.eigenvalues), plain.collect(lambda r: r.eigenvalues))


def test_error_is_none_for_plain_values():
    result = pinlin.sweep(failing_above, {"P": [0.5, 1.0]})
    assert result.point_errors == (None, None) and result.error is None
    assert "error=none" in repr(result)


def test_result_convention_of_a_sweep():
    result = pinlin.sweep(failing_above, {"P": [0.5, 2.0, 1.0]}, on_error="record")
    text = repr(result)
    assert text.startswith("SweepResult(3 points, P[3], 1 failed") and len(text.splitlines()) == 1
    data = json.loads(json.dumps(result.to_dict(), allow_nan=False))
    assert data["type"] == "SweepResult" and data["failures"] == 1 and data["error"] is None
    assert data["values"][0] == 0.5 and data["values"][1]["type"] == "SweepFailure"
    assert data["values"][1]["exception"] == {"type": "ParameterError", "message": "P: too large"}
    assert data["points"] == [{"P": 0.5}, {"P": 2.0}, {"P": 1.0}] and data["shape"] == [3]


def test_failures_survive_a_process_pool():
    """A PinlinError whose constructor takes more than a message is rebuilt from its attributes."""
    with ProcessPoolExecutor(2) as pool:
        result = pinlin.sweep(failing_above, {"P": [0.5, 2.0]}, executor=pool, on_error="record")
        failure = result.failures[0]
        assert isinstance(failure.exception, pinlin.ParameterError) and failure.exception.parameter == "P"
        assert str(failure.exception) == "P: too large"
        assert failure.error is None and failure.elapsed >= 0
        assert failure.method == "failing_above(**point) raised ParameterError"
        with pytest.raises(pinlin.ParameterError, match="P: too large") as info:
            pinlin.sweep(failing_above, {"P": [0.5, 2.0, 3.0]}, executor=pool)
    assert info.value.parameter == "P"


def test_the_first_failure_in_grid_order_is_raised():
    def fails_differently(P):
        raise pinlin.ParameterError("P", f"bad value {P}")

    with ThreadPoolExecutor(2) as pool, pytest.raises(pinlin.ParameterError, match="bad value 1"):
        pinlin.sweep(fails_differently, {"P": [1, 2, 3]}, executor=pool)
