"""Ranking designs when no requirement is given: one stated rule, one recommendation.

The rule (:data:`RANKING_RULE`): a design's score is the geometric mean of its improved
workspace area [m²] (eq 16), average manipulability w_A [m³] (eq 27), axis-locked FB [-]
(eq 29) and walking payload capacity [kg] (:mod:`hexaleg.gait.capacity`: what the robot
carries walking the design's gait, its ``[gait]`` or else the default, within its
ratings, not only standing), each divided by
the user's design's own value. A score of 1.10 is 10 % better than the user's design on
that (logarithmic) average, and every metric counts alike whatever its unit or its spread
over a grid: doubling the payload raises a score as much as doubling FB. A score depends
on that design and the user's design alone, so adding or removing other designs of a grid
never changes it; and the order of the designs is the same whatever the reference (the
reference only scales every score by one factor). A design missing a metric (it cannot
stand, or cannot walk the gait unloaded within its ratings) has no score; one that walks
but carries nothing scores 0.

The recommendation (:mod:`hexaleg.study.recommendation`), the Pareto front's order
(:mod:`hexaleg.study.pareto`) and the report's Decision section all rank by this rule.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from hexaleg._typing import ArrayF
from hexaleg.evaluation.metrics import METRICS, Metrics, MetricSpec

RANKED_METRICS: tuple[MetricSpec, ...] = (
    METRICS.improved_area,
    METRICS.average_manipulability,
    METRICS.fb,
    METRICS.walking_payload_capacity,
)
"""The metrics a score combines [m², m³, -, kg], every one larger-is-better."""

RANKING_RULE = (
    "a design's score is the geometric mean of its improved workspace area (eq 16), "
    "average manipulability w_A (eq 27), axis-locked body flexibility FB (eq 29) and "
    "walking payload capacity (the largest payload carried walking the gait — the design "
    "file's [gait], else the default tripod — within every rating, in place of the standing "
    "capacity, which a leg that cannot walk "
    "still has), each divided by your design's own value: your design scores 1, and 1.10 is "
    "10 % better on that average, every metric counting alike whatever its unit. Only legs "
    "that walk the gait unloaded within their ratings are ranked. A score depends on that "
    "design and yours alone, so adding or removing other designs of the grid never changes it"
)
"""The rule in one sentence, for reports."""


def ranked_values(metrics: Metrics) -> ArrayF:
    """One design's :data:`RANKED_METRICS` (M,), in that order (NaN where one is missing)."""
    return np.array([metrics.value(spec) for spec in RANKED_METRICS])


def relative_values(values: ArrayF, reference: Metrics) -> ArrayF:
    """Each metric of ``values`` (..., M) over the reference's (a non-positive one: 1 unit)."""
    scale = ranked_values(reference)
    scale = np.where(scale > 0, scale, 1.0)
    relative: ArrayF = np.asarray(values, dtype=float) / scale
    return relative


def scores(values: ArrayF, reference: Metrics) -> ArrayF:
    """The score of each design by :data:`RANKING_RULE` (NaN where a metric is missing).

    Args:
        values: The :data:`RANKED_METRICS` of each design (..., M), last axis in that order.
        reference: The user's design's metrics; a non-positive one is replaced by 1 in its
            unit (scores scale, the order stays).

    """
    relative = relative_values(values, reference)
    with np.errstate(divide="ignore", invalid="ignore"):
        logs = np.log(relative)  # log 0 = -inf: a design that carries nothing scores 0
    found: ArrayF = np.exp(logs.mean(axis=-1))
    bad = np.isnan(relative).any(axis=-1) | (relative < 0).any(axis=-1)
    return np.where(bad, np.nan, found)


def score(metrics: Metrics, reference: Metrics) -> float:
    """One design's score by :data:`RANKING_RULE` (NaN if a metric is missing)."""
    return float(scores(ranked_values(metrics), reference))


def ranking_scores(table: pd.DataFrame, reference: Metrics) -> pd.Series:
    """Each row's score by :data:`RANKING_RULE` (NaN where a metric is missing).

    Args:
        table: One row per design, a column for each of :data:`RANKED_METRICS`.
        reference: The user's design's metrics.

    """
    values = table[ranked_columns()].to_numpy(dtype=float)
    return pd.Series(scores(values, reference), index=table.index, name="score")


def ranked_columns() -> list[str]:
    """The table columns of :data:`RANKED_METRICS`: their names."""
    return [spec.name for spec in RANKED_METRICS]
