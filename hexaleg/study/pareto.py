"""The designs no other design beats in every metric at once (the Pareto front).

On the study's grid of (coxa, tibia) ratios, at the user's posture, every design that meets
the ranking's constraint (it walks the gait with the payload within every rating,
:class:`~hexaleg.study.ranking.WalkingConstraint`) has its improved area, w_A and FB
(:data:`~hexaleg.study.ranking.RANKED_METRICS`), all to be maximized. The grid is dense and
every metric on it exact, so the front is read off the grid directly (no evolutionary search
is needed, and none could be more exact). The front is ordered by the one ranking rule
(:mod:`hexaleg.study.ranking`): a design that beats another in every metric also scores
higher, so the grid's best-scoring design is always on the front, first.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from hexaleg._typing import ArrayF
from hexaleg.evaluation.metrics import METRICS, Metrics
from hexaleg.study.ranking import WalkingConstraint, ranked_columns, ranking_scores
from hexaleg.study.recommendation import DecisionOptions, Recommendation, candidate_mask
from hexaleg.swing.manipulability import AverageManipulabilityMap
from hexaleg.swing.workspace import improved_area_closed_form


def non_dominated(values: ArrayF) -> np.ndarray:
    """Mask of the rows (K, M) no other row beats: ≥ in every column and > in one.

    Rows with a NaN (a design that cannot stand) are never on the front.
    """
    values = np.asarray(values, dtype=float)
    valid = ~np.isnan(values).any(axis=1)
    front = valid.copy()
    for i in np.flatnonzero(valid):
        others = values[valid]
        dominated = np.all(others >= values[i], axis=1) & np.any(others > values[i], axis=1)
        front[i] = not dominated.any()
    return front


def pareto_table(grid: pd.DataFrame, reference: Metrics) -> pd.DataFrame:
    """The front of ``grid`` (one row per design, a column per ranked metric), best first.

    Args:
        grid: One row per design, a column for each of
            :data:`~hexaleg.study.ranking.RANKED_METRICS`.
        reference: The user's design's metrics: each front design's ``score`` is
            :func:`~hexaleg.study.ranking.ranking_scores` against them.

    """
    front = grid[non_dominated(grid[ranked_columns()].to_numpy(dtype=float))].copy()
    front["score"] = ranking_scores(front, reference)
    return front.sort_values("score", ascending=False, kind="stable").reset_index(drop=True)


def pareto_front(
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    recommendation: Recommendation,
    options: DecisionOptions,
) -> pd.DataFrame:
    """The Pareto front of the study's allowed designs (see :func:`.pareto.pareto_table`).

    Args:
        average_map: w_A on the study's grid.
        study: The study's table (columns ``fb``, ``walking_payload_capacity``, ``walks``).
        recommendation: The recommendation (its reference: the user's design's metrics;
            its constraint).
        options: The allowed coxa ratios.

    """
    grid = pareto_grid(average_map, study, recommendation.constraint)
    allowed = candidate_mask(grid["l1_ratio"].to_numpy(dtype=float), options.l1_ratios)
    return pareto_table(grid[allowed], recommendation.reference)


def pareto_grid(
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    constraint: WalkingConstraint | None = None,
) -> pd.DataFrame:
    """Every design of the study with the ranked metrics (NaN where it misses ``constraint``).

    ``constraint``: what a ranked design must do (default: walk the gait unloaded).
    """
    grid = study[["l1_ratio", "l3_ratio", "l1", "l2", "l3"]].copy()
    grid[METRICS.improved_area.name] = improved_area_closed_form(
        grid["l2"].to_numpy(dtype=float), grid["l3"].to_numpy(dtype=float)
    )
    w_a = {
        (r1, r3): value
        for i, r1 in enumerate(average_map.l1_ratios)
        for r3, value in zip(average_map.l3_ratios, average_map.improved[i], strict=True)
    }
    grid[METRICS.average_manipulability.name] = [
        w_a.get((r1, r3), np.nan) for r1, r3 in zip(grid["l1_ratio"], grid["l3_ratio"], strict=True)
    ]
    for spec in (METRICS.fb, METRICS.walking_payload_capacity, METRICS.payload_capacity):
        grid[spec.name] = study[spec.name] if spec.name in study else np.nan
    met = (constraint or WalkingConstraint()).met_rows(study)
    grid.loc[~met, ranked_columns()] = np.nan  # a leg that misses it has no score: off the front
    return grid
