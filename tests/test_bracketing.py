"""The bracketing root-finder: the first failure along a search, not a later one."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.numerics.bracketing import anderson_bjorck, first_crossings


def test_first_failure_wins_over_a_later_feasible_region():
    """A margin that dips below zero and recovers: the extreme stops at the dip."""

    def margins(direction, t):
        dip = np.abs(t - 0.35) - 0.05  # negative on (0.30, 0.40), feasible again after
        other = 0.8 - t  # breaks at 0.8
        return np.stack([dip, other], axis=-1)

    t, which, binding = first_crossings(margins, np.array([1.0, 0.5]))
    np.testing.assert_allclose(t, [0.30, 0.30], atol=1e-12)
    assert which.tolist() == [0, 0]
    assert binding == ((0,), (0,))


def test_a_cheaper_scan_finds_the_same_crossings_and_margins_solve_them():
    """The scan's stand-in only says where a margin is negative; the roots come from margins."""
    calls = {"margins": 0, "scan": 0}

    def margins(direction, t):
        calls["margins"] += len(t)
        dip = np.abs(t - 0.35) - 0.05
        return np.stack([dip, 0.8 - t], axis=-1)

    def scan(direction, t):
        calls["scan"] += len(t)
        values = margins(direction, t)
        calls["margins"] -= len(t)
        return np.where(values < 0, values, np.inf)

    alone = first_crossings(margins, np.array([1.0, 0.5]))
    spent_alone = calls["margins"]
    calls.update(margins=0, scan=0)
    scanned = first_crossings(margins, np.array([1.0, 0.5]), scan=scan)
    np.testing.assert_array_equal(scanned.t, alone.t)
    assert scanned.which.tolist() == alone.which.tolist() and scanned.binding == alone.binding
    assert calls["scan"] > 0 and calls["margins"] < spent_alone  # the scan used the stand-in


def test_nothing_breaking_reports_the_search_range():
    def margins(direction, t):
        return np.ones((*np.shape(t), 1))

    t, which, binding = first_crossings(margins, np.array([2.0]))
    assert t.tolist() == [2.0] and which.tolist() == [-1] and binding == ((),)


def test_anderson_bjorck_finds_smooth_roots_and_keeps_the_feasible_end():
    """Known roots: g(t) = c − t² has its root at √c; the returned end is never past it."""
    c = np.array([0.5, 2.0, 0.01])
    roots = anderson_bjorck(lambda t, i: c[i] - t**2, np.zeros(3), np.full(3, 2.0))
    np.testing.assert_allclose(roots, np.sqrt(c), rtol=1e-11)
    assert np.all(c - roots**2 >= 0)


def test_ties_are_broken_by_constraint_order_and_all_named():
    """Two mirror-image margins cross together (to round-off): the first is named, both bind."""

    def margins(direction, t):
        return np.stack([0.4 - t * (1 + 1e-15), 0.9 - t, 0.4 - t], axis=-1)

    crossings = first_crossings(margins, np.array([1.0]))
    assert crossings.t[0] == pytest.approx(0.4, abs=1e-12)
    assert crossings.which.tolist() == [0] and crossings.binding == ((0, 2),)
