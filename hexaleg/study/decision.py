"""The decision: which segment ratios to build, and how the user's design compares.

Three steps, each on results the analyses already produced (nothing here draws or
writes):

1. :func:`grid_recommendation`: the three metrics (improved area, w_A, axis-locked FB)
   on the study's (coxa, tibia) ratio grid, combined by :func:`~.recommendation.recommend`.
2. :func:`decide`: the user's design beside the recommended one, metric by metric,
   with the payload capacity of each (not in the score).
3. :func:`pareto_front`: the grid's designs no other beats in area, w_A, FB and
   payload capacity at once, best equal-weight score first.

Which designs may be recommended and how they are ranked is :class:`DecisionOptions`
and :data:`RANKING_RULE`; requirements (payload, slope, speed, ratings) belong here too,
as further fields of the options record that filter the candidates before ranking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.loads import loads_at_extremes
from hexaleg.study.metrics import design_metrics, ratio_metrics
from hexaleg.study.pareto import pareto_table
from hexaleg.study.recommendation import (
    BAND,
    PRACTICAL_L1_RATIO,
    Metrics,
    Recommendation,
    candidate_mask,
    combined_score,
    recommend,
)
from hexaleg.swing.manipulability import AverageManipulabilityMap
from hexaleg.swing.workspace import improved_area_closed_form

RANKING_RULE = (
    "Each metric — improved workspace area (eq 16), average manipulability w_A on the "
    "improved domain (eq 27) and axis-locked body flexibility FB (eq 29) — is divided by its "
    "best value over the whole grid of designs, and the three are averaged with equal "
    "weights; the recommended design has the highest such score among the allowed coxa "
    f"ratios, its tibia ratio refined between grid points. The band keeps ≥ {BAND:.0%} of "
    "that score. Payload capacity is not in the score; the Pareto front adds it as a fourth "
    "metric, ranked the same way."
)
"""How designs are ranked, in words the report shows beside the decision."""


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


@dataclass(frozen=True)
class Decision:
    """The user's design beside the recommended one, on the recommendation's scale.

    Attributes:
        yours: The user's design's metrics (:data:`~hexaleg.study.recommendation.METRICS`).
        your_score: Its combined score [-].
        recommended: The recommended ratios at the user's leg length, body and posture;
            ``None`` if that design cannot stand.
        recommended_metrics: The recommended design's metrics (NaN if it cannot stand).
        recommended_score: Its combined score [-].
        your_payload: The user's design's payload capacity [kg] (not in the score).
        recommended_payload: The recommended design's payload capacity [kg] (NaN if it
            cannot stand).

    """

    yours: Metrics
    your_score: float
    recommended: HexapodDesign | None
    recommended_metrics: Metrics
    recommended_score: float
    your_payload: float
    recommended_payload: float

    def to_json(self) -> dict[str, Any]:
        """JSON-ready form (metrics in m², m³ and 1)."""
        return {
            "yours": {
                "metrics": dict(self.yours),
                "score": self.your_score,
                "payload_capacity": self.your_payload,
            },
            "recommended": {
                "lengths_m": list(self.recommended.lengths) if self.recommended else None,
                "metrics": dict(self.recommended_metrics),
                "score": self.recommended_score,
                "payload_capacity": self.recommended_payload,
            },
        }


def grid_recommendation(
    design: HexapodDesign,
    template: StanceGeometry,
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    options: DecisionOptions,
) -> Recommendation:
    """Recommend ratios from the three metrics on the (coxa, tibia) ratio grid.

    Args:
        design: The user's design (its leg length, body and posture are kept).
        template: The stance geometry of its body and mounts.
        average_map: w_A on the grid (its ratios define the grid).
        study: The FB study on the same grid (column ``fb``).
        options: The allowed coxa ratios and collision setting.

    """
    r1, r3 = average_map.l1_ratios, average_map.l3_ratios
    total = design.leg_length
    l2 = (1 - r1[:, None] - r3[None, :]) * total
    area = np.where(l2 > 0, improved_area_closed_form(l2, r3[None, :] * total), np.nan)
    fb = np.full(area.shape, np.nan)
    for i, ratio in enumerate(r1):
        rows = study[np.isclose(study["l1_ratio"], ratio)]
        fb[i] = rows["fb"].to_numpy(dtype=float) if "fb" in rows else np.nan
    maps = {
        "improved_area": area,
        "average_manipulability": average_map.improved,
        "flexibility": fb,
    }
    return recommend(
        r1,
        r3,
        maps,
        candidates=options.l1_ratios,
        evaluate=lambda a, b: ratio_metrics(design, a, b, template, options.collisions),
    )


def decide(
    design: HexapodDesign,
    model: HexapodModel,
    template: StanceGeometry,
    recommendation: Recommendation,
    your_payload: float,
    options: DecisionOptions,
) -> Decision:
    """The user's design beside the recommended one.

    Args:
        design: The user's design.
        model: Its Pinocchio model (the recommended design's is derived from it).
        template: The stance geometry of its body and mounts.
        recommendation: The recommended ratios.
        your_payload: The user's design's payload capacity [kg].
        options: The collision setting.

    """
    rec, collisions = recommendation, options.collisions
    yours = design_metrics(design, template, collisions)
    recommended_metrics = ratio_metrics(design, rec.l1_ratio, rec.l3_ratio, template, collisions)
    try:
        recommended: HexapodDesign | None = design.with_ratios(rec.l1_ratio, rec.l3_ratio)
    except HexalegError:
        recommended = None
    payload = math.nan
    if recommended is not None:
        their_model = model.with_design(recommended)
        locked = axis_locked_flexibility(recommended, "all", their_model, collisions=collisions)
        payload = loads_at_extremes(their_model, locked).capacity.mass
    return Decision(
        your_payload=your_payload,
        recommended_payload=payload,
        yours=yours,
        your_score=combined_score(yours, rec.maxima),
        recommended=recommended,
        recommended_metrics=recommended_metrics,
        recommended_score=combined_score(recommended_metrics, rec.maxima),
    )


def pareto_front(
    average_map: AverageManipulabilityMap, study: pd.DataFrame, options: DecisionOptions
) -> pd.DataFrame:
    """The Pareto front of the study's allowed designs (see :func:`.pareto.pareto_table`).

    Args:
        average_map: w_A on the study's grid.
        study: The study's table (columns ``fb`` and ``payload_capacity``).
        options: The allowed coxa ratios.

    """
    grid = pareto_grid(average_map, study)
    allowed = candidate_mask(grid["l1_ratio"].to_numpy(dtype=float), options.l1_ratios)
    return pareto_table(grid[allowed])


def pareto_grid(average_map: AverageManipulabilityMap, study: pd.DataFrame) -> pd.DataFrame:
    """Every design of the study with the four metrics of the Pareto front."""
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
