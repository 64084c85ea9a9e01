"""Report part: the decision, first in the report — what to build, beside the user's design.

With requirements, the best design meeting them comes first
(:func:`hexaleg.study.decide.decide`, presented by :mod:`.requirements`). Then, or
alone without requirements, the one recommendation of the grid (its own section) beside the
user's design, metric by metric, scored by the one ranking rule
(:mod:`hexaleg.study.ranking`), and the rule itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from hexaleg.design import HexapodDesign
from hexaleg.evaluation.evaluate import Evaluation, evaluate
from hexaleg.evaluation.metrics import METRICS, MetricSpec
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.report.document import Section, change, table
from hexaleg.output.report.flexibility import FlexibilityRecord
from hexaleg.output.report.pareto import ParetoRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.recommendation import RANKED_GRID, RecommendationRecord
from hexaleg.output.report.requirements import requirement_blocks
from hexaleg.output.report.robot import answer_lines, requirements_answer
from hexaleg.paper import CLAIMED_L3_RATIO_PEAK
from hexaleg.ratios import proportions_text, ratio_text
from hexaleg.study.decide import DecideResult
from hexaleg.study.ranking import RANKED_METRICS, RANKING_RULE, ranked_columns, score
from hexaleg.study.recommendation import BAND, Recommendation

COSTS: tuple[MetricSpec, ...] = (
    METRICS.nominal_height,
    METRICS.stability_margin,
    METRICS.min_zmp_margin,
    *(spec for spec in METRICS if spec.torque is not None),
    METRICS.max_speed,
    METRICS.mechanical_energy_per_km,
    METRICS.payload_capacity,
)
"""What the choice costs, beside the scored metrics: the body's height and stability, the
report's gait's ZMP margin, torques, speed and energy, and the standing payload capacity."""


def cost_metrics(design: HexapodDesign) -> tuple[MetricSpec, ...]:
    """:data:`COSTS`, and with actuators the energy per km drawn through them."""
    return COSTS + ((METRICS.energy_per_km,) if design.actuators is not None else ())


@dataclass(frozen=True)
class DecisionRecord:
    """The recommendation beside the user's design, and the answer to their requirements.

    Attributes:
        recommendation: The grid's one recommendation, with the user's
            design's metrics it is scored against.
        leg_length: The user's leg length, at which the ratios are lengths [m].
        yours: The user's design's :func:`cost_metrics`, walking the report's gait.
        recommended: The recommended design's :func:`cost_metrics`, the same way.
        requirements: The best design meeting the user's requirements, and the user's
            checked against them; ``None`` when none were given.

    """

    recommendation: Recommendation
    leg_length: float
    yours: Evaluation
    recommended: Evaluation
    requirements: DecideResult | None = None


def compute(data: ReportData) -> DecisionRecord:
    """What the choice costs; decide from the user's requirements, if they gave some."""
    grid = data[RecommendationRecord]
    rec = grid.recommendation
    theirs = data.robot.at_ratios(rec.l1_ratio, rec.l3_ratio)
    metrics, conditions = cost_metrics(data.design), data.options.decision.conditions
    costs = [evaluate(r.design, metrics, conditions, model=r.model) for r in (data.robot, theirs)]
    return DecisionRecord(rec, grid.leg_length, costs[0], costs[1], requirements_answer(data))


def section(data: ReportData) -> Section:
    """The answer first: the requirements' if any, then the recommended design beside yours."""
    record = data[DecisionRecord]
    rec = record.recommendation
    design = data.design
    total = design.leg_length
    lengths = ", ".join(f"{r * total:.3f}" for r in (rec.l1_ratio, rec.l2_ratio, rec.l3_ratio))
    yours = ", ".join(f"{length:.3f}" for length in design.lengths)
    answer, gait = record.requirements, data.options.gait
    first = () if answer is None else (*requirement_blocks(answer), _WITHOUT_REQUIREMENTS)
    return Section(
        "Decision",
        (
            *first,
            f"**Recommended: {proportions_text(rec.l1_ratio, rec.l2_ratio, rec.l3_ratio)}**, "
            f"for your {total:g} m leg **{lengths} m** (yours: {yours} m), "
            f"chosen among {data.options.decision.describe_candidates()}, every one walking "
            f"{gait.named} ({gait.pattern} at {gait.speed:.2g} m/s); any tibia ratio in "
            f"{ratio_text(rec.l3_band[0])}–{ratio_text(rec.l3_band[1])} keeps "
            f"≥ {BAND:.0%} of its score and walks. Both keep your body, mounts, posture and "
            f"ratings; what changes is below. {departure(rec)}",
            table(
                ["metric", "your design", "recommended", "recommended vs yours"],
                [*_rows(rec), *_cost_rows(record, design)],
            ),
            f"*How designs are ranked.* One rule for this section, the recommendation "
            f"(section {data.number(RecommendationRecord)}) and the Pareto front (section "
            f"{data.number(ParetoRecord)}): {RANKING_RULE}.",
        ),
    )


