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


def test_unreachable_scheduler_is_a_hexaleg_error():
    pytest.importorskip("distributed")
    with pytest.raises(HexalegError, match="cannot reach the Dask scheduler"):
        with dask_executor("tcp://127.0.0.1:9"):
            pass
