"""Report part: the recommended ratios and the evidence behind them (paper §4–6 combined)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.output.report.document import Section, table, write_csv
from hexaleg.output.report.manipulability import ManipulabilityRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.study import StudyRecord
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.decision import grid_recommendation
from hexaleg.study.recommendation import BAND, Recommendation


@dataclass(frozen=True)
class RecommendationRecord:
    """The recommendation on the study's grid.

    Attributes:
        recommendation: Recommended ratios, the band, and the scores behind them.
        leg_length: The design's leg length, at which the ratios are lengths [m].

    """

    recommendation: Recommendation
    leg_length: float


def compute(data: ReportData) -> RecommendationRecord:
    """Recommend ratios from area, w_A and FB on the grid of the study."""
    template = StanceGeometry.from_model(data.model, "all")
    return RecommendationRecord(
        grid_recommendation(
            data.design,
            template,
            data[ManipulabilityRecord].average_map,
            data[StudyRecord].table,
            data.options.decision,
        ),
        data.design.leg_length,
    )


def section(data: ReportData) -> Section:
    """The recommended ratios and the evidence behind them."""
    rec = data[RecommendationRecord].recommendation
    total = data.design.leg_length
    return Section(
        "5. Recommendation",
        (
            "Each metric on the same grid — improved workspace area (eq 16), average "
            "manipulability on the improved domain (eq 27), and axis-locked body flexibility "
            "(eq 29) — is divided by its best value over the whole grid, and the three are "
            "averaged with equal weights, so scores compare across coxa ratios. Where each "
            "peaks, and the best score each coxa ratio reaches:",
            table(
                [
                    "l1 ratio",
                    "area peak l3",
                    "w_A peak l3",
                    "FB peak l3",
                    "combined peak l3",
                    "best combined score",
                ],
                [
                    (
                        f"{r['l1_ratio']:.2f}",
                        f"{r['improved_area_peak_l3_ratio']:.3f}",
                        f"{r['average_manipulability_peak_l3_ratio']:.3f}",
                        f"{r['flexibility_peak_l3_ratio']:.3f}",
                        f"{r['combined_peak_l3_ratio']:.3f}",
                        f"{r['combined_best_score']:.4f}",
                    )
                    for r in rec.peaks.to_dict(orient="records")
                ],
            ),
            "Every metric grows as the coxa shrinks (Table 5, sections 2 and 3.1), so the coxa "
            "should be as short as the root actuator's packaging allows. The recommendation "
            "takes the best score among the allowed coxa ratios, its tibia ratio refined "
            "between grid points with every metric computed exactly:",
            f"**Recommended: l1 : l2 : l3 = {rec.l1_ratio:.3f} : {rec.l2_ratio:.3f} : "
            f"{rec.l3_ratio:.3f}** (score {rec.score:.4f}; for a {total:g} m leg: "
            f"{rec.l1_ratio * total:.3f} m, "
            f"{rec.l2_ratio * total:.3f} m, {rec.l3_ratio * total:.3f} m). Any tibia ratio in "
            f"{rec.l3_band[0]:.3f}–{rec.l3_band[1]:.3f} keeps ≥ {BAND:.0%} of the best combined "
            "score; choose within it by the constraints these metrics leave out (ground "
            "clearance, actuator torque, mass).",
        ),
    )


def write_files(data: ReportData, out: Path) -> None:
    """``recommendation_scores.csv``: normalized metrics and score on the whole grid."""
    scores = data[RecommendationRecord].recommendation.scores
    write_csv(out / "recommendation_scores.csv", scores.to_dict(orient="records"))


def to_json(record: RecommendationRecord) -> dict[str, Any]:
    """``recommendation`` (ratios, band, score, maxima, peaks; lengths for the design's leg)."""
    rec, total = record.recommendation, record.leg_length
    return {
        "recommendation": {
            "l1_ratio": rec.l1_ratio,
            "l2_ratio": rec.l2_ratio,
            "l3_ratio": rec.l3_ratio,
            "l3_band": list(rec.l3_band),
            "score": rec.score,
            "maxima": rec.maxima,
            "peaks": rec.peaks.to_dict(orient="records"),
            "lengths_m": [rec.l1_ratio * total, rec.l2_ratio * total, rec.l3_ratio * total],
        }
    }


PART = Part(
    RecommendationRecord,
    compute,
    section,
    needs=(ManipulabilityRecord, StudyRecord),
    step="recommendation",
    files=write_files,
    json=to_json,
)
