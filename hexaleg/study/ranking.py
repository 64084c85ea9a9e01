"""Ranking designs when no requirement is given: one stated rule, one recommendation.

The rule (:data:`RANKING_RULE`): a design's score is the geometric mean of its improved
workspace area [m²], average manipulability w_A [m³], axis-locked FB [-] and payload
capacity [kg], each divided by the user's design's own value. A score of 1.10 is 10 %
better than the user's design on that (logarithmic) average, and every metric counts
alike whatever its unit or its spread over a grid: doubling the payload raises a score
as much as doubling FB. A score depends on that design and the user's design alone, so
adding or removing other designs of a grid never changes it; and the order of the
designs is the same whatever the reference (the reference only scales every score by
one factor). The recommendation is the design with the highest score, the first in
table order among equal ones; a design missing a metric (it cannot stand) has no score.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from hexaleg.study.pareto import PARETO_METRICS

RANKING_RULE = (
    "designs are ranked by the geometric mean of improved area, w_A, FB and payload "
    "capacity, each relative to your design's (1.10: 10 % better on average); a score "
    "depends on that design and yours alone, not on the other designs of the grid"
)
"""The rule in one sentence, for reports."""


def ranking_scores(
    table: pd.DataFrame,
    reference: Mapping[str, float],
    metrics: Sequence[str] = PARETO_METRICS,
) -> pd.Series:
    """Each row's score by :data:`RANKING_RULE` (NaN where a metric is missing).

    Args:
        table: One row per design, a column per metric (larger is better).
        reference: The user's design's value of each metric; a non-positive one is
            replaced by 1 in its unit (scores scale, the order stays).
        metrics: The metrics that count, each alike.

    """
    values = table[list(metrics)].to_numpy(dtype=float)
    scale = np.array([reference[m] if reference[m] > 0 else 1.0 for m in metrics], dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        logs = np.log(values / scale)  # log 0 = -inf: a design that carries nothing scores 0
    scores = np.exp(logs.mean(axis=1))
    scores[np.isnan(values).any(axis=1) | (values < 0).any(axis=1)] = np.nan
    return pd.Series(scores, index=table.index, name="score")


def recommend_by_rule(
    table: pd.DataFrame,
    reference: Mapping[str, float],
    metrics: Sequence[str] = PARETO_METRICS,
) -> pd.Series:
    """The row of ``table`` with the highest score, its ``score`` added.

    Raises:
        ValueError: no row has a score.

    """
    scores = ranking_scores(table, reference, metrics)
    if scores.isna().all():
        raise ValueError("no design has every metric: nothing to recommend")
    best = int(np.nanargmax(scores.to_numpy()))
    row = table.iloc[best].copy()
    row["score"] = float(scores.iloc[best])
    return row
