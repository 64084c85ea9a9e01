"""Report part: the recommended ratios and the evidence behind them (paper §4–6 combined).

One ranking rule (:mod:`hexaleg.study.ranking`) serves this section, the Pareto front
and the Decision section: the geometric mean of the four metrics, each
relative to the user's design.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.output.report.document import Section, cell, table, write_csv
from hexaleg.output.report.manipulability import ManipulabilityRecord
from hexaleg.output.report.part import Part, ReportData, where_legs_are_the_designs
from hexaleg.output.report.study import StudyRecord
from hexaleg.ratios import proportions_text, ratio_text
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.ranking import RANKED_METRICS, RANKING_RULE
from hexaleg.study.recommendation import BAND, Recommendation, grid_recommendation
from hexaleg.study.rows import StudyRow


@dataclass(frozen=True)
class RecommendationRecord:
    """The recommendation on the study's grid.

    Attributes:
        recommendation: Recommended ratios, the band, and the scores behind them.
        leg_length: The design's leg length, at which the ratios are lengths [m].
        recommended: The recommended design measured as the study measures its own (it is
            marked on the study's figures).

    """

    recommendation: Recommendation
    leg_length: float
    recommended: StudyRow


def compute(data: ReportData) -> RecommendationRecord:
    """Recommend ratios from the ranked metrics on the grid of the study."""
    template = StanceGeometry.from_model(data.model, "all")
    study = data[StudyRecord]
    rec = grid_recommendation(
        data.design,
        data.model,
        template,
        data[ManipulabilityRecord].average_map,
        study.table,
        data.options.decision,
    )
    theirs = data.robot.at_ratios(rec.l1_ratio, rec.l3_ratio)
    return RecommendationRecord(rec, data.design.leg_length, study.spec.row_of(theirs))


def section(data: ReportData) -> Section:
    """The recommended ratios and the evidence behind them."""
    rec = data[RecommendationRecord].recommendation
    total = data.design.leg_length
    return Section(
        "Recommendation",
        (
            f"Every design of the grid is ranked by one rule: {RANKING_RULE}. Among the legs "
            "that walk, where each metric and the score peak (the kinematic metrics peak "
            "at shorter tibias than walking allows: their own peaks over every leg are in "
            f"sections {data.number(ManipulabilityRecord)} and {data.number(StudyRecord)}), "
            "and the best score each coxa ratio reaches:",
            table(
                [
                    "l1 ratio",
                    "area peak l3, walking legs",
                    "w_A peak l3, walking legs",
                    "FB peak l3, walking legs",
                    "walking payload peak l3",
                    "score peak l3",
                    "best score",
                ],
                [_peak_row(r) for r in rec.peaks.to_dict(orient="records")],
            ),
            "Workspace, manipulability and flexibility grow as the coxa shrinks (Table 5); "
            "the walking payload capacity peaks where its column says, and the score weighs "
            "all four alike. The recommendation takes the best score among the allowed coxa "
            "ratios, its tibia ratio refined between grid points with every metric computed "
            "exactly (so it differs from the best grid point of the Pareto front):",
            f"**Recommended: {proportions_text(rec.l1_ratio, rec.l2_ratio, rec.l3_ratio)}** "
            f"(score {rec.score:.4f} against your design's 1; for a "
            f"{total:g} m leg: {rec.l1_ratio * total:.3f} m, {rec.l2_ratio * total:.3f} m, "
            f"{rec.l3_ratio * total:.3f} m). Any tibia ratio in {ratio_text(rec.l3_band[0])}–"
            f"{ratio_text(rec.l3_band[1])} keeps ≥ {BAND:.0%} of its score and walks; choose "
            "within it by what these metrics leave out (ground clearance, speed, mass), or "
            "give those as requirements (`hexaleg decide`, `report --payload …`).",
        ),
    )


NO_WALKER = "no leg at this coxa ratio walks the gait within its ratings"
"""The §5 table's words for a coxa ratio with no leg to rank (every cell would be NaN)."""


def _peak_row(peaks: dict[str, float]) -> list[str]:
    """One coxa ratio's row of peaks: the tibia ratios and best score, or why there are none."""
    l3_columns = [*(f"{spec.name}_peak_l3_ratio" for spec in RANKED_METRICS), "score_peak_l3_ratio"]
    values = [peaks[column] for column in l3_columns]
    if not any(math.isfinite(v) for v in (*values, peaks["best_score"])):
        return [f"{peaks['l1_ratio']:.2f}", NO_WALKER, *("—" for _ in l3_columns)]
    return [
        f"{peaks['l1_ratio']:.2f}",
        *(cell(v, ratio_text, "none") for v in values),
        cell(peaks["best_score"], lambda v: f"{v:.4f}", "no score"),
    ]


def write_files(data: ReportData, out: Path) -> None:
    """``recommendation_scores.csv``: metrics, relative to yours, and score on the whole grid."""
    scores = data[RecommendationRecord].recommendation.scores
    write_csv(out / "recommendation_scores.csv", scores.to_dict(orient="records"))


def to_json(record: RecommendationRecord) -> dict[str, Any]:
    """``recommendation``: ratios, band, metrics, score, your metrics, peaks, lengths, rule."""
    rec, total = record.recommendation, record.leg_length
    return {
        "recommendation": {
            "rule": RANKING_RULE,
            "l1_ratio": rec.l1_ratio,
            "l2_ratio": rec.l2_ratio,
            "l3_ratio": rec.l3_ratio,
            "l3_band": list(rec.l3_band),
            "metrics": rec.metrics.to_dict(),
            "score": rec.score,
            "reference": rec.reference.to_dict(),
            "peaks": rec.peaks.to_dict(orient="records"),
            "lengths_m": [rec.l1_ratio * total, rec.l2_ratio * total, rec.l3_ratio * total],
        }
    }


RANKED_GRID = where_legs_are_the_designs(
    "Recommendation, Pareto front and the decision's costs",
    "they rank the paper's ratio grid with the template's manipulability map; with "
    "requirements, the decision over your robot's segments is shown instead",
)
"""Where the ranked grid holds: every leg the paper's leg of l1, l2, l3."""

PART = Part(
    RecommendationRecord,
    compute,
    section,
    needs=(ManipulabilityRecord, StudyRecord),
    step="recommendation",
    files=write_files,
    json=to_json,
    holds=RANKED_GRID,
)
