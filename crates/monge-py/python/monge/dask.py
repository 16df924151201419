"""Design-space scans (§4.3) on a Dask cluster: the ``dask`` extra.

    >>> from dask.distributed import Client                   # doctest: +SKIP
    >>> client = Client("tcp://scheduler:8786")               # doctest: +SKIP
    >>> frame = monge.dask.scan(client, design, np.linspace(-180, 180, 100_000))  # doctest: +SKIP

The values are cut into batches of ``batch_size``; each batch is one task,
``monge.scan`` on a worker (itself parallel over the worker's cores), and the
batches are gathered into one pandas DataFrame in the order of the values, with
the columns of ``monge.scan`` and ``index``, the position of the value. The
rows do not depend on the batch size nor on which worker computed them; a batch
whose worker dies is computed again by the scheduler (Dask's own retry), and
its rows appear once.
"""

import numpy as np
import pandas as pd

import monge


def scan_frame(columns, start=0):
    """The columns returned by ``monge.scan`` as a DataFrame, ``index`` from ``start``.

    The text columns (``status``, ``error``) have pandas' string dtype whatever
    the rows hold: a batch without an error would otherwise make ``error`` an
    object column, and the gathered frame would depend on the split.
    """
    frame = pd.DataFrame(
        {
            k: v if isinstance(v, np.ndarray) else pd.array(v, dtype="string")
            for k, v in columns.items()
            if k != "parameter"
        }
    )
    frame.insert(0, "index", np.arange(start, start + len(frame), dtype=np.int64))
    return frame


def _scan_batch(design, values, param, start):
    return scan_frame(monge.scan(monge.Design.from_dict(design), values, param), start)


def scan_futures(client, design, values, param="theta", batch_size=1000):
    """The batches of ``scan`` submitted to the cluster: one future per batch, in order."""
    if batch_size < 1:
        raise ValueError(f"batch_size must be at least 1, not {batch_size}")
    values = np.asarray(values, dtype=float).ravel()
    as_dict = design.to_dict()
    starts = list(range(0, len(values), batch_size))
    return client.map(
        _scan_batch,
        [as_dict] * len(starts),
        [values[s : s + batch_size] for s in starts],
        [param] * len(starts),
        starts,
    )


def gather(client, futures):
    """The DataFrame of the batches of ``scan_futures``, in the order of the values."""
    return pd.concat(client.gather(futures), ignore_index=True)


def scan(client, design, values, param="theta", batch_size=1000):
    """``monge.scan(design, values, param)`` on the cluster of ``client``, as one DataFrame.

    ``batch_size`` values per task: a task costs the cluster milliseconds
    whatever its size, so batches of a second or more of work keep that cost
    small (docs/python.md gives the measurements).
    """
    return gather(client, scan_futures(client, design, values, param, batch_size))
