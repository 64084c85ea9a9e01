"""The grid decision: which segment ratios to build when no requirement is given.

Two steps on results the analyses already produced (nothing here draws or writes),
both ranking by the one rule of :mod:`hexaleg.study.ranking` (the geometric mean of
improved area, w_A, FB and payload capacity, each relative to the user's design):

1. :func:`grid_recommendation`: the four metrics on the study's (coxa, tibia) ratio
   grid, the best-scoring design among the allowed coxa ratios, its tibia ratio refined
   (:func:`~.recommendation.recommend`), beside the user's design;
2. :func:`pareto_front`: the grid's designs no other beats in all four metrics at once,
   best score first — the first is the recommendation's grid point.

Which designs may be recommended is :class:`DecisionOptions`. Requirements (payload,
slope, speed, ratings) are the other decision, :func:`hexaleg.study.decide.decide`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from hexaleg.design import HexapodDesign
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.metrics import design_metrics, ratio_metrics
from hexaleg.study.pareto import pareto_table
from hexaleg.study.ranking import Metrics
from hexaleg.study.recommendation import (
    PRACTICAL_L1_RATIO,
    Recommendation,
    candidate_mask,
    recommend,
)
from hexaleg.swing.manipulability import AverageManipulabilityMap
from hexaleg.swing.workspace import improved_area_closed_form


@dataclass(frozen=True)
class DecisionOptions:
    """What the decision may choose from.

    Attributes:
        l1_ratios: Coxa ratios the recommendation may take; ``None``: the swept ones at
            least :data:`~.recommendation.PRACTICAL_L1_RATIO` (all of them if none is).
        collisions: The robot's own parts touching also stop the body (FB).

    """

    l1_ratios: tuple[float, ...] | None = None
    collisions: bool = False

    def describe_candidates(self) -> str:
        """The allowed coxa ratios, in words."""
        if self.l1_ratios:
            listed = ", ".join(f"{r:.3g}" for r in self.l1_ratios)
            return f"the coxa ratios you allowed ({listed})"
        return f"the paper's practical coxa ratios (≥ {PRACTICAL_L1_RATIO:.2f})"


def your_metrics(
    design: HexapodDesign, model: HexapodModel, template: StanceGeometry, options: DecisionOptions
) -> Metrics:
    """The user's design's four ranked metrics: what every score is relative to."""
    return design_metrics(design, model, template, options.collisions)


def grid_recommendation(
    design: HexapodDesign,
    model: HexapodModel,
    template: StanceGeometry,
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    options: DecisionOptions,
) -> Recommendation:
    """Recommend ratios from the four metrics on the (coxa, tibia) ratio grid.

    Args:
        design: The user's design (its leg length, body and posture are kept).
        model: Its Pinocchio model (the grid's designs' are derived from it).
        template: The stance geometry of its body and mounts.
        average_map: w_A on the grid (its ratios define the grid).
        study: The study on the same grid (columns ``fb`` and ``payload_capacity``).
        options: The allowed coxa ratios and collision setting.

    """
    r1, r3 = average_map.l1_ratios, average_map.l3_ratios
    total = design.leg_length
    l2 = (1 - r1[:, None] - r3[None, :]) * total
    maps = {
        "improved_area": np.where(
            l2 > 0, improved_area_closed_form(l2, r3[None, :] * total), np.nan
        ),
        "average_manipulability": average_map.improved,
        "flexibility": _study_map(study, "fb", r1, len(r3)),
        "payload_capacity": _study_map(study, "payload_capacity", r1, len(r3)),
    }
    return recommend(
        r1,
        r3,
        maps,
        your_metrics(design, model, template, options),
        candidates=options.l1_ratios,
        evaluate=lambda a, b: ratio_metrics(design, a, b, model, template, options.collisions),
    )


def _study_map(study: pd.DataFrame, column: str, l1_ratios: np.ndarray, width: int) -> np.ndarray:
    """A study column on the (coxa, tibia) grid: each coxa ratio's rows in tibia order."""
    values = np.full((len(l1_ratios), width), np.nan)
    if column in study:
        for i, ratio in enumerate(l1_ratios):
            values[i] = study.loc[np.isclose(study["l1_ratio"], ratio), column].to_numpy(float)
    return values


def pareto_front(
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    recommendation: Recommendation,
    options: DecisionOptions,
) -> pd.DataFrame:
    """The Pareto front of the study's allowed designs (see :func:`.pareto.pareto_table`).

    Args:
        average_map: w_A on the study's grid.
        study: The study's table (columns ``fb`` and ``payload_capacity``).
        recommendation: The recommendation (its reference: the user's design's metrics).
        options: The allowed coxa ratios.

    """
    grid = pareto_grid(average_map, study)
    allowed = candidate_mask(grid["l1_ratio"].to_numpy(dtype=float), options.l1_ratios)
    return pareto_table(grid[allowed], recommendation.reference)


def pareto_grid(average_map: AverageManipulabilityMap, study: pd.DataFrame) -> pd.DataFrame:
    """Every design of the study with the four ranked metrics."""
    grid = study[["l1_ratio", "l3_ratio", "l1", "l2", "l3"]].copy()
    grid["improved_area"] = improved_area_closed_form(
        grid["l2"].to_numpy(dtype=float), grid["l3"].to_numpy(dtype=float)
    )
    w_a = {
        (r1, r3): value
        for i, r1 in enumerate(average_map.l1_ratios)
        for r3, value in zip(average_map.l3_ratios, average_map.improved[i], strict=True)
    }
    grid["average_manipulability"] = [
        w_a.get((r1, r3), np.nan) for r1, r3 in zip(grid["l1_ratio"], grid["l3_ratio"], strict=True)
    ]
    grid["flexibility"] = study["fb"] if "fb" in study else np.nan
    grid["payload_capacity"] = study["payload_capacity"] if "payload_capacity" in study else np.nan
    return grid
