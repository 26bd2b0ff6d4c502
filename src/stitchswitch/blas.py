"""One BLAS thread for the small banded LAPACK calls of the solvers.

A solve factors a banded matrix of a few hundred rows some 20-50 times; threads cannot speed
that up, but a multithreaded OpenBLAS whose threads spin while the machine is busy slows it
down by 40x and more (measured: a 10 ms solve took 200-800 ms with other processes running).
``one_thread()`` limits the BLAS thread pools for the duration of a block; the controller is
built once (its context costs about 0.04 ms), and the caller's own setting is restored after.
Inside a block of the same thread a nested ``one_thread()`` does nothing, so a loop over many
solves can hold the limit once instead of setting and restoring it for every solve.
The controller sees only the libraries loaded when it is built, so scipy's LAPACK (which the
solvers call, and which carries its own OpenBLAS) is loaded first.
"""
from __future__ import annotations

import threading
from contextlib import contextmanager
from functools import lru_cache

_held = threading.local()


@lru_cache(maxsize=1)
def _controller():
    import scipy.linalg  # noqa: F401  (loads scipy's own OpenBLAS before the controller looks)
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextmanager
def one_thread():
    if getattr(_held, "limited", False):
        yield
        return
    with _controller().limit(limits=1, user_api="blas"):
        _held.limited = True
        try:
            yield
        finally:
            _held.limited = False
