"""The host a benchmark ran on: the numerical libraries' versions, the CPU, and its speed.

A benchmark whose figures pass through least-squares fits on a rough landscape
(``bench_discover.py``) can give other verdicts when the last digits of its arithmetic change,
and those can change with the libraries' versions and with the CPU kernels OpenBLAS picks; its CPU
seconds depend on the host's speed (measured: docs/discovery.md, "The same code on a third
machine"). Runs are comparable only with this record beside them.

``record()`` returns the versions, the CPU's model name and ``cpu_us_per_newton_iteration``:
the process CPU time of one Newton iteration of the certified solver, the fastest of
``REPEATS`` cold solves of each of ``DESIGNS``, median over the designs (the quantity
``bench_solver.py`` reports over its 21 designs). The discovery workflow spends about 90 % of
its CPU in such solves, so its CPU seconds scale with this figure from host to host.
"""
from __future__ import annotations

import functools
import pathlib
import platform
import statistics
import time

DESIGNS = ((25.0, 0.6), (40.0, 0.8), (70.0, 1.0))
REPEATS = 5


def _cpu_model() -> str:
    info = pathlib.Path("/proc/cpuinfo")
    if info.exists():
        for line in info.read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return platform.processor() or platform.machine()


def timed_solves(patch, material, repeats: int) -> tuple[list, list]:
    """``repeats`` cold certified solves of ``patch``: the solutions and the process CPU time
    (s) of each."""
    from stitchswitch import solve

    runs, cpu = [], []
    for _ in range(repeats):
        t = time.process_time()
        runs.append(solve(patch, material))
        cpu.append(time.process_time() - t)
    return runs, cpu


def _per_iteration_us() -> float:
    from stitchswitch import DEFAULT_MATERIAL, Patch, solve

    solve(Patch(*DESIGNS[0]), DEFAULT_MATERIAL)              # load the compiled kernels
    per = []
    for d, p in DESIGNS:
        runs, cpu = timed_solves(Patch(d, p), DEFAULT_MATERIAL, REPEATS)
        per.append(min(cpu) / max(runs[0].iterations, 1) * 1e6)
    return float(statistics.median(per))


@functools.lru_cache(maxsize=1)
def record() -> dict:
    """This process's host record (measured once per process)."""
    import numba
    import numpy
    import scipy

    return {"python": platform.python_version(), "numpy": numpy.__version__,
            "scipy": scipy.__version__, "numba": numba.__version__, "cpu": _cpu_model(),
            "cpu_us_per_newton_iteration": round(_per_iteration_us(), 1)}


def describe(rec: dict) -> str:
    """One line: the CPU, its speed and the versions."""
    return (f"{rec['cpu']}, {rec['cpu_us_per_newton_iteration']:.0f} us CPU per Newton iteration; "
            f"Python {rec['python']}, numpy {rec['numpy']}, scipy {rec['scipy']}, "
            f"numba {rec['numba']}")
