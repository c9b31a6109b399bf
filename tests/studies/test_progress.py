"""sweep's progress in completion order: callbacks, the text bar and tqdm never wait behind a slow early point."""

import io
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import pinlin
from pinlin.errors import MissingDependencyError
from pinlin.studies import progress as progress_module

#: Seconds a blocked point waits for its release before failing the test (the release comes in milliseconds).
RELEASE_TIMEOUT = 30.0
#: Seconds each point after a failure takes: 36 of them would take 1.8 s, the cancellation comes in microseconds.
LATER_POINT_SECONDS = 0.05


def test_callback_receives_points_in_completion_order():
    """Point 0 blocks until the callback has seen every other point: reporting in grid order would deadlock
    (and fail on the timeout); reporting in completion order sees 1, 2, 3, 4 and then 0."""
    release = threading.Event()
    stream = io.StringIO()
    seen, bar_when_released = [], []

    def slow_first(i):
        if i == 0 and not release.wait(RELEASE_TIMEOUT):
            raise pinlin.ComputationError("point 0 was never released: progress waited behind it")
        return 10 * i

    def callback(index, point, value):
        seen.append(index)
        assert point == {"i": index} and value == 10 * index
        if len(seen) == 4:
            bar_when_released.append(stream.getvalue())
            release.set()

    with ThreadPoolExecutor(2) as pool:
        result = pinlin.sweep(slow_first, {"i": range(5)}, executor=pool, callback=callback, progress="text",
                              stream=stream)
    assert seen == [1, 2, 3, 4, 0]
    assert "4/5" in bar_when_released[0] and "5/5" not in bar_when_released[0]  # the bar moved past point 0
    assert "5/5" in stream.getvalue()
    assert result.values == [0, 10, 20, 30, 40]  # values in grid order all the same


def test_serial_callback_and_recorded_failures():
    seen = []
    result = pinlin.sweep(
        failing_above, {"P": [0.5, 2.0, 1.0]}, on_error="record", callback=lambda i, p, v: seen.append((i, v)),
    )
    assert [i for i, _ in seen] == [0, 1, 2]
    assert seen[0][1] == 0.5 and isinstance(seen[1][1], pinlin.SweepFailure) and seen[1][1] is result.values[1]


def failing_above(P):
    if P > 1:
        raise pinlin.ParameterError("P", "too large")
    return P


def test_the_first_failure_in_grid_order_wins_even_when_it_finishes_last():
    """Point 3 fails first; point 1 fails later (it waits for point 3): the error raised is point 1's, and the
    points after point 3 are cancelled instead of run."""
    three_failed = threading.Event()
    ran = []

    def point(i):
        ran.append(i)
        if i == 1:
            three_failed.wait(RELEASE_TIMEOUT)
            raise pinlin.ParameterError("i", "bad 1")
        if i == 3:
            three_failed.set()
            raise pinlin.ParameterError("i", "bad 3")
        time.sleep(LATER_POINT_SECONDS)
        return i

    with ThreadPoolExecutor(2) as pool, pytest.raises(pinlin.ParameterError, match="bad 1"):
        pinlin.sweep(point, {"i": range(40)}, executor=pool, progress=False)
    assert len(ran) < 40  # those after the failure were cancelled (the few started meanwhile ran)


def test_a_failing_callback_stops_the_sweep():
    def callback(index, point, value):
        raise pinlin.ParameterError("callback", f"refused point {index}")

    with ThreadPoolExecutor(2) as pool, pytest.raises(pinlin.ParameterError, match="refused point"):
        pinlin.sweep(failing_above, {"P": [0.1, 0.2, 0.3]}, executor=pool, callback=callback)
    with pytest.raises(pinlin.ParameterError, match="callback: expected a callable"):
        pinlin.sweep(failing_above, {"P": [0.1]}, callback="print")


def test_tqdm_when_installed_and_the_text_bar_without(monkeypatch):
    pytest.importorskip("tqdm")
    stream = io.StringIO()
    pinlin.sweep(failing_above, {"P": np.linspace(0, 1, 5)}, progress=True, stream=stream)
    assert "5/5" in stream.getvalue() and "point/s" in stream.getvalue() and "sweep [" not in stream.getvalue()
    monkeypatch.setattr(progress_module, "_tqdm", lambda: None)  # as if tqdm were not installed
    stream = io.StringIO()
    pinlin.sweep(failing_above, {"P": np.linspace(0, 1, 5)}, progress=True, stream=stream)
    assert "sweep [" in stream.getvalue() and "5/5" in stream.getvalue()
    with pytest.raises(MissingDependencyError, match="needs tqdm"):
        pinlin.sweep(failing_above, {"P": [0.1]}, progress="tqdm")


def test_default_bar_only_for_long_sweeps_and_bad_progress():
    stream = io.StringIO()
    n = progress_module.PROGRESS_MIN_POINTS
    pinlin.sweep(failing_above, {"P": np.zeros(n)}, stream=stream)
    assert stream.getvalue() == ""
    pinlin.sweep(failing_above, {"P": np.zeros(n + 1)}, stream=stream)
    assert f"{n + 1}/{n + 1}" in stream.getvalue()
    with pytest.raises(pinlin.ParameterError, match="progress: expected None, True, False or one of"):
        pinlin.sweep(failing_above, {"P": [0.1]}, progress="fancy")
