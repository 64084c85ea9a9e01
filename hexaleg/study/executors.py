"""Where a study's tasks run: a local process pool, or a Dask cluster.

Both are context managers yielding a ``concurrent.futures.Executor``, so a study
never cares which it got, and both release what they started on exit.
"""

from __future__ import annotations

import ctypes
import errno
import os
import signal
import sys
import threading
import time
from collections.abc import Iterator
from concurrent.futures import BrokenExecutor, Executor, ProcessPoolExecutor
from concurrent.futures import TimeoutError as FuturesTimeoutError
from contextlib import contextmanager
from typing import Any

from threadpoolctl import threadpool_limits

from hexaleg._checks import require_int
from hexaleg.exceptions import HexalegError

DASK_CONNECT_TIMEOUT = "10s"
"""How long to wait for a Dask scheduler before giving up."""

WORKERS_PER_CPU = 4
"""Local workers allowed per CPU: more only costs memory and switching."""

STARTUP_TIMEOUT = 60.0
"""How long a new local pool may take to answer its first task [s]."""
_LIMIT_HINT = "is the limit on processes (ulimit -u) too low? try fewer --workers"
_SETUP_FAILED = 3
"""Exit status of a worker that could not set itself up."""
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
        _start(pool)
        yield pool
    finally:
        try:
            pool.shutdown(wait=True, cancel_futures=True)
        except RuntimeError:  # its manager thread never started: nothing to wait for
            pass


def _start(pool: ProcessPoolExecutor) -> None:
    """Start the pool's processes and threads now, and see them answer.

    A pool whose manager thread cannot start a thread of its own (the limit on
    processes counts threads) dies without resolving its futures, and its idle workers
    would keep this process from exiting: a study would wait forever. Here that is one
    clear error instead, the workers stopped, and CPython's traceback of the thread
    not shown.
    """
    failures: list[BaseException] = []
    previous = threading.excepthook

    def quiet(args: Any) -> None:
        if args.thread is getattr(pool, "_executor_manager_thread", None):
            failures.append(args.exc_value)
        else:
            previous(args)

    threading.excepthook = quiet
    try:
        with worker_failures():
            ping = pool.submit(os.getpid)
            deadline = time.monotonic() + STARTUP_TIMEOUT
            while not (ping.done() or failures) and time.monotonic() < deadline:
                time.sleep(0.01)
            ping.result(timeout=0)
    except (RuntimeError, FuturesTimeoutError) as err:  # "can't start new thread"
        _stop_workers(pool)
        reason = str(failures[0] if failures else err) or f"no answer in {STARTUP_TIMEOUT:g} s"
        raise HexalegError(f"cannot start the worker processes: {reason}; {_LIMIT_HINT}") from None
    except BaseException:
        _stop_workers(pool)
        raise
    finally:
        threading.excepthook = previous


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Kill the workers of a pool that cannot run (they would wait for work forever)."""
    for process in list(getattr(pool, "_processes", {}).values()):
        process.kill()
        process.join(timeout=10)


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


@contextmanager
def worker_failures() -> Iterator[None]:
    """Turn workers that cannot start or that die into one :class:`HexalegError`.

    A process pool whose workers cannot be created (the limit on processes,
    ``ulimit -u``; no memory) or that lost one (killed, out of memory) cannot finish
    its tasks; what was done before stays done (a study's journal keeps it).
    """
    try:
        yield
    except BrokenExecutor:
        raise HexalegError(
            "a worker process died (killed, out of memory, or the limit on processes, "
            "ulimit -u, too low?); finished work is kept: try again, or with fewer --workers"
        ) from None
    except OSError as err:
        if err.errno not in (errno.EAGAIN, errno.ENOMEM):
            raise
        raise HexalegError(
            f"cannot start worker processes: {err.strerror}; {_LIMIT_HINT}"
        ) from None


def init_worker(parent: int) -> None:
    """Set up a worker process: one BLAS thread, and exit when ``parent`` dies.

    A worker that cannot set itself up (no thread left under ``ulimit -u``) exits
    quietly: the pool then reports it broken, and the study says so in one line.
    """
    try:
        threadpool_limits(1)
        linux = sys.platform.startswith("linux")
        if linux:  # the kernel kills us with the parent
            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
        if os.getppid() != parent:  # the parent died before prctl took effect
            os._exit(1)
        if not linux:  # elsewhere, a thread watches the parent
            threading.Thread(target=_exit_when_orphaned, args=(parent,), daemon=True).start()
    except BaseException:  # OpenBLAS raises SIGINT when it cannot start its threads
        os._exit(_SETUP_FAILED)


def _exit_when_orphaned(parent: int, poll: float = 1.0) -> None:
    """Portable fallback: poll the parent's pid and exit once it has changed."""
    while os.getppid() == parent:
        time.sleep(poll)
    os._exit(1)
