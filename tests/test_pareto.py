"""The Pareto front: non-dominated designs, NaN designs excluded, scored on the grid's best."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from hexaleg.study.pareto import non_dominated, pareto_table


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


def test_pareto_table_scores_against_the_grids_best():
    grid = pd.DataFrame(
        {"a": [1.0, 2.0, 2.0, 4.0], "b": [4.0, 2.0, 1.0, 1.0], "name": ["p", "q", "r", "s"]}
    )
    front = pareto_table(grid, ["a", "b"])
    assert set(front["name"]) == {"p", "q", "s"}
    scores = dict(zip(front["name"], front["score"], strict=True))
    assert scores == pytest.approx({"p": (0.25 + 1) / 2, "q": (0.5 + 0.5) / 2, "s": (1 + 0.25) / 2})
    assert front["score"].is_monotonic_decreasing
