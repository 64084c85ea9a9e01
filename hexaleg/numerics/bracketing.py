"""Bracketing root-finders for margins along many one-dimensional searches at once.

Pure numerics, independent of the robot: :func:`first_crossings` finds, for each of
many directions, the *first* parameter t at which any of several margins turns
negative (a chunked scan, so a region that is feasible again beyond the first failure
never counts), then solves each broken margin inside its bracket with
:func:`anderson_bjorck`, a vectorized regula falsi that keeps the feasible end.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.exceptions import HexalegError

IndexArray = npt.NDArray[np.int_]

SCAN_STEPS = 256
"""Resolution of the first-failure scan: t_max / 256 (≈ 8 mm or 0.7° for a 1 m leg)."""
SCAN_CHUNKS = 8
REFINE_ITERATIONS = 60
MARGIN_ROUNDOFF = 1e-15
"""A margin this small [m or rad] is zero to round-off: its end of the bracket is the root."""
BRACKET_TOLERANCE = 1e-12
"""Final bracket width relative to the searched distance (at least 1 m or 1 rad)."""
TIE_TOLERANCE = 1e-9
"""Roots this close (relative, at least 1 m or 1 rad) break together: a tie, such as two
mirror-image legs, is decided by constraint order, never by round-off."""


class Crossings(NamedTuple):
    """Result of :func:`first_crossings`.

    Attributes:
        t: The crossing per direction (t_max where nothing breaks) (D,).
        which: The breaking constraint per direction, the first in constraint order
            among ties (−1 where nothing breaks) (D,).
        binding: Every constraint that breaks there, per direction, in constraint order.

    """

    t: ArrayF
    which: npt.NDArray[np.int_]
    binding: tuple[tuple[int, ...], ...]


class StartBroken(HexalegError):
    """The start (t = 0) already breaks a constraint: the caller names it from its column.

    Attributes:
        direction: The direction whose start was checked.
        column: The broken constraint's column in the margins.
        margin: Its margin there (negative).

    """

    def __init__(self, direction: int, column: int, margin: float) -> None:
        self.direction, self.column, self.margin = direction, column, margin
        super().__init__(f"the start breaks constraint {column} (margin {margin:.6g})")

    def __reduce__(self) -> tuple[object, ...]:  # picklable across process pools
        return (type(self), (self.direction, self.column, self.margin))


def first_crossings(
    margins: Callable[[IndexArray, ArrayF], ArrayF],
    t_max: ArrayF,
    steps: int = SCAN_STEPS,
    chunks: int = SCAN_CHUNKS,
    tolerance: float = BRACKET_TOLERANCE,
    check_start: bool = True,
    scan: Callable[[IndexArray, ArrayF], ArrayF] | None = None,
) -> Crossings:
    """For each direction d, the first t ∈ (0, t_max[d]] where any margin turns negative.

    The scan steps through (0, t_max] at t_max/:data:`SCAN_STEPS` in chunks, dropping
    directions that have broken, so only the first failure along the motion counts.
    In each bracket every constraint that broke is solved on its own (smooth) margin by
    Anderson–Björck regula falsi, and the earliest root wins; roots within
    :data:`TIE_TOLERANCE` of it bind too.

    Args:
        margins: Maps (direction index (K,), t (K,)) to margins (K, C).
        t_max: Search range per direction (D,).
        steps: Scan resolution: t_max / steps.
        chunks: The scan runs in this many chunks, dropping directions that broke.
        tolerance: Final bracket width, relative to the searched distance (at least 1).
        check_start: Evaluate t = 0 too and refuse a start that already violates a
            margin; pass False when the caller has checked it (each t is evaluated once).
        scan: A cheaper stand-in for ``margins`` in the scan, negative exactly where
            their smallest is (positive values need not be margins); ``margins`` itself
            if omitted. The bracket's far end and the roots use ``margins``.

    Returns:
        The crossings, breaking constraints and every binding constraint per direction.

    """
    t_max = np.asarray(t_max, dtype=float)
    lo, hi, broken = _first_failures(
        margins if scan is None else scan, t_max, steps // chunks, chunks, check_start
    )
    which = np.full(len(t_max), -1)
    binding: list[tuple[int, ...]] = [()] * len(t_max)
    index = np.flatnonzero(broken)
    if index.size:
        _solve_brackets(margins, index, lo, hi, tolerance, which, binding)
    return Crossings(np.where(broken, lo, t_max), which, tuple(binding))


def _first_failures(
    scan: Callable[[IndexArray, ArrayF], ArrayF],
    t_max: ArrayF,
    per_chunk: int,
    chunks: int,
    check_start: bool,
) -> tuple[ArrayF, ArrayF, npt.NDArray[np.bool_]]:
    """Brackets [lo, hi] of each direction's first failure, and which directions fail.

    The scan runs chunk by chunk along (0, t_max], dropping the directions that failed.
    """
    count = len(t_max)
    lo, hi = np.zeros(count), t_max.copy()
    broken = np.zeros(count, dtype=bool)
    for chunk in range(chunks):
        active = np.flatnonzero(~broken)
        if active.size == 0:
            break
        with_start = chunk == 0 and check_start
        fractions = np.arange(0 if with_start else 1, per_chunk + 1) / per_chunk
        start = t_max[active] * chunk / chunks  # evaluated by the previous chunk
        t = start[:, None] + (t_max[active] / chunks)[:, None] * fractions
        rows = np.broadcast_to(active[:, None], t.shape)
        smallest = scan(rows.ravel(), t.ravel()).min(axis=-1).reshape(t.shape)
        if with_start and np.any(smallest[:, 0] < 0):
            worst = int(np.argmin(smallest[:, 0]))
            at_start = scan(active[worst : worst + 1], t[worst : worst + 1, 0])[0]
            column = int(np.argmin(at_start))
            raise StartBroken(int(active[worst]), column, float(at_start[column]))
        infeasible = smallest < 0
        hit = infeasible.any(axis=1)
        first = np.argmax(infeasible, axis=1)
        for k in np.flatnonzero(hit):
            d = active[k]
            lo[d] = t[k, first[k] - 1] if first[k] > 0 else start[k]
            hi[d] = t[k, first[k]]
        broken[active[hit]] = True
    return lo, hi, broken


def _solve_brackets(
    margins: Callable[[IndexArray, ArrayF], ArrayF],
    index: IndexArray,
    lo: ArrayF,
    hi: ArrayF,
    tolerance: float,
    which: npt.NDArray[np.int_],
    binding: list[tuple[int, ...]],
) -> None:
    """Solve every constraint that broke in its direction's bracket; keep the earliest.

    Writes, per direction of ``index``, the crossing into ``lo``, the breaking
    constraint into ``which`` and the tied ones into ``binding``.
    """
    at_hi = margins(index, hi[index])
    pair_row, pair_constraint = np.nonzero(at_hi < 0)
    directions = index[pair_row]

    def pair_margin(t: ArrayF, pairs: IndexArray) -> ArrayF:
        return margins(directions[pairs], t)[np.arange(len(t)), pair_constraint[pairs]]

    root = anderson_bjorck(pair_margin, lo[directions], hi[directions], tolerance)
    for d in index:
        mine = np.flatnonzero(directions == d)  # in constraint order
        earliest = root[mine].min()
        tied = mine[root[mine] <= earliest + TIE_TOLERANCE * max(1.0, abs(earliest))]
        lo[d], which[d] = earliest, pair_constraint[tied[0]]
        binding[d] = tuple(int(c) for c in pair_constraint[tied])


def anderson_bjorck(
    g: Callable[[ArrayF, IndexArray], ArrayF],
    lo: ArrayF,
    hi: ArrayF,
    relative_tolerance: float = BRACKET_TOLERANCE,
) -> ArrayF:
    """Roots of g in brackets [lo, hi] with g(lo) ≥ 0 > g(hi), vectorized; returns the feasible end.

    Regula falsi with the Anderson–Björck correction: when the same end moves
    twice, the other end's value is scaled by m = 1 − g(new)/g(old) (½ if m ≤ 0),
    which keeps the bracket and converges superlinearly on smooth margins.

    Args:
        g: ``g(t, index)``: the functions numbered ``index`` at ``t`` (both (K,)); only
            brackets still open are evaluated.
        lo: Feasible ends (D,).
        hi: Infeasible ends (D,).
        relative_tolerance: Final bracket width relative to ``hi`` (at least 1).

    """
    lo, hi = lo.astype(float), hi.astype(float)
    every = np.arange(len(lo))
    g_lo, g_hi = g(lo, every), g(hi, every)
    side = np.zeros(len(lo))  # which end moved last: +1 lo, −1 hi
    tolerance = relative_tolerance * np.maximum(hi, 1.0)
    for _ in range(REFINE_ITERATIONS):
        # done: a tight bracket, or a feasible end whose margin is at round-off level
        live = np.flatnonzero((hi - lo > tolerance) & (g_lo > MARGIN_ROUNDOFF))
        if live.size == 0:
            break
        a, b, ga, gb = lo[live], hi[live], g_lo[live], g_hi[live]
        t = (a * gb - b * ga) / (gb - ga)
        t = np.where((t > a) & (t < b), t, 0.5 * (a + b))
        g_t = g(t, live)
        feasible = g_t >= 0
        old = np.where(feasible, ga, gb)  # value at the end being replaced
        scale = 1.0 - g_t / np.where(old != 0, old, 1.0)
        scale = np.where(scale > 0, scale, 0.5)
        moved = side[live]
        gb = np.where(feasible & (moved > 0), scale * gb, gb)
        ga = np.where(~feasible & (moved < 0), scale * ga, ga)
        lo[live], g_lo[live] = np.where(feasible, t, a), np.where(feasible, g_t, ga)
        hi[live], g_hi[live] = np.where(feasible, b, t), np.where(feasible, gb, g_t)
        side[live] = np.where(feasible, 1.0, -1.0)
    return lo
