"""The executor: serial, local processes and a Dask LocalCluster give identical results."""
import numpy as np
import pytest

from stitchswitch import InvalidInputError
from stitchswitch.executor import make_executor, run_all


def _h(dp):
    from stitchswitch import Patch, solve

    sol = solve(Patch(*dp))
    return sol.keypoints.h_mm, sol.energy, sol.z_mm.copy()


DESIGNS = [(30.0, 0.7), (45.0, 0.9), (60.0, 0.6), (80.0, 1.0)]


def test_local_processes_match_serial():
    serial = run_all(_h, DESIGNS, workers=1)
    parallel = run_all(_h, DESIGNS, workers=2)
    for a, b in zip(serial, parallel):
        assert a[0] == b[0] and a[1] == b[1] and np.array_equal(a[2], b[2])


def test_dask_local_cluster_matches_local_run():
    import distributed

    serial = run_all(_h, DESIGNS, workers=1)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        dask_results = run_all(_h, DESIGNS, scheduler=cluster.scheduler_address)
    for a, b in zip(serial, dask_results):
        assert a[0] == b[0] and a[1] == b[1] and np.array_equal(a[2], b[2])


@pytest.mark.parametrize("workers", [0, -1, True, 1.5])
def test_bad_workers(workers):
    with pytest.raises(InvalidInputError, match="workers"):
        make_executor(workers)


def test_bad_scheduler_address():
    with pytest.raises(InvalidInputError, match="scheduler"):
        make_executor(scheduler="localhost:8786")
