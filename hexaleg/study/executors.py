"""Where a study's tasks run: a local process pool, or a Dask cluster.

Both are context managers yielding a ``concurrent.futures.Executor``, so a study
never cares which it got, and both release what they started on exit.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys
import threading
import time
from collections.abc import Iterator
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager

from threadpoolctl import threadpool_limits

from hexaleg._checks import require_int
from hexaleg.exceptions import HexalegError

DASK_CONNECT_TIMEOUT = "10s"
"""How long to wait for a Dask scheduler before giving up."""

WORKERS_PER_CPU = 4
"""Local workers allowed per CPU: more only costs memory and switching."""

_PR_SET_PDEATHSIG = 1  # Linux prctl option: a signal to receive when the parent dies


def max_workers() -> int:
    """The most local worker processes hexaleg starts: 4 per CPU."""
    return WORKERS_PER_CPU * (os.cpu_count() or 1)


@contextmanager
def local_pool(workers: int | None = None) -> Iterator[Executor]:
    """A process pool of ``workers`` processes (default: the number of CPUs).

    Each worker uses one BLAS thread (the processes already fill the cores; more
    threads only oversubscribe them) and dies with this process, even on SIGKILL.

    Raises:
        HexalegError: ``workers`` is not in 1..:func:`max_workers`.

    """
    count = workers or os.cpu_count() or 1
    require_int("workers", count, 1, max_workers())  # WORKERS_PER_CPU per CPU
    pool = ProcessPoolExecutor(max_workers=count, initializer=init_worker, initargs=(os.getpid(),))
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
    except (OSError, TimeoutError, ValueError) as err:  # ValueError: not an address at all
        raise HexalegError(f"cannot reach the Dask scheduler at {address}: {err}") from None
    try:
        yield client.get_executor()
    finally:
        client.close()


def init_worker(parent: int) -> None:
    """Set up a worker process: one BLAS thread, and exit when ``parent`` dies."""
    threadpool_limits(1)
    if sys.platform.startswith("linux"):  # the kernel kills us with the parent
        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
    if os.getppid() != parent:  # the parent died before prctl took effect
        os._exit(1)
    threading.Thread(target=_exit_when_orphaned, args=(parent,), daemon=True).start()


def _exit_when_orphaned(parent: int, poll: float = 1.0) -> None:
    """Portable fallback: poll the parent's pid and exit once it has changed."""
    while os.getppid() == parent:
        time.sleep(poll)
    os._exit(1)
