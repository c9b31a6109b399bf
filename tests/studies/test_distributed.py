"""sweep on a Dask cluster (LocalCluster, worker processes) and on Ray through RayExecutor.

The Dask part needs the ``distributed`` extra (``pip install 'pinlin[distributed]'``) and is skipped
without it; one two-worker cluster serves the module (about 5-10 s to start on two cores).  Ray is not a
dependency: RayExecutor is checked against a stand-in module with the three pieces of Ray's API it uses
(``ray.remote(fn)`` or ``ray.remote(**options)(fn)``, ``.remote(*args)`` and ``ObjectRef.future()``).
"""

import sys
import types
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import pinlin
from pinlin.errors import MissingDependencyError
from pinlin.studies import RayExecutor


def pendulum_stiffness(P, k2=2.0):
    """S and N of the paper's double pendulum at follower load P (module level: picklable for the workers)."""
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(
        robot, [pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", k2), pinlin.FollowerWrench("tip", force=(0, 0, P))]
    )
    sys_ = pinlin.linearize(scene, np.zeros(2))
    return np.stack([sys_.S, sys_.N])


def lowest_modes(P):
    """A pinlin result per point (its figures are taken on the worker); refuses negative loads."""
    if P < 0:
        raise pinlin.ParameterError("P", "must be >= 0")
    robot = pinlin.load_urdf_string(pinlin.double_pendulum_urdf())
    scene = pinlin.Scene(robot, [pinlin.JointSpring("joint1", 3.0), pinlin.JointSpring("joint2", 2.0),
                                 pinlin.FollowerWrench("tip", force=(0, 0, P))])
    return pinlin.modal_analysis(pinlin.linearize(scene, np.zeros(2)))


GRID = {"P": np.linspace(0.0, 10.0, 6), "k2": [1.0, 2.0]}


@pytest.fixture(scope="module")
def dask_client():
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster,
        distributed.Client(cluster) as client,
    ):
        yield client


def test_dask_cluster_sweep_equals_the_serial_one(dask_client):
    serial = pinlin.sweep(pendulum_stiffness, GRID)
    dask = pinlin.sweep(pendulum_stiffness, GRID, executor=dask_client.get_executor())
    assert_array_equal(dask.collect(), serial.collect())  # bitwise: same function, same arguments
    assert dask.points == serial.points and dask.shape == serial.shape == (6, 2)
    assert "ClientExecutor" in dask.method


def test_dask_cluster_keeps_figures_failures_and_reports_every_point(dask_client):
    seen = []
    grid = {"P": [0.0, -1.0, 4.0, 8.0]}
    serial = pinlin.sweep(lowest_modes, grid, on_error="record")
    dask = pinlin.sweep(lowest_modes, grid, executor=dask_client.get_executor(), on_error="record",
                        callback=lambda i, point, value: seen.append(i))
    assert sorted(seen) == [0, 1, 2, 3]
    assert dask.point_errors == serial.point_errors and dask.error == serial.error
    failure = dask.failures[0]
    assert failure.point == {"P": -1.0} and failure.exception.parameter == "P"
    assert_array_equal(dask.collect(lambda m: m.eigenvalues), serial.collect(lambda m: m.eigenvalues))
    with pytest.raises(pinlin.ParameterError, match="P: must be >= 0"):
        pinlin.sweep(lowest_modes, grid, executor=dask_client.get_executor())


class _FakeRay(types.ModuleType):
    """Ray's API as RayExecutor uses it, running tasks on a thread pool."""

    def __init__(self, pool):
        super().__init__("ray")
        self.pool, self.registered, self.options = pool, [], []

    def remote(self, *args, **options):
        if args:  # ray.remote(fn)
            return self._remote_function(args[0], {})
        return lambda fn: self._remote_function(fn, options)  # ray.remote(num_cpus=1)(fn)

    def _remote_function(self, fn, options):
        self.registered.append(fn)
        self.options.append(options)
        pool = self.pool

        class ObjectRef:
            def __init__(self, args, kwargs):
                self._future = pool.submit(fn, *args, **kwargs)

            def future(self):
                return self._future

        return types.SimpleNamespace(remote=lambda *a, **k: ObjectRef(a, k))


def test_ray_executor_through_rays_api(monkeypatch):
    with ThreadPoolExecutor(2) as pool:
        fake = _FakeRay(pool)
        monkeypatch.setitem(sys.modules, "ray", fake)
        executor = RayExecutor(num_cpus=1)
        result = pinlin.sweep(pendulum_stiffness, GRID, executor=executor)
    assert_array_equal(result.collect(), pinlin.sweep(pendulum_stiffness, GRID).collect())
    assert len(fake.registered) == 1 and fake.options == [{"num_cpus": 1}]  # one remote function, reused
    assert "RayExecutor" in result.method and repr(executor) == "RayExecutor(num_cpus=1)"


def test_ray_executor_without_ray(monkeypatch):
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray raises ImportError
    with pytest.raises(MissingDependencyError, match="RayExecutor needs Ray: pip install ray"):
        pinlin.sweep(pendulum_stiffness, {"P": [1.0]}, executor=RayExecutor())
