"""Executors for engines that do not offer a ``concurrent.futures.Executor`` of their own.
Dask (``Client.get_executor()``), mpi4py (``MPIPoolExecutor``) and the standard library do;
Ray does not, and takes this small adapter."""

from __future__ import annotations

from concurrent.futures import Executor, Future


class RayExecutor(Executor):
    """Runs each submitted call as a Ray task; ``options`` go to ``ray.remote`` (``num_cpus``,
    resources). Ray must be initialised (``ray.init()``) first."""

    def __init__(self, **options):
        import ray

        self._ray = ray
        self._options = options
        self._remote = {}

    def submit(self, fn, /, *args, **kwargs) -> Future:
        remote = self._remote.get(fn)
        if remote is None:
            remote = self._ray.remote(**self._options)(fn) if self._options else self._ray.remote(fn)
            self._remote[fn] = remote
        return remote.remote(*args, **kwargs).future()


__all__ = ["RayExecutor"]
