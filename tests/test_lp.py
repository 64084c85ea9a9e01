"""The compiled elastic LP against SciPy's HiGHS on random programs."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import linprog

from hexaleg.numerics.lp import elastic_lp


def _highs(objective, offsets, rows, lower, upper, penalty):
    """The same program for HiGHS: minimize −c·x + penalty·Σt, −a·x − t ≤ g."""
    m = rows.shape[0]
    cost = np.concatenate([-objective, np.full(m, penalty)])
    bounds = list(zip(lower, upper, strict=True)) + [(0, None)] * m
    result = linprog(cost, A_ub=np.hstack([-rows, -np.eye(m)]), b_ub=offsets, bounds=bounds)
    assert result.status == 0
    return -result.fun


@pytest.mark.parametrize("seed", range(6))
def test_random_programs_reach_highs_optimum(seed):
    rng = np.random.default_rng(seed)
    for _ in range(50):
        m, n = int(rng.integers(1, 30)), int(rng.integers(1, 7))
        rows = rng.normal(size=(m, n))
        rows /= np.linalg.norm(rows, axis=1)[:, None]
        offsets = rng.normal(size=m) * rng.choice([0.01, 0.5, 3.0])
        lower, upper = -rng.uniform(0.0, 1, n), rng.uniform(0.0, 1, n)
        objective = rng.normal(size=n)
        _assert_optimal(objective, offsets, rows, lower, upper)


def test_degenerate_programs_terminate():
    # many copies of one constraint through the optimum: every pivot but one is degenerate
    rows = np.tile([[1.0, 1.0]], (12, 1)) / np.sqrt(2)
    x, t = elastic_lp(np.array([-1.0, -1.0]), np.zeros(12), rows, -np.ones(2), np.ones(2), 10.0)
    assert x.sum() == pytest.approx(0.0, abs=1e-12)  # any point of x + y = 0 in the box
    assert t.max() == 0


def test_a_relaxation_is_used_only_where_no_step_can_satisfy_the_constraint():
    # x ≥ 2 within |x| ≤ 1: the best is x = 1, short by t = 1
    x, t = elastic_lp(
        np.array([0.0]), np.array([-2.0]), np.array([[1.0]]), -np.ones(1), np.ones(1), 5.0
    )
    assert x[0] == pytest.approx(1.0) and t[0] == pytest.approx(1.0)


@pytest.mark.parametrize("seed", range(4))
def test_degenerate_random_programs_reach_highs_optimum(seed):
    # a climb's programs: mirror-image legs give equal rows, tight rows pass through x = 0,
    # and a point on the search box's edge leaves a variable only one side (or none)
    rng = np.random.default_rng(100 + seed)
    for _ in range(50):
        m, n = int(rng.integers(2, 30)), int(rng.integers(1, 7))
        rows = rng.normal(size=(m, n))
        rows /= np.linalg.norm(rows, axis=1)[:, None]
        offsets = rng.normal(size=m) * rng.choice([0.01, 0.5])
        offsets[rng.random(m) < 0.3] = 0.0
        copies = rng.integers(0, m, size=m // 2)
        rows[: len(copies)], offsets[: len(copies)] = rows[copies], offsets[copies]
        lower, upper = -rng.uniform(0.0, 1, n), rng.uniform(0.0, 1, n)
        lower[rng.random(n) < 0.2] = 0.0
        upper[rng.random(n) < 0.2] = 0.0
        objective = rng.normal(size=n)
        _assert_optimal(objective, offsets, rows, lower, upper)


def _assert_optimal(objective, offsets, rows, lower, upper):
    """elastic_lp's answer is feasible and its value equals HiGHS's on the same program."""
    x, t = elastic_lp(objective, offsets, rows, lower, upper, 100.0)
    assert np.all(x >= lower - 1e-12) and np.all(x <= upper + 1e-12) and np.all(t >= 0)
    assert np.all(offsets + rows @ x + t >= -1e-10)
    value = objective @ x - 100.0 * t.sum()
    assert value == pytest.approx(_highs(objective, offsets, rows, lower, upper, 100.0), abs=1e-9)
