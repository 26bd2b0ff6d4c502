"""One small interface for embarrassingly parallel work.

``make_executor(workers, scheduler)`` returns an object with ``map(func, items) -> list`` (in
the order of ``items``, whatever the scheduling, so parallel runs are bit-identical to serial
ones) and ``close()``; it is also a context manager and usable as the ``workers`` map of
``scipy.optimize.differential_evolution``.

* ``SerialExecutor``: in this process (``workers == 1``).
* ``LocalExecutor``: a persistent pool of local processes. Each worker limits BLAS to one
  thread: the solver's banded factorizations are tiny, and OpenBLAS threads fighting over two
  cores made a parallel map 5x slower (81 s against 15 s for the default grid, measured).
* ``DaskExecutor``: a Dask distributed cluster, given its scheduler address
  (``--scheduler tcp://HOST:PORT``). Start one with ``dask scheduler`` on a head node and
  ``dask worker tcp://HOST:8786 --nthreads 1`` on each machine (each with this package
  installed); the functions and data are sent by pickle.
"""
from __future__ import annotations

import multiprocessing
import os
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor

from stitchswitch.errors import InvalidInputError


def _limit_threads() -> None:
    from threadpoolctl import threadpool_limits

    threadpool_limits(1)


def default_workers() -> int:
    return max(1, os.cpu_count() or 1)


class SerialExecutor:
    def imap(self, func: Callable, items):
        """Results one by one, in order."""
        return (func(item) for item in items)

    def map(self, func: Callable, items) -> list:
        return list(self.imap(func, items))

    def __call__(self, func: Callable, items) -> list:     # scipy's map-like protocol
        return self.map(func, items)

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class LocalExecutor(SerialExecutor):
    def __init__(self, workers: int):
        # fork where the platform has it: no re-import of the caller's __main__ (scripts need
        # no main guard) and the compiled kernels are inherited
        methods = multiprocessing.get_all_start_methods()
        ctx = multiprocessing.get_context("fork" if "fork" in methods else "spawn")
        self._pool = ProcessPoolExecutor(max_workers=workers, mp_context=ctx,
                                         initializer=_limit_threads)

    def imap(self, func: Callable, items):
        return self._pool.map(func, list(items))

    def close(self) -> None:
        self._pool.shutdown()


class DaskExecutor(SerialExecutor):
    def __init__(self, scheduler: str):
        from distributed import Client

        try:
            self._client = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError) as exc:
            raise InvalidInputError(f"scheduler: cannot connect to {scheduler!r} ({exc})") from None

    def imap(self, func: Callable, items):
        futures = self._client.map(func, list(items), pure=False)
        return iter(self._client.gather(futures))

    def close(self) -> None:
        self._client.close()


def make_executor(workers: int = 1, scheduler: str | None = None) -> SerialExecutor:
    """Serial, local processes, or Dask (when ``scheduler`` is given)."""
    if scheduler:
        if not scheduler.startswith(("tcp://", "tls://", "inproc://", "ws://", "wss://")):
            raise InvalidInputError(f"scheduler: {scheduler!r} is not an address like tcp://HOST:PORT")
        return DaskExecutor(scheduler)
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InvalidInputError(f"workers: {workers!r} must be a positive integer")
    return SerialExecutor() if workers == 1 else LocalExecutor(workers)


def run_all(func: Callable, items: Sequence, workers: int = 1, progress: Callable | None = None,
            scheduler: str | None = None) -> list:
    """[func(item) for item in items] in order; ``progress(n_done)`` after each result."""
    items = list(items)
    if type(workers) is int and workers > len(items):       # no idle processes
        workers = max(len(items), 1)
    results = []
    with make_executor(workers, scheduler) as ex:
        for result in ex.imap(func, items):
            results.append(result)
            if progress:
                progress(len(results))
    return results
