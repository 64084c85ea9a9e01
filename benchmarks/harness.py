"""Benchmark harness: timing, agreement checks and the results table's rows.

Every baseline must agree numerically with hexaleg before it is timed; medians
are measured round-robin where several implementations race, so drift hits all alike.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Row:
    """One line of the results table."""

    workload: str
    implementation: str
    median_s: float
    ratio: float | None  # baseline median / hexaleg median
    max_difference: float | None
    target: str = ""
    note: str = ""
    extra: dict = field(default_factory=dict)


def median_time(fn: Callable[[], object], repeats: int, min_time: float = 0.05) -> float:
    """Median wall time of ``fn`` over ``repeats`` runs (each run looped to ≥ min_time)."""
    for _ in range(3):  # warm-up: caches, allocator, CPU frequency
        fn()
    start = time.perf_counter()
    fn()
    once = time.perf_counter() - start
    loops = max(1, math.ceil(min_time / max(once, 1e-9)))
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(loops):
            fn()
        samples.append((time.perf_counter() - start) / loops)
    return statistics.median(samples)


def median_times(
    fns: list[Callable[[], object]], repeats: int, min_time: float = 0.05
) -> list[float]:
    """Median wall times of several functions measured round-robin, so drift hits all alike."""
    loops = []
    for fn in fns:
        for _ in range(3):
            fn()
        start = time.perf_counter()
        fn()
        loops.append(max(1, math.ceil(min_time / max(time.perf_counter() - start, 1e-9))))
    samples: list[list[float]] = [[] for _ in fns]
    for _ in range(repeats):
        for k, fn in enumerate(fns):
            start = time.perf_counter()
            for _ in range(loops[k]):
                fn()
            samples[k].append((time.perf_counter() - start) / loops[k])
    return [statistics.median(s) for s in samples]


def check_agree(name: str, reference: np.ndarray, other: np.ndarray, atol: float) -> float:
    """Largest absolute difference; raise if it exceeds ``atol``."""
    diff = float(np.max(np.abs(np.asarray(reference) - np.asarray(other))))
    if not diff <= atol:
        raise SystemExit(f"benchmark {name}: results disagree by {diff:.3g} > {atol:.3g}")
    return diff


def missing(workload: str, name: str) -> Row:
    return Row(workload, name, math.nan, None, None, note="not installed: pip install '.[bench]'")


def seconds(value: float) -> str:
    if value >= 1:
        return f"{value:.2f} s"
    if value >= 1e-3:
        return f"{value * 1e3:.1f} ms"
    return f"{value * 1e6:.0f} µs"
