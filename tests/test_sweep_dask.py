"""The same sweep on a Dask LocalCluster on the loopback gives the local results exactly
(skipped without dask.distributed)."""

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")

from velplan.mechanism.loader import load  # noqa: E402
from velplan.sweep.run import monte_carlo, run_sweep, tolerances  # noqa: E402


def test_sweep_on_a_local_cluster_equals_the_local_run():
    mech = load("four-bar")
    values = monte_carlo(mech, tolerances(mech, 2e-3, 0.5), 60, "dask")
    values["crank.length"][3] = 0.2  # one variant that does not close
    local = run_sweep(mech, values, mode="monte-carlo", positions=72, chunk=16)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp",
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        with distributed.Client(cluster) as client:
            remote = run_sweep(mech, values, mode="monte-carlo", positions=72, chunk=16, scheduler=client)
        by_address = run_sweep(mech, values, mode="monte-carlo", positions=72, chunk=16,
                               scheduler=cluster.scheduler_address)
    for res in (remote, by_address):
        assert res.failures == local.failures and res.failures[3].startswith("group '2-3'")
        for name, arr in local.figures.items():
            assert np.array_equal(res.figures[name], arr, equal_nan=True), name
