#!/usr/bin/env python3
"""Variants per second of monge.scan on one machine and of monge.dask on a local cluster.

    python scripts/bench-dask.py [VARIANTS] [WORKERS]    (defaults 100000, 2)

from the repository root, with the wheel and the dask extra installed. Prints
the variants per second of monge.scan in this process, of monge.dask.scan on a
dask.distributed.LocalCluster of WORKERS processes (one thread each) at several
batch sizes, and the cluster's cost per task (the same variants as tasks of one variant
and as one task per worker), and
checks that every run gave the same rows.
"""

import sys
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import monge
import monge.dask


def timed(f):
    start = time.perf_counter()
    result = f()
    return result, time.perf_counter() - start


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    workers = int(sys.argv[2]) if len(sys.argv) > 2 else 2
    design = monge.Design.from_file("examples/fig12-dupin-theta30.json")
    values = np.linspace(-179.0, 179.0, n)
    here, t = timed(lambda: monge.dask.scan_frame(monge.scan(design, values)))
    print(f"monge.scan, one process, all cores: {n} variants in {t:.2f} s, {n / t:.0f} variants/s")
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            for batch in (n // (4 * workers), 1000, 100):
                there, t = timed(lambda: monge.dask.scan(client, design, values, batch_size=batch))
                assert there.equals(here), f"batch size {batch}: rows differ from monge.scan's"
                print(f"monge.dask.scan, {workers} workers, batches of {batch}: {n / t:.0f} variants/s")
            m = min(n, 2000)
            _, t_tasks = timed(lambda: monge.dask.scan(client, design, values[:m], batch_size=1))
            _, t_batches = timed(lambda: monge.dask.scan(client, design, values[:m], batch_size=m // workers))
            print(f"cost per task: {1e3 * (t_tasks - t_batches) / m:.2f} ms of wall time ({m} tasks of 1 variant vs {workers} of {m // workers})")

if __name__ == "__main__":
    main()