def departure(rec: Recommendation) -> str:
    """One sentence: where the recommendation sits against the paper's chosen tibia band."""
    low, high = CLAIMED_L3_RATIO_PEAK
    band = f"the paper's chosen tibia ratios {low:.2f}–{high:.2f}"
    if low <= rec.l3_ratio <= high:
        return f"Its tibia ratio {ratio_text(rec.l3_ratio)} lies within {band}."
    side = "above" if rec.l3_ratio > high else "below"
    theirs, yours = rec.metrics, rec.reference
    changes = {
        spec: math.log(theirs.value(spec) / yours.value(spec))
        for spec in RANKED_METRICS
        if theirs.value(spec) > 0 < yours.value(spec)
    }
    gain = max(changes, key=lambda spec: changes[spec])
    lost = [spec.label for spec, value in changes.items() if value < 0]
    cost = f", giving up {' and '.join(lost)}" if lost else ""
    return (
        f"Its tibia ratio {ratio_text(rec.l3_ratio)} lies {side} {band} (chosen there for FB): the "
        f"score moves it because its {gain.label} "
        f"{change(yours.value(gain), theirs.value(gain))} outweighs the rest{cost}."
    )


def _rows(rec: Recommendation) -> list[tuple[str, ...]]:
    """The scored metrics of both designs, and their scores."""
    yours, theirs = rec.reference, rec.metrics
    rows = [_compared(spec, yours.value(spec), theirs.value(spec)) for spec in RANKED_METRICS]
    your_score = score(yours, yours)
    rows.append(
        (
            "score [-] (geometric mean of the four, each relative to yours)",
            f"{your_score:.4f}",
            f"{rec.score:.4f}",
            change(your_score, rec.score),
        )
    )
    return rows


def _cost_rows(record: DecisionRecord, design: HexapodDesign) -> list[tuple[str, ...]]:
    """The costs of the choice, a torque beside its rating, a speed beside what binds."""
    rated = dict(zip(LEG_JOINTS, design.rated_torques or (math.nan,) * 3, strict=True))
    yours, theirs = record.yours.metrics, record.recommended.metrics
    rows = []
    for spec in cost_metrics(design):
        row = _compared(spec, yours.value(spec), theirs.value(spec))
        if spec.joint is not None:  # a joint's torque: beside its rating
            row = (f"{row[0]}, rated {rated[spec.joint]:g} N·m", *row[1:])
        rows.append(row)
    return rows


def _compared(spec: MetricSpec, yours: float, theirs: float) -> tuple[str, ...]:
    """A metric's row: what it is [unit], your design's value, the other's, the change."""
    return (spec.described, spec.cell(yours), spec.cell(theirs), change(yours, theirs))


_WITHOUT_REQUIREMENTS = (
    "*Without your requirements*, ranking the paper's grid of segment ratios by workspace, "
    "manipulability, flexibility and payload capacity alike, one design is recommended:"
)


def to_json(record: DecisionRecord) -> dict[str, Any]:
    """``decision`` (the rule, yours and the recommended), ``requirements_decision`` if any."""
    rec, leg_length = record.recommendation, record.leg_length
    out: dict[str, Any] = {
        "decision": {
            "rule": RANKING_RULE,
            "yours": {
                "metrics": rec.reference.to_dict(),
                "score": score(rec.reference, rec.reference),
            },
            "recommended": {
                "lengths_m": [r * leg_length for r in (rec.l1_ratio, rec.l2_ratio, rec.l3_ratio)],
                "metrics": rec.metrics.to_dict(),
                "score": rec.score,
            },
            "metrics": ranked_columns(),
            "costs": {
                "yours": record.yours.metrics.to_dict(),
                "recommended": record.recommended.metrics.to_dict(),
            },
        }
    }
    if record.requirements is not None:
        out["requirements_decision"] = record.requirements.to_dict()
    return out


def headline(data: ReportData) -> tuple[str, ...]:
    """The recommended ratios, this design's FB, and the lengths meeting the requirements."""
    record = data[DecisionRecord]
    rec = record.recommendation
    fb = data[FlexibilityRecord].axis.fb
    return (
        f"recommended l1 : l2 : l3 = {rec.l1_ratio:.3f} : {rec.l2_ratio:.3f} : "
        f"{rec.l3_ratio:.3f} (tibia ratio band {rec.l3_band[0]:.3f}-{rec.l3_band[1]:.3f}); "
        f"this design: FB = {fb:.4f}",
        *answer_lines(record.requirements, ".3f"),
    )


PART = Part(
    DecisionRecord,
    compute,
    section,
    needs=(RecommendationRecord,),
    step="decision",
    json=to_json,
    level=0,
    holds=RANKED_GRID,
    headline=headline,
)
