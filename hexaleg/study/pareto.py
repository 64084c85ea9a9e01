"""The designs no other design beats in every metric at once (the Pareto front).

On the study's grid of (coxa, tibia) ratios every design has its improved area,
w_A, FB and payload capacity (:data:`~hexaleg.study.ranking.RANKED_METRICS`), all to be
maximized. The grid is dense and every metric on it exact, so the front is read off the
grid directly (no evolutionary search is needed, and none could be more exact). The
front is ordered by the one ranking rule (:mod:`hexaleg.study.ranking`): a design that
beats another in every metric also scores higher, so the grid's best-scoring design is
always on the front, first.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from hexaleg._typing import ArrayF
from hexaleg.study.ranking import RANKED_METRICS, Metrics, ranking_scores


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
    front = grid[non_dominated(grid[list(RANKED_METRICS)].to_numpy(dtype=float))].copy()
    front["score"] = ranking_scores(front, reference)
    return front.sort_values("score", ascending=False, kind="stable").reset_index(drop=True)
