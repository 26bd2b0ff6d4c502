"""Native libraries' console output, kept off stdout.

HiGHS (through cvxpy) prints a copyright banner with C stdio on every solve, whatever the
solver's verbosity option says. Written to file descriptor 1, it would corrupt a command's
``--json`` output, where stdout must carry the JSON and nothing else. ``to_logger(log)`` points
descriptor 1 at a temporary file for the duration of a block, flushes the C library's buffers
before restoring it, and passes each captured line to ``log.debug`` (shown with ``-v``).
"""
from __future__ import annotations

import ctypes
import os
import sys
import tempfile
from contextlib import contextmanager

_LIBC = ctypes.CDLL(None)


@contextmanager
def to_logger(log):
    """Capture what native code writes to stdout inside the block and log it at debug level."""
    sys.stdout.flush()
    saved = os.dup(1)
    with tempfile.TemporaryFile() as sink:
        os.dup2(sink.fileno(), 1)
        try:
            yield
        finally:
            _LIBC.fflush(None)
            os.dup2(saved, 1)
            os.close(saved)
            sink.seek(0)
            for line in sink.read().decode("utf-8", "replace").splitlines():
                if line.strip():
                    log.debug("%s", line)
