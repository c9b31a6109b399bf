"""pinlin.sweep's last crashes: names, executors, huge grids, futures that never finish."""

from concurrent.futures import Executor, Future, ThreadPoolExecutor

import pytest

import pinlin
from pinlin.studies import MAX_POINTS, SweepTimeoutError
from pinlin.studies.grid import GridPoints


def double(x, y=0.0):
    return 2 * x + y


class NotFutures(Executor):
    """An executor whose submit returns the value itself (as some wrappers do), not a Future."""

    def submit(self, fn, /, *args, **kwargs):
        return fn(*args, **kwargs)


class NeverFinishes(Executor):
    """An executor whose futures never complete (a lost cluster worker)."""

    def __init__(self):
        self.futures = []

    def submit(self, fn, /, *args, **kwargs):
        future = Future()
        self.futures.append(future)
        return future


class FinishesFirst(Executor):
    """Runs the first ``k`` submissions; the others never complete."""

    def __init__(self, k):
        self.k, self.count = k, 0

    def submit(self, fn, /, *args, **kwargs):
        future = Future()
        self.count += 1
        if self.count <= self.k:
            future.set_result(fn(*args, **kwargs))
        return future


def test_a_grid_key_that_is_not_a_string_is_refused():
    with pytest.raises(pinlin.ParameterError, match=r"grid: expected parameter names that are strings .* got 1"):
        pinlin.sweep(double, {1: [1.0, 2.0]})
    with pytest.raises(pinlin.ParameterError, match=r"grid: expected parameter names that are strings"):
        pinlin.sweep(double, [{"x": 1.0}, {2: 1.0}])


def test_an_executor_whose_submit_returns_no_future_is_refused():
    with pytest.raises(pinlin.ParameterError, match=r"executor: its submit\(\) returned .* expected a concurrent.futures.Future"):
        pinlin.sweep(double, {"x": [1.0, 2.0]}, executor=NotFutures(), chunk_size=1)


def test_a_huge_grid_is_refused_before_any_point_is_built():
    axis = list(range(1000))
    with pytest.raises(pinlin.ParameterError, match=rf"grid: has 1000000000 points, more than max_points={MAX_POINTS}"):
        pinlin.sweep(double, {"x": axis, "y": axis, "z": axis})
    with pytest.raises(pinlin.ParameterError, match=r"grid: has 3 points, more than max_points=2"):
        pinlin.sweep(double, [{"x": 1.0}, {"x": 2.0}, {"x": 3.0}], max_points=2)


def test_the_point_cap_can_be_raised_or_lifted():
    from pinlin.report.sweep import MAX_POINTS as CLI_MAX_POINTS

    assert MAX_POINTS == CLI_MAX_POINTS  # the CLI's cap is the API's default
    grid = {"x": list(range(120)), "y": list(range(100))}
    assert len(pinlin.sweep(double, grid, max_points=None).values) == 12_000
    assert pinlin.sweep(double, grid, max_points=12_000).values[-1] == 2 * 119 + 99
    for bad in (0, -1, 2.5, True, "10"):
        with pytest.raises(pinlin.ParameterError, match=r"max_points: expected a positive integer or None"):
            pinlin.sweep(double, {"x": [1.0]}, max_points=bad)


def test_grid_points_are_made_on_demand_in_product_order():
    points = GridPoints(("x", "y"), ([1, 2, 3], [10, 20]))
    assert len(points) == 6
    assert list(points) == [{"x": x, "y": y} for x in (1, 2, 3) for y in (10, 20)]
    assert points[-1] == {"x": 3, "y": 20}
    assert points[1:3] == [{"x": 1, "y": 20}, {"x": 2, "y": 10}]
    huge = GridPoints(("a", "b", "c"), (range(1000),) * 3)  # 10^9 points, none built
    assert len(huge) == 10**9 and huge[10**9 - 1] == {"a": 999, "b": 999, "c": 999}
    with pytest.raises(IndexError, match="point 6 of a grid of 6"):
        points[6]


def test_futures_that_never_finish_time_out_naming_the_points():
    executor = NeverFinishes()
    with pytest.raises(SweepTimeoutError, match=r"timeout: 2 points not finished after 0.05 s \(cancelled unless already running\): "
                       r"#0 \{'x': 1.0\}, #1 \{'x': 2.0\}") as info:
        pinlin.sweep(double, {"x": [1.0, 2.0]}, executor=executor, timeout=0.05, chunk_size=1)
    assert info.value.pending == (0, 1) and info.value.points == ({"x": 1.0}, {"x": 2.0})
    assert isinstance(info.value, pinlin.ComputationError) and isinstance(info.value, TimeoutError)
    assert all(f.cancelled() for f in executor.futures)


def test_a_timeout_names_only_the_unfinished_points_also_in_chunks():
    with pytest.raises(SweepTimeoutError, match=r"2 points not finished .* #2 \{'x': 3.0\}, #3 \{'x': 4.0\}") as info:
        pinlin.sweep(double, {"x": [1.0, 2.0, 3.0, 4.0]}, executor=FinishesFirst(1), timeout=0.05, chunk_size=2)
    assert info.value.pending == (2, 3)


def test_a_timeout_long_enough_changes_nothing():
    with ThreadPoolExecutor(2) as pool:
        result = pinlin.sweep(double, {"x": [1.0, 2.0]}, executor=pool, timeout=60)
    assert result.values == [2.0, 4.0]


@pytest.mark.parametrize("bad", [0, -1.0, float("nan"), float("inf"), True, "5"])
def test_a_bad_timeout_is_refused(bad):
    with pytest.raises(pinlin.ParameterError, match=r"timeout: expected a positive number of seconds or None"):
        pinlin.sweep(double, {"x": [1.0]}, timeout=bad)
