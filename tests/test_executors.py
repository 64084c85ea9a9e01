"""Executors: the local pool is released on exit; an unreachable scheduler is one clear error."""

from __future__ import annotations

import pytest

from hexaleg.exceptions import HexalegError
from hexaleg.study.executors import dask_executor, local_pool


def test_local_pool_runs_tasks_and_is_shut_down_on_exit():
    with local_pool(1) as pool:
        assert pool.submit(pow, 2, 10).result(timeout=60) == 1024
    with pytest.raises(RuntimeError):
        pool.submit(pow, 2, 3)


@pytest.mark.slow  # Dask waits out its connect timeout (10 s)
def test_unreachable_scheduler_is_a_hexaleg_error():
    pytest.importorskip("distributed")
    with pytest.raises(HexalegError, match="cannot reach the Dask scheduler"):
        with dask_executor("tcp://127.0.0.1:9"):
            pass


ORPHAN_SCRIPT = """
import os, sys, time
from hexaleg.study.executors import local_pool
with local_pool(2) as pool:
    futures = [pool.submit(time.sleep, 600) for _ in range(2)]
    time.sleep(1.0)
    print(" ".join(str(pid) for pid in pool._processes), flush=True)
    time.sleep(600)
"""


def test_workers_die_with_their_parent_even_on_sigkill():
    import os
    import signal
    import subprocess
    import sys
    import time

    psutil = pytest.importorskip("psutil")
    parent = subprocess.Popen(
        [sys.executable, "-c", ORPHAN_SCRIPT], stdout=subprocess.PIPE, text=True
    )
    try:
        workers = [int(pid) for pid in parent.stdout.readline().split()]
        assert len(workers) == 2 and all(psutil.pid_exists(pid) for pid in workers)
    finally:
        os.kill(parent.pid, signal.SIGKILL)  # the parent alone, as an OOM killer would
        parent.wait(timeout=30)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and any(_alive(psutil, pid) for pid in workers):
        time.sleep(0.1)
    assert not any(_alive(psutil, pid) for pid in workers)


def _alive(psutil, pid: int) -> bool:
    try:
        return psutil.Process(pid).status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def test_one_blas_thread_per_worker():
    with local_pool(1) as pool:
        assert set(pool.submit(_blas_threads).result(timeout=60)) <= {1}


def _blas_threads() -> list[int]:
    import numpy  # noqa: F401
    from threadpoolctl import threadpool_info

    return [info["num_threads"] for info in threadpool_info() if info["user_api"] == "blas"]


def test_more_workers_than_allowed_are_refused():
    from hexaleg.study.executors import max_workers

    with pytest.raises(HexalegError, match="workers = "):
        with local_pool(max_workers() + 1):
            pass


def test_a_worker_that_dies_is_one_line():
    import os

    from hexaleg.study.executors import worker_failures

    with local_pool(1) as pool:
        with pytest.raises(HexalegError, match="a worker process died") as caught:
            with worker_failures():
                pool.submit(os._exit, 1).result(timeout=60)
    assert "\n" not in str(caught.value)


def _cannot_set_up(parent: int) -> None:
    raise RuntimeError("can't start new thread")


def test_workers_that_cannot_set_up_are_one_line_before_any_task(monkeypatch):
    from hexaleg.study import executors

    monkeypatch.setattr(executors, "init_worker", _cannot_set_up)
    with pytest.raises(HexalegError, match="ulimit -u"):
        with local_pool(2):
            pytest.fail("the pool was handed out")


@pytest.mark.slow  # a few short studies as a plain user
def test_a_low_limit_on_processes_is_one_line_never_a_hang_or_a_traceback():
    """`ulimit -u` too low for the pool (root ignores it: a plain user)."""
    import shutil

    from unprivileged import plain_folder, run_plain

    folder = plain_folder()
    try:
        statuses = []
        for limit in (2, 3, 4, 5):
            argv = ["study", "--l1-ratios", "0.1", "--l3-points", "2", "--workers", "2"]
            result = run_plain([*argv, "-o", f"s{limit}"], cwd=folder, nproc=limit, timeout=300)
            statuses.append(result.returncode)
            assert "Traceback" not in result.stderr, result.stderr
            assert result.returncode in (0, 2), result.stderr
            if result.returncode == 2:
                assert result.stderr.count("\n") == 1 and "ulimit -u" in result.stderr
        assert 2 in statuses  # the smallest limits leave no room for the pool
    finally:
        shutil.rmtree(folder, ignore_errors=True)
