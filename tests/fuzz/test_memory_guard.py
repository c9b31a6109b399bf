"""The memory guard's budget is validated: a negative one gave "-0.00 GiB allowed"."""

from __future__ import annotations

import pytest

import pinlin
from pinlin.model.memory import check_memory, check_memory_limit, format_bytes, pinocchio_data_bytes

URDF = pinlin.pendulum_chain_urdf(2)


@pytest.mark.parametrize(
    "limit, match",
    [
        (-1, "memory_limit: expected a finite positive number of bytes, got -1"),
        (0, "memory_limit: expected a finite positive number of bytes, got 0"),
        (0.5, "memory_limit: expected a finite positive number of bytes, got 0.5"),
        (float("nan"), "memory_limit: expected a finite positive number of bytes, got nan"),
        (float("inf"), "memory_limit: expected a finite positive number of bytes, got inf"),
        (-float("inf"), "memory_limit: expected a finite positive number of bytes, got -inf"),
        ("1e9", "memory_limit: expected a number of bytes or None, got '1e9'"),
        (True, "memory_limit: expected a number of bytes or None, got True"),
        ([1e9], r"memory_limit: expected a number of bytes or None, got \[1000000000.0\]"),
    ],
)
def test_bad_memory_limits_are_refused(limit, match):
    with pytest.raises(pinlin.ParameterError, match=match):
        check_memory_limit(limit)
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.load_urdf_string(URDF, memory_limit=limit)
    robot = pinlin.load_urdf_string(URDF)
    with pytest.raises(pinlin.ParameterError, match=match):
        pinlin.Scene(robot, [], memory_limit=limit)


def test_a_valid_limit_is_applied_and_reported():
    required = pinocchio_data_bytes(2)
    assert required == 72 * 8 + 400 * 4 + 4_000_000
    assert check_memory_limit(1e9) == 1_000_000_000 and check_memory_limit(None) is None
    check_memory(2, required, "exact fit")  # the estimate itself fits
    with pytest.raises(pinlin.ModelTooLargeError, match=r"needs about 3.82 MiB .* more than the 3.82 MiB allowed") as info:
        check_memory(2, required - 1, "one byte short")
    assert info.value.required == required and info.value.available == required - 1


def test_sizes_print_in_readable_units():
    assert [format_bytes(b) for b in (0, 1023, 1024, 3 * 2**20 + 2**19, 2**31)] == [
        "0 bytes", "1023 bytes", "1.00 KiB", "3.50 MiB", "2.00 GiB"]
