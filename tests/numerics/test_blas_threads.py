"""One BLAS thread for small kernels: the limit is set, counted and restored; results unchanged."""

from __future__ import annotations

import threading

import numpy as np
from threadpoolctl import threadpool_limits

import pinlin
import pinlin.numerics.threads as threads
from pinlin.numerics.threads import SMALL_KERNEL_ORDER, blas_threads, small_kernels


def test_small_kernels_run_on_one_thread_and_restore_the_count():
    with threadpool_limits(2, user_api="blas"):
        assert set(blas_threads()) == {2}
        with small_kernels(10):
            assert set(blas_threads()) == {1}
            with small_kernels(10):  # nested: still one, and the outer exit restores
                assert set(blas_threads()) == {1}
            assert set(blas_threads()) == {1}
        assert set(blas_threads()) == {2}
        with small_kernels(SMALL_KERNEL_ORDER + 1):  # a large problem keeps its threads
            assert set(blas_threads()) == {2}


def test_other_threads_leave_the_count_alone():
    # OpenBLAS ignores a raise requested from another thread after the main thread lowered the count:
    # the limit is applied on the main thread only, so a worker's block neither lowers nor strands it
    seen = {}

    def worker():
        with small_kernels(10):
            seen["inside"] = blas_threads()

    with threadpool_limits(2, user_api="blas"):
        t = threading.Thread(target=worker)
        t.start()
        t.join(5)
        assert set(seen["inside"]) == {2}
        assert set(blas_threads()) == {2}


def test_modal_analysis_is_bitwise_the_same_with_and_without_the_limit(monkeypatch):
    robot = pinlin.load_urdf_string(pinlin.pendulum_chain_urdf(30, length=1.0, mass=1.0))
    el = [pinlin.JointSpring(f"joint{i + 1}", 5.0) for i in range(30)]
    el += [pinlin.JointDamper(f"joint{i + 1}", 0.1 * (i + 1)) for i in range(30)]
    el.append(pinlin.FollowerWrench("tip", force=(0.0, 0.0, 0.3)))
    sys = pinlin.linearize(pinlin.Scene(robot, el), robot.neutral())
    with threadpool_limits(2, user_api="blas"):
        limited = pinlin.modal_analysis(sys)
        monkeypatch.setattr(threads, "SMALL_KERNEL_ORDER", -1)
        threaded = pinlin.modal_analysis(sys)
    assert limited.method.name == threaded.method.name == "general"
    for name in ("eigenvalues", "backward_error", "error_bound", "condition", "right", "left"):
        np.testing.assert_array_equal(getattr(limited, name), getattr(threaded, name), err_msg=name)
