"""monge.dask on a local cluster of worker processes: the rows of monge.scan, whatever the split."""

import contextlib
import os

import numpy as np
import pytest

import monge
from conftest import example

distributed = pytest.importorskip("distributed", reason="monge.dask needs the dask extra (dask[distributed], pandas)")
pd = pytest.importorskip("pandas")
import monge.dask  # noqa: E402

# 10 000 variants of a small design: θ over its whole range, fair, folded and
# inadmissible ones among them.
VALUES = np.linspace(-179.0, 179.0, 10_000)


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as c:
            yield c


@pytest.fixture(scope="module")
def design():
    return monge.Design.from_file(example("contract.json"))


def test_the_cluster_gives_the_rows_of_one_machine_whatever_the_split(client, design):
    here = monge.dask.scan_frame(monge.scan(design, VALUES))
    assert len(here) == 10_000 and set(here["status"]) == {"fair", "folded", "inadmissible"}
    for batch_size in (97, 1000, 4096):
        there = monge.dask.scan(client, design, VALUES, batch_size=batch_size)
        pd.testing.assert_frame_equal(there, here, check_exact=True)


def test_a_worker_killed_mid_run_loses_and_repeats_no_row(client, design):
    workers = len(client.scheduler_info()["workers"])
    futures = monge.dask.scan_futures(client, design, VALUES, batch_size=20)
    distributed.wait(futures[:1])
    busy = {w: keys for w, keys in client.processing().items() if keys}
    assert busy, "every batch finished before a worker could be killed"
    victim = next(iter(busy))
    # The worker exits holding batches; its nanny starts a new one and the
    # scheduler computes the lost batches again.
    # The call loses its connection when the worker exits: that is the point.
    with contextlib.suppress(Exception):
        client.run(os._exit, 1, workers=[victim])
    there = monge.dask.gather(client, futures)
    here = monge.dask.scan_frame(monge.scan(design, VALUES))
    pd.testing.assert_frame_equal(there, here, check_exact=True)
    assert there["index"].tolist() == list(range(len(VALUES)))
    client.wait_for_workers(workers, timeout=60)


def test_a_batch_size_below_one_is_refused(client, design):
    with pytest.raises(ValueError, match="batch_size must be at least 1, not 0"):
        monge.dask.scan(client, design, VALUES, batch_size=0)
