"""Report part: the decision, first in the report — the recommended design beside the user's."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg.output.report.document import Section, change, table
from hexaleg.output.report.pareto import ParetoRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.recommendation import RecommendationRecord
from hexaleg.output.report.requirements import requirement_blocks
from hexaleg.output.report.statics import StaticsRecord
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.decide import DecideResult
from hexaleg.study.decide import decide as decide_from_requirements
from hexaleg.study.decision import RANKING_RULE, Decision, decide
from hexaleg.study.executors import local_pool
from hexaleg.study.recommendation import BAND


@dataclass(frozen=True)
class DecisionRecord:
    """The user's design beside the recommended one.

    Attributes:
        decision: Both designs' metrics, scores and payload capacities.
        requirements: The best design meeting the user's requirements, and the user's
            checked against them; ``None`` when none were given.

    """

    decision: Decision
    requirements: DecideResult | None = None


def compute(data: ReportData) -> DecisionRecord:
    """Score the user's design and the recommended one on the grid's scale."""
    return DecisionRecord(
        decide(
            data.design,
            data.model,
            StanceGeometry.from_model(data.model, "all"),
            data[RecommendationRecord].recommendation,
            data[StaticsRecord].axis.capacity.mass,
            data.options.decision,
        ),
        _requirements(data),
    )


def _requirements(data: ReportData) -> DecideResult | None:
    """The decision from the user's requirements, on the report's workers (none: ``None``)."""
    requirements = data.options.requirements
    if requirements is None:
        return None
    with local_pool(data.options.workers) as pool:
        return decide_from_requirements(data.design, requirements, executor=pool, progress=False)


METRIC_LABELS = {
    "improved_area": "improved workspace area [m²] (eq 16)",
    "average_manipulability": "average manipulability w_A [m³] (eq 27, improved domain)",
    "flexibility": "body flexibility FB [-] (eq 29, axis-locked)",
}
"""How the decision's table names each metric of the score."""


def section(data: ReportData) -> Section:
    """The answer first: the recommended design beside the user's, metric by metric."""
    rec = data[RecommendationRecord].recommendation
    design = data.design
    total = design.leg_length
    lengths = ", ".join(f"{r * total:.3f}" for r in (rec.l1_ratio, rec.l2_ratio, rec.l3_ratio))
    yours = ", ".join(f"{length:.3f}" for length in design.lengths)
    best = data[ParetoRecord].front.iloc[0]
    answer = data[DecisionRecord].requirements
    first = () if answer is None else (*requirement_blocks(answer), _WITHOUT_REQUIREMENTS)
    return Section(
        "Decision",
        (
            *first,
            f"**Recommended: l1 : l2 : l3 = {rec.l1_ratio:.3f} : {rec.l2_ratio:.3f} : "
            f"{rec.l3_ratio:.3f}**, for your {total:g} m leg **{lengths} m** (yours: {yours} m), "
            f"chosen among {data.options.decision.describe_candidates()}; any tibia ratio in "
            f"{rec.l3_band[0]:.3f}–{rec.l3_band[1]:.3f} keeps ≥ {BAND:.0%} of its score. Both "
            "designs keep your body, mounts and posture; the score divides each metric by its "
            "best value over the whole grid of section 5.",
            table(
                ["metric", "your design", "recommended", "recommended vs yours"],
                _rows(data[DecisionRecord].decision),
            ),
            "Counting payload capacity too, the Pareto front of section 5.1 recommends "
            f"l1 : l2 : l3 = {best['l1_ratio']:.3f} : {1 - best['l1_ratio'] - best['l3_ratio']:.3f}"
            f" : {best['l3_ratio']:.3f} ({best['l1']:.3f}, {best['l2']:.3f}, {best['l3']:.3f} m; "
            f"payload capacity {best['payload_capacity']:.1f} kg).",
            f"*How designs are ranked.* {RANKING_RULE}",
        ),
    )


def _rows(decision: Decision) -> list[tuple[str, str, str, str]]:
    rows = [
        (
            label,
            f"{decision.yours[name]:.4g}",
            f"{decision.recommended_metrics[name]:.4g}",
            change(decision.yours[name], decision.recommended_metrics[name]),
        )
        for name, label in METRIC_LABELS.items()
    ]
    rows.append(
        (
            "combined score [-] (1 = best of the grid in every metric)",
            f"{decision.your_score:.4f}",
            f"{decision.recommended_score:.4f}",
            change(decision.your_score, decision.recommended_score),
        )
    )
    rows.append(
        (
            "payload capacity [kg] (section 3.3; not in the score)",
            f"{decision.your_payload:.1f}",
            f"{decision.recommended_payload:.1f}",
            change(decision.your_payload, decision.recommended_payload),
        )
    )
    return rows


_WITHOUT_REQUIREMENTS = (
    "*Without your requirements*, ranking the paper's grid of segment ratios by workspace, "
    "manipulability and flexibility alone:"
)


def to_json(record: DecisionRecord) -> dict[str, Any]:
    """``decision``, and ``requirements_decision`` when requirements were given."""
    out = {"decision": record.decision.to_json()}
    if record.requirements is not None:
        out["requirements_decision"] = record.requirements.to_dict()
    return out


PART = Part(
    DecisionRecord,
    compute,
    section,
    needs=(RecommendationRecord, StaticsRecord, ParetoRecord),
    step="decision",
    json=to_json,
)
