"""The Pareto front: non-dominated designs, NaN designs excluded, ranked by the one rule."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from hexaleg.evaluation.metrics import Metrics
from hexaleg.study.pareto import non_dominated, pareto_table
from hexaleg.study.ranking import ranked_columns

COLUMNS = ranked_columns()


def _ranked(values) -> Metrics:
    """The three ranked metrics, in their order."""
    return Metrics(**{name: float(v) for name, v in zip(COLUMNS, values, strict=True)})


def test_non_dominated_on_hand_made_points():
    points = np.array(
        [
            [1.0, 5.0],  # front
            [2.0, 4.0],  # front
            [2.0, 3.0],  # dominated by [2, 4]
            [3.0, 1.0],  # front
            [1.0, 5.0],  # a twin of the first: neither beats the other
            [np.nan, 9.0],  # cannot stand
        ]
    )
    assert non_dominated(points).tolist() == [True, True, False, True, True, False]


def _grid(values, names):
    grid = pd.DataFrame(values, columns=COLUMNS)
    grid["name"] = names
    return grid


def test_the_front_is_ranked_by_the_geometric_mean_relative_to_yours():
    grid = _grid(
        [[1.0, 1.0, 2.0], [2.0, 1.5, 0.5], [2.0, 1.0, 0.5], [4.0, 1.0, 1.0]],
        ["p", "q", "r", "s"],
    )
    yours = _ranked([1.0, 1.0, 1.0])
    front = pareto_table(grid, yours)
    assert set(front["name"]) == {"p", "q", "s"}  # r is beaten by q
    scores = dict(zip(front["name"], front["score"], strict=True))
    # by hand: the cube roots of the products of the ratios to yours
    assert scores == pytest.approx({"p": 2 ** (1 / 3), "q": 1.5 ** (1 / 3), "s": 4 ** (1 / 3)})
    assert list(front["name"]) == ["s", "p", "q"]


def test_adding_designs_never_changes_a_score_on_the_front():
    rng = np.random.default_rng(7)
    grid = _grid(rng.uniform(0.1, 1.0, (40, 3)), range(40))
    reference = rng.uniform(0.1, 1.0, 3)
    yours = _ranked(reference)
    before = pareto_table(grid, yours).set_index("name")["score"]
    more = pd.concat([grid, _grid(rng.uniform(0.1, 1.0, (40, 3)), range(40, 80))])
    after = pareto_table(more, yours).set_index("name")["score"]
    kept = before.index.intersection(after.index)
    assert len(kept) > 0
    np.testing.assert_array_equal(after[kept].to_numpy(), before[kept].to_numpy())
    products = [
        np.prod([r[m] / y for m, y in zip(COLUMNS, reference, strict=True)])
        for r in grid.to_dict("records")
    ]
    best = grid.iloc[int(np.argmax(products))]
    assert pareto_table(grid, yours).iloc[0]["name"] == best["name"]  # the grid's best is first
