"""The designs no other design beats in every metric at once (the Pareto front).

On the study's grid of (coxa, tibia) ratios every design has its improved area,
w_A, FB and payload capacity, all to be maximized. The grid is dense and every
metric on it exact, so the front is read off the grid directly (no evolutionary
search is needed, and none could be more exact). The recommendation on the front is
its design with the best equal-weight score, each metric divided by its best value.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

from hexaleg._typing import ArrayF

PARETO_METRICS = ("improved_area", "average_manipulability", "flexibility", "payload_capacity")
"""The metrics of the front [m², m³, -, kg], every one to be maximized."""


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


def pareto_table(grid: pd.DataFrame, metrics: Sequence[str] = PARETO_METRICS) -> pd.DataFrame:
    """The front of ``grid`` (one row per design, a column per metric), best first.

    Each front design's score is the mean of its metrics over their best values on the grid.
    """
    values = grid[list(metrics)].to_numpy(dtype=float)
    best = np.nanmax(values, axis=0)
    front = grid[non_dominated(values)].copy()
    front["score"] = (front[list(metrics)].to_numpy(dtype=float) / best).mean(axis=1)
    return front.sort_values("score", ascending=False, kind="stable").reset_index(drop=True)
