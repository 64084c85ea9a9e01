"""Report part: the Pareto front of the paper's metrics among the legs that walk, ranked."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from hexaleg.evaluation.metrics import METRICS
from hexaleg.output.figures import pareto_figure, save
from hexaleg.output.report.document import Figure, Section, table, write_csv
from hexaleg.output.report.manipulability import ManipulabilityRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.recommendation import RANKED_GRID, RecommendationRecord
from hexaleg.output.report.study_record import StudyRecord
from hexaleg.ratios import proportions_text, ratio_text
from hexaleg.study.pareto import pareto_front
from hexaleg.study.ranking import RANKED_METRICS


@dataclass(frozen=True)
class ParetoRecord:
    """The designs of the grid that walk and that no other beats in area, w_A and FB.

    Attributes:
        front: One row per front design, best score first (the first is the grid's best,
            which the recommendation refines).

    """

    front: pd.DataFrame


def compute(data: ReportData) -> ParetoRecord:
    """The front among the study's designs at the allowed coxa ratios, ranked by the rule."""
    return ParetoRecord(
        pareto_front(
            data[ManipulabilityRecord].average_map,
            data[StudyRecord].table,
            data[RecommendationRecord].recommendation,
            data.options.decision,
        )
    )


def section(data: ReportData) -> Section:
    """The Pareto front of the paper's metrics among the legs that walk, ranked by the rule."""
    front = data[ParetoRecord].front
    rec = data[RecommendationRecord].recommendation
    best = front.iloc[0]
    l2_ratio = 1 - best["l1_ratio"] - best["l3_ratio"]
    proportions = proportions_text(best["l1_ratio"], l2_ratio, best["l3_ratio"])
    recommended = data.number(RecommendationRecord)
    rows = [
        (
            f"{r['l1_ratio']:.2f}",
            ratio_text(r["l3_ratio"]),
            *(spec.cell(r[spec.name]) for spec in RANKED_METRICS),
            METRICS.walking_payload_capacity.cell(r[METRICS.walking_payload_capacity.name]),
            f"{r['score']:.4f}",
        )
        for r in front.head(12).to_dict(orient="records")
    ]
    return Section(
        "Pareto front: workspace, manipulability and flexibility among the legs that walk",
        (
            f"Among the sweep's designs at the allowed coxa ratios (as in section "
            f"{recommended}), each at your posture, {len(front)} "
            f"{rec.constraint.describe(plural=len(front) != 1)} ({data.options.gait.named})"
            f" and {'are' if len(front) != 1 else 'is'} beaten by no other in improved area, "
            "w_A and FB at once (their walking "
            "payload is shown, not ranked: walking is the constraint). The grid is dense and "
            "every metric on it exact, so the front is read off it directly (no evolutionary "
            f"search could be more exact). The front is ranked by the rule of section "
            f"{recommended} (each score relative to your design's 1); a design that beats "
            f"another in every metric also scores higher, so its first, {proportions}, is the "
            f"grid's best point at your posture; section {recommended} searches each leg at "
            "its own best posture for the one recommendation.",
            table(
                [
                    "l1 ratio",
                    "l3 ratio",
                    "area [m²]",
                    "w_A [m³]",
                    "FB",
                    "walking payload [kg]",
                    "score",
                ],
                rows,
            ),
            Figure(
                "pareto_front",
                "Body flexibility against walking payload capacity for every design of the "
                "sweep; the front and its best grid point marked, your design beside them, the "
                "largest capacity named",
            ),
        ),
    )


def write_files(data: ReportData, out: Path) -> None:
    """The front figure and ``pareto_front.csv``."""
    front = data[ParetoRecord].front
    save(
        pareto_figure(
            data[StudyRecord].table, front, data[RecommendationRecord].recommendation.reference
        ),
        out / "pareto_front.png",
        svg=data.options.svg,
    )
    write_csv(out / "pareto_front.csv", front.to_dict(orient="records"))


def to_json(record: ParetoRecord) -> dict[str, Any]:
    """``pareto_front``."""
    return {"pareto_front": record.front.to_dict(orient="records")}


PART = Part(
    ParetoRecord,
    compute,
    section,
    needs=(ManipulabilityRecord, StudyRecord, RecommendationRecord),
    step="Pareto front",
    files=write_files,
    json=to_json,
    level=2,
    holds=RANKED_GRID,
)
