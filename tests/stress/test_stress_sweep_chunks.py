"""Chunked sweeps: several points per submitted task, results identical to a serial sweep.

Placed with the stress tests because it runs process pools; the sweep's own tests
(progress, Dask) are in tests/studies.
"""

from __future__ import annotations

import math
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

import pinlin
from pinlin.studies.sweep import CHUNKS_PER_WORKER, chunk_size_for


def modal_point(k):
    """A picklable point: the spring-mass chain of stiffness k, its eigenvalues and verdict."""
    n = 4
    K = k * (2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1))
    modes = pinlin.modal_analysis(pinlin.LinearizedSystem.from_matrices(np.eye(n), 0.01 * K, K))
    return modes.eigenvalues, modes.stability.kind


def refuse_above(P):
    if P > 0.5:
        raise pinlin.ParameterError("P", f"{P} is beyond the load the scene is defined for")
    return 2 * P


def test_chunk_size_from_points_and_workers():
    with ThreadPoolExecutor(2) as pool:
        assert chunk_size_for(5, pool) == 1  # short sweeps keep one point per task (progress point by point)
        assert chunk_size_for(400, pool) == math.ceil(400 / (2 * CHUNKS_PER_WORKER))
        assert chunk_size_for(400, pool, 7) == 7
        for bad in (0, -1, 2.5, True, "3"):
            with pytest.raises(pinlin.ParameterError, match="chunk_size: expected a positive integer"):
                chunk_size_for(400, pool, bad)


def test_chunked_process_sweep_equals_serial():
    ks = list(np.linspace(1.0, 50.0, 64))
    serial = pinlin.sweep(modal_point, {"k": ks}, progress=False)
    seen = []
    with ProcessPoolExecutor(2) as pool:
        par = pinlin.sweep(modal_point, {"k": ks}, executor=pool, progress=False,
                           callback=lambda i, point, value: seen.append(i))
    assert "in chunks of 4 points" in par.method
    assert sorted(seen) == list(range(len(ks)))  # every point reported once, with its own index
    for (lam_a, kind_a), (lam_b, kind_b) in zip(serial.values, par.values):
        assert np.array_equal(lam_a, lam_b) and kind_a == kind_b  # bitwise: the same calls on the same data
    # each point's run time is measured where it ran, inside its chunk
    assert len(par.point_elapsed) == len(ks) and all(t > 0 for t in par.point_elapsed)


def test_chunked_failures_recorded_or_raised_in_grid_order():
    P = list(np.linspace(0.0, 1.0, 40))
    with ThreadPoolExecutor(2) as pool:
        rec = pinlin.sweep(refuse_above, {"P": P}, executor=pool, on_error="record", progress=False, chunk_size=6)
        assert [isinstance(v, pinlin.SweepFailure) for v in rec.values] == [p > 0.5 for p in P]
        assert rec.values[:3] == [0.0, 2 * P[1], 2 * P[2]]
        with pytest.raises(pinlin.ParameterError, match=f"P: {P[20]} is beyond"):
            pinlin.sweep(refuse_above, {"P": P}, executor=pool, progress=False, chunk_size=6)
