"""Ray as a sweep executor: a ``concurrent.futures.Executor`` over Ray tasks, without a Ray dependency.

:func:`~pinlin.sweep` runs on anything with ``submit`` returning
``concurrent.futures.Future``.  Dask offers one (``Client.get_executor()``);
Ray offers futures (``ObjectRef.future()``) but no executor, so this adapter
makes each submitted call a Ray task::

    import ray
    ray.init()                                   # or ray.init(address="auto") on a cluster
    result = pinlin.sweep(analyse, grid, executor=pinlin.studies.RayExecutor(num_cpus=1))

Ray is imported on the first ``submit``, never by pinlin itself; the function
and its points must be picklable, as for a process pool.
"""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import Executor, Future
from typing import Any

from ..extras import import_ray

__all__ = ["RayExecutor"]


class RayExecutor(Executor):
    """Submit calls as Ray tasks; each returns the task's ``concurrent.futures.Future``.

    Parameters
    ----------
    **options
        Passed to ``ray.remote`` for every task (``num_cpus=1``, ``max_retries=0``, ...).

    Notes
    -----
    Ray must be initialized (``ray.init()``) before the first ``submit``, or Ray
    starts a local instance itself.  ``shutdown`` cancels nothing and leaves
    Ray running: the Ray session belongs to the caller.

    Examples
    --------
    Building one needs no Ray (it is imported on the first ``submit``):

    >>> executor = pinlin.studies.RayExecutor(num_cpus=1, max_retries=0)
    >>> executor
    RayExecutor(num_cpus=1, max_retries=0)
    """

    def __init__(self, **options: Any):
        self.options = options
        self._remote: dict[Callable, Any] = {}

    def submit(self, fn: Callable, /, *args: Any, **kwargs: Any) -> Future:
        """Run ``fn(*args, **kwargs)`` as a Ray task.

        Parameters
        ----------
        fn : callable
            A picklable function (a module-level one).
        *args, **kwargs
            Its arguments.

        Returns
        -------
        concurrent.futures.Future
            ``ObjectRef.future()`` of the task.

        Raises
        ------
        MissingDependencyError
            Ray is not installed.
        """
        ray = import_ray()
        remote = self._remote.get(fn)
        if remote is None:
            remote = self._remote[fn] = ray.remote(**self.options)(fn) if self.options else ray.remote(fn)
        return remote.remote(*args, **kwargs).future()

    def __repr__(self) -> str:
        return f"RayExecutor({', '.join(f'{k}={v!r}' for k, v in self.options.items())})"
