"""The memory guard in front of every Pinocchio ``createData``.

``pin.Data`` keeps second-order derivative tensors of 32 nv^3 bytes (theory: equations):
4 GB at nv = 500.  Every ``createData`` in pinlin goes through :func:`check_memory`
first, so a model too large is refused with a clear error, never an out-of-memory kill.
"""

from __future__ import annotations

import math
import numbers
import os
import warnings

from ..errors import ModelTooLargeError, ParameterError

__all__ = ["pinocchio_data_bytes", "check_memory", "check_memory_limit", "available_memory", "format_bytes",
           "MEMORY_FRACTION"]

#: Share of the memory available now that one ``createData`` peak may take when no
#: ``memory_limit`` is given: the analyses' own workspaces are O(n^2), small beside it,
#: and the rest leaves room for the process and its neighbours.
MEMORY_FRACTION = 0.8


def pinocchio_data_bytes(nv: int) -> int:
    """Estimated peak bytes of one ``createData`` for a model with ``nv`` velocities.

    ``pin.Data`` keeps four nv x nv x nv tensors of doubles for the second-order
    derivatives (theory: equations): 32 nv^3 bytes.  While ``createData`` builds
    them it transiently holds about twice that (peak resident growth of a
    :class:`~pinlin.Scene` measured at 2.25x, 2.14x and 2.10x of 32 nv^3 for
    nv = 100, 150 and 200), so the estimate is 72 nv^3 plus the quadratic terms
    (Jacobians, mass matrix, derivative matrices) with a generous constant.
    """
    return 72 * nv**3 + 400 * nv**2 + 4_000_000


def available_memory() -> int | None:
    """Bytes of memory available now (Linux ``MemAvailable``, else free pages), or None."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_AVPHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        return None


def format_bytes(size: int) -> str:
    """``size`` bytes in the largest binary unit that keeps it at 1 or more (``3.81 MiB``, ``2.00 GiB``)."""
    for unit, scale in (("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if size >= scale:
            return f"{size / scale:.2f} {unit}"
    return f"{size} bytes"


def check_memory_limit(memory_limit) -> int | None:
    """A memory budget in bytes: a finite positive number (as int), or None for "what is available".

    Raises
    ------
    ParameterError
        Not a number (a bool, a string), not finite, or not positive: a budget of
        zero or less bytes allows nothing, and would only be reported later as
        "-0.00 GiB allowed".
    """
    if memory_limit is None:
        return None
    if isinstance(memory_limit, bool) or not isinstance(memory_limit, numbers.Real):
        raise ParameterError("memory_limit", f"expected a number of bytes or None, got {memory_limit!r}")
    if not (math.isfinite(memory_limit) and memory_limit >= 1):
        raise ParameterError("memory_limit", f"expected a finite positive number of bytes, got {memory_limit!r}")
    return int(memory_limit)


def check_memory(nv: int, memory_limit: int | None, what: str) -> None:
    """Refuse, before allocating, a model whose ``pin.Data`` would not fit.

    ``memory_limit`` in bytes; ``None`` allows :data:`MEMORY_FRACTION` of the
    memory available now for the peak of ``createData``.  When the available
    memory cannot be read the guard cannot decide: it says so with a
    ``ResourceWarning`` and lets the allocation go ahead.

    Raises
    ------
    ParameterError
        ``memory_limit`` is not None and not a finite positive number of bytes
        (:func:`check_memory_limit`).
    ModelTooLargeError
        The estimate :func:`pinocchio_data_bytes` exceeds the limit.
    """
    memory_limit = check_memory_limit(memory_limit)
    required = pinocchio_data_bytes(nv)
    if memory_limit is None:
        available = available_memory()
        if available is None:
            warnings.warn(
                f"{what}: the memory available cannot be read on this system, so the guard "
                f"cannot check that Pinocchio's data (about {format_bytes(required)} at its peak) "
                f"fit; pass memory_limit=... to check against a known budget",
                ResourceWarning,
                stacklevel=3,
            )
            return
        limit = int(MEMORY_FRACTION * available)
    else:
        limit = memory_limit
    if required > limit:
        raise ModelTooLargeError(
            f"{what}: nv = {nv} needs about {format_bytes(required)} while Pinocchio builds its "
            f"data (its second-order derivative tensors keep 32 nv^3 bytes and peak near twice "
            f"that), more than the "
            f"{format_bytes(limit)} allowed; lock joints (locked=...) to reduce nv or "
            f"raise memory_limit",
            required=required,
            available=limit,
        )
