"""The one ranking rule: walking first, then a stated geometric mean; no ratio to zero."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from hexaleg.evaluation.metrics import METRICS, Metrics
from hexaleg.exceptions import ParameterError
from hexaleg.study.ranking import (
    RANKED_METRICS,
    RANKING_RULE,
    WalkingConstraint,
    left_out,
    ranked_columns,
    ranking_scores,
    rule_note,
    score,
)

COLUMNS = ranked_columns()


def _ranked(*values: float) -> Metrics:
    """The three ranked metrics, in their order."""
    return Metrics(**dict(zip(COLUMNS, values, strict=True)))


def _grid(rows, seed):
    rng = np.random.default_rng(seed)
    return pd.DataFrame(rng.uniform(0.1, 2.0, (rows, len(RANKED_METRICS))), columns=COLUMNS)


def test_the_objective_is_the_paper_s_metrics_and_walking_is_the_constraint():
    assert RANKED_METRICS == (METRICS.improved_area, METRICS.average_manipulability, METRICS.fb)
    assert "walks the gait" in RANKING_RULE and "payload" in RANKING_RULE


def test_a_score_is_the_geometric_mean_of_ratios_to_your_design():
    table = pd.DataFrame([[0.4, 0.1, 1.0]], columns=COLUMNS)
    yours = _ranked(0.2, 0.1, 0.25)
    # by hand: (2 · 1 · 4) ** (1/3) = 2
    assert ranking_scores(table, yours).iloc[0] == pytest.approx(2.0, rel=1e-12)
    assert score(_ranked(0.4, 0.1, 1.0), yours) == pytest.approx(2.0, rel=1e-12)
    assert score(yours, yours) == 1.0


def test_scores_do_not_change_when_unrelated_designs_are_added():
    table = _grid(30, seed=1)
    yours = _ranked(0.5, 0.05, 0.2)
    before = ranking_scores(table, yours)
    wider = pd.concat([table, _grid(50, seed=2) * 3.0], ignore_index=True)
    after = ranking_scores(wider, yours)
    np.testing.assert_array_equal(after.iloc[:30].to_numpy(), before.to_numpy())


def test_the_order_does_not_depend_on_the_reference():
    table = _grid(40, seed=3)
    a, b = ranking_scores(table, _ranked(1, 1, 1)), ranking_scores(table, _ranked(0.3, 0.02, 0.4))
    assert list(a.sort_values().index) == list(b.sort_values().index)
    np.testing.assert_allclose(b / a, (b / a).iloc[0], rtol=1e-12)  # one factor scales all


@pytest.mark.parametrize("baseline", [0.0, -0.1, math.nan])
def test_a_metric_with_no_positive_baseline_never_enters_a_ratio(baseline):
    """Your FB is 0: the old rule printed score 0 or divided by '1 unit'. It is left out."""
    table = _grid(6, seed=4)
    yours = _ranked(0.5, 0.05, baseline)
    found = ranking_scores(table, yours).to_numpy()
    assert np.all(np.isfinite(found)) and np.all(found > 0)  # never 0, inf or nan
    rows = table.to_numpy()
    by_hand = np.sqrt(rows[:, 0] / 0.5 * rows[:, 1] / 0.05)  # the other two, averaged
    np.testing.assert_allclose(found, by_hand, rtol=1e-12)
    assert score(yours, yours) == 1.0
    assert left_out(yours) == (METRICS.fb,) and "left out" in rule_note(yours)
    assert rule_note(_ranked(1, 1, 1)) == ""


def test_a_leg_missing_a_scored_metric_has_no_score():
    table = _grid(4, seed=5)
    table.loc[1, METRICS.fb.name] = np.nan
    table.loc[2, METRICS.fb.name] = 0.0
    found = ranking_scores(table, _ranked(1, 1, 1))
    assert np.isnan(found.iloc[1]) and np.isnan(found.iloc[2]) and np.isfinite(found.iloc[0])


def test_the_walking_constraint_reads_the_capacity_and_the_unloaded_walk():
    unloaded, carrying = WalkingConstraint(), WalkingConstraint(30.0)
    assert unloaded.met(0.0, True) and not unloaded.met(50.0, False)
    assert carrying.met(30.0, True) and not carrying.met(29.9, True)
    assert carrying.shortfall(15.0, True) == pytest.approx(0.5)
    assert carrying.shortfall(math.nan, True) == 1.0 and carrying.shortfall(99.0, None) == 1.0
    walking = METRICS.walking_payload_capacity.name
    table = pd.DataFrame({"walks": [True, True, False, None], walking: [40, 20, 90, 90]})
    assert carrying.met_rows(table).tolist() == [True, False, False, False]
    assert "30 kg" in carrying.describe() and "unloaded" in unloaded.describe()
    with pytest.raises(ParameterError, match="payload"):
        WalkingConstraint(-1.0)
