"""Where a study's tasks run: a local process pool, or a Dask cluster.

Both are context managers yielding a ``concurrent.futures.Executor``, so a study
never cares which it got, and both release what they started on exit.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager

from hexaleg.exceptions import HexalegError

DASK_CONNECT_TIMEOUT = "10s"
"""How long to wait for a Dask scheduler before giving up."""


@contextmanager
def local_pool(workers: int | None = None) -> Iterator[Executor]:
    """A process pool of ``workers`` processes (default: the number of CPUs)."""
    pool = ProcessPoolExecutor(max_workers=workers or os.cpu_count() or 1)
    try:
        yield pool
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


@contextmanager
def dask_executor(address: str) -> Iterator[Executor]:
    """An executor on the Dask cluster whose scheduler listens at ``address``.

    Raises:
        HexalegError: Dask is not installed, or the scheduler cannot be reached.

    """
    try:
        from distributed import Client
    except ImportError:
        raise HexalegError("--scheduler needs Dask: pip install 'hexaleg[dask]'") from None
    try:
        client = Client(address, timeout=DASK_CONNECT_TIMEOUT)
    except (OSError, TimeoutError) as err:
        raise HexalegError(f"cannot reach the Dask scheduler at {address}: {err}") from None
    try:
        yield client.get_executor()
    finally:
        client.close()
