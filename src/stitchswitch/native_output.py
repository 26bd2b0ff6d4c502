"""Native libraries' console output, kept off stdout.

HiGHS (through cvxpy) prints a copyright banner with C stdio on every solve, whatever the
solver's verbosity option says. Written to file descriptor 1, it would corrupt a command's
``--json`` output, where stdout must carry the JSON and nothing else. ``to_logger(log)`` points
descriptor 1 at a temporary file for the duration of a block, flushes the C library's buffers
before restoring it, and passes each captured line to ``log.info`` (shown with ``-v``).

Python libraries log too: ezdxf reports each value its recover mode repaired as a warning on
its own logger, which, with no handler configured, Python's last-resort handler prints on
stderr; numpy's ``RuntimeWarning`` goes through the ``warnings`` module to stderr.
``relay_library_logs(log)`` sends both to ``log.info`` instead (``logging.captureWarnings``
for the warnings), so that they appear with ``-v`` and not on a clean run; the package's own
warnings summarise what matters (e.g. "ezdxf recover mode repaired 3 problem(s)").
"""
from __future__ import annotations

import ctypes
import logging
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
                    log.info("%s", line)


#: The loggers of libraries whose messages ``relay_library_logs`` sends to the package's log
#: (``py.warnings`` carries Python warnings once ``logging.captureWarnings`` is on).
LIBRARY_LOGGERS = ("ezdxf", "py.warnings")


class _Relay(logging.Handler):
    """Re-log a library's record on the package's logger at info level, first line only."""

    def __init__(self, target: logging.Logger):
        super().__init__()
        self.target = target

    def emit(self, record: logging.LogRecord) -> None:
        try:
            first = record.getMessage().strip().splitlines()[:1] or [""]
            self.target.info("%s: %s", record.name, first[0])
        except Exception:  # pragma: no cover - logging must never raise
            self.handleError(record)


def relay_library_logs(log: logging.Logger) -> None:
    """Send ezdxf's log and Python warnings to ``log.info`` instead of stderr (idempotent)."""
    logging.captureWarnings(True)
    for name in LIBRARY_LOGGERS:
        library = logging.getLogger(name)
        library.propagate = False
        if not any(isinstance(h, _Relay) for h in library.handlers):
            library.addHandler(_Relay(log))
