"""The one ranking rule: a stated geometric mean, scores that stay put, one order."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from hexaleg.evaluation.metrics import METRICS, Metrics
from hexaleg.study.ranking import RANKED_METRICS, ranked_columns, ranking_scores, score

COLUMNS = ranked_columns()


def _ranked(*values: float) -> Metrics:
    """The four ranked metrics, in their order."""
    return Metrics(**dict(zip(COLUMNS, values, strict=True)))


def _grid(rows, seed):
    rng = np.random.default_rng(seed)
    return pd.DataFrame(rng.uniform(0.1, 2.0, (rows, len(RANKED_METRICS))), columns=COLUMNS)


def test_a_score_is_the_geometric_mean_of_ratios_to_your_design():
    table = pd.DataFrame([[0.4, 0.1, 0.25, 200.0]], columns=COLUMNS)
    yours = _ranked(0.2, 0.1, 0.25, 50.0)
    # by hand: (2 · 1 · 1 · 4) ** (1/4) = 8 ** 0.25
    assert ranking_scores(table, yours).iloc[0] == pytest.approx(8**0.25, rel=1e-12)
    assert score(_ranked(0.4, 0.1, 0.25, 200.0), yours) == pytest.approx(8**0.25, rel=1e-12)
    assert score(yours, yours) == 1.0


def test_scores_do_not_change_when_unrelated_designs_are_added():
    table = _grid(30, seed=1)
    yours = _ranked(0.5, 0.05, 0.2, 100.0)
    before = ranking_scores(table, yours)
    wider = pd.concat([table, _grid(50, seed=2) * 3.0], ignore_index=True)
    after = ranking_scores(wider, yours)
    np.testing.assert_array_equal(after.iloc[:30].to_numpy(), before.to_numpy())


def test_the_order_does_not_depend_on_the_reference():
    table = _grid(40, seed=3)
    ones = _ranked(1.0, 1.0, 1.0, 1.0)
    other = _ranked(0.3, 0.02, 0.4, 500.0)
    a, b = ranking_scores(table, ones), ranking_scores(table, other)
    assert list(a.sort_values().index) == list(b.sort_values().index)
    np.testing.assert_allclose(b / a, (b / a).iloc[0], rtol=1e-12)  # one factor scales all


def test_payload_counts_as_much_as_any_other_metric():
    table = pd.DataFrame(
        [[1.0, 1.0, 1.0, 1.0], [1.0, 1.0, 2.0, 1.0], [1.0, 1.0, 1.0, 2.0]], columns=COLUMNS
    )
    scores = ranking_scores(table, _ranked(1.0, 1.0, 1.0, 1.0))
    assert scores.iloc[1] == pytest.approx(scores.iloc[2]) and scores.iloc[1] > scores.iloc[0]


def test_a_design_that_cannot_stand_has_no_score_and_one_that_carries_nothing_scores_zero():
    table = _grid(5, seed=4)
    table.loc[2, METRICS.fb.name] = np.nan
    table.loc[3, METRICS.walking_payload_capacity.name] = 0.0
    yours = _ranked(1.0, 1.0, 1.0, 0.0)  # the walking payload 0: replaced by 1 kg
    scores = ranking_scores(table, yours)
    assert np.isnan(scores.iloc[2]) and scores.iloc[3] == 0.0
    row = table.iloc[0]
    assert scores.iloc[0] == pytest.approx(float(np.prod(row.to_numpy()) ** 0.25), rel=1e-12)
