"""Report part: the decision, first in the report — what to build, beside the user's design.

With requirements, the best design meeting them comes first
(:func:`hexaleg.study.decide.decide`, presented by :mod:`.requirements`). Then, or alone
without requirements, three legs side by side, each at its posture: your design as posed,
your lengths at their best posture (only the posture changes: the cheapest improvement),
and the recommended lengths at theirs (its own section), with their angles, body height
and every metric, scored by the one ranking rule (:mod:`hexaleg.study.ranking`). Every
number is one evaluation's (the recommendation's legs'): nothing is measured here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from hexaleg.design import HexapodDesign
from hexaleg.evaluation.metrics import METRICS, MetricSpec
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.report.document import Section, change, table
from hexaleg.output.report.flexibility import FlexibilityRecord
from hexaleg.output.report.pareto import ParetoRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.recommendation import RANKED_GRID, RecommendationRecord, band_text
from hexaleg.output.report.requirements import requirement_blocks
from hexaleg.output.report.robot import answer_lines, requirements_answer
from hexaleg.output.report.yours import YoursRecord, report_metrics
from hexaleg.paper import CLAIMED_L3_RATIO_PEAK
from hexaleg.ratios import proportions_text, ratio_text
from hexaleg.study.best_leg import Leg
from hexaleg.study.decide import DecideResult
from hexaleg.study.ranking import RANKED_METRICS, RANKING_RULE, ranked_columns, rule_note
from hexaleg.study.recommendation import Recommendation

SHOWN_APART = (METRICS.leg_length, METRICS.coxa_length, METRICS.nominal_height)
"""Metrics the Decision's table gives in its own rows (the lengths, the body height)."""


def decision_metrics(design: HexapodDesign) -> tuple[MetricSpec, ...]:
    """The Decision table's metrics: the ranked ones first, then every other one it has."""
    rest = [s for s in report_metrics(design) if s not in RANKED_METRICS and s not in SHOWN_APART]
    return (*RANKED_METRICS, *rest)


@dataclass(frozen=True)
class DecisionRecord:
    """The three legs side by side, and the answer to the user's requirements.

    Attributes:
        recommendation: The recommendation: your design as posed, your lengths re-posed and
            the recommended leg, each measured once.
        leg_length: The user's leg length, at which the ratios are lengths [m].
        requirements: The best design meeting the user's requirements, and the user's
            checked against them; ``None`` when none were given.

    """

    recommendation: Recommendation
    leg_length: float
    requirements: DecideResult | None = None


def compute(data: ReportData) -> DecisionRecord:
    """Decide from the user's requirements, if they gave some; the legs are the record's."""
    grid = data[RecommendationRecord]
    return DecisionRecord(grid.recommendation, grid.leg_length, requirements_answer(data))


def section(data: ReportData) -> Section:
    """The answer first: the requirements' if any, then the three legs side by side."""
    record = data[DecisionRecord]
    rec = record.recommendation
    design = data.design
    total = design.leg_length
    lengths = ", ".join(f"{r * total:.3f}" for r in (rec.l1_ratio, rec.l2_ratio, rec.l3_ratio))
    yours = ", ".join(f"{length:.3f}" for length in design.lengths)
    answer, gait = record.requirements, data.options.gait
    first = () if answer is None else (*requirement_blocks(answer), _WITHOUT_REQUIREMENTS)
    note = rule_note(rec.reference)
    return Section(
        "Decision",
        (
            *first,
            f"**Recommended: {proportions_text(rec.l1_ratio, rec.l2_ratio, rec.l3_ratio)}**, "
            f"for your {total:g} m leg **{lengths} m** standing at "
            f"θ = ({_angles(rec.best)}) rad (yours: {yours} m at θ = ({_angles(rec.yours)}) rad), "
            f"chosen among {data.options.decision.describe_candidates()}, every leg at its "
            f"best posture and walking {gait.named} ({gait.pattern} at {gait.speed:.2g} m/s). "
            f"{band_text(rec)} {_reposed(rec)} All three keep your body, mounts and ratings; "
            f"what changes is below. {departure(rec)}",
            _measured_under(data),
            table(
                [
                    "",
                    "your design as posed",
                    "your lengths re-posed",
                    "recommended",
                    "recommended vs yours",
                ],
                [*_leg_rows(rec), *_metric_rows(rec, design)],
            ),
            f"*How legs are ranked.* One rule for this section, the recommendation "
            f"(section {data.number(RecommendationRecord)}) and the Pareto front (section "
            f"{data.number(ParetoRecord)}): {RANKING_RULE}.{' ' + note if note else ''}",
        ),
    )


def _measured_under(data: ReportData) -> str:
    """What the three legs below are measured under (the requirements' answer: under them)."""
    spec = data[YoursRecord].spec
    slope = spec.walking_slope
    ground = (
        "level ground"
        if not slope
        else f"level ground, walking up, down and across a {math.degrees(slope):.3g}° slope"
    )
    mass = spec.conditions.payload.mass
    payload = "no payload" if mass == 0 else f"{mass:g} kg"
    above = (
        "" if data[DecisionRecord].requirements is None
        else " (the answer to your requirements above is measured under them)"
    )  # fmt: skip
    return (
        f"Each leg below stands at its own posture on {ground}, carrying {payload} and walking "
        f"{data.options.gait.named}{above}:"
    )


def _angles(leg: Leg) -> str:
    """A leg's posture θ1, θ2, θ3 [rad] as the report prints it."""
    return ", ".join(f"{a:.3f}" for a in leg.design.nominal_angles)


def _reposed(rec: Recommendation) -> str:
    """What posture alone gives your lengths (the cheapest improvement)."""
    reposed, yours = rec.reposed, rec.yours
    if reposed.design == yours.design:
        return "Your lengths are at their best posture already."
    walking = METRICS.walking_payload_capacity
    before, after = yours.evaluation.metrics, reposed.evaluation.metrics
    score = f"score {reposed.score:.4f}" if math.isfinite(reposed.score) else "no score"
    return (
        f"The cheapest improvement keeps your lengths and changes only the posture: at "
        f"θ = ({_angles(reposed)}) rad your leg has {score} and walks carrying "
        f"{walking.short(after.value(walking))} (as posed: "
        f"{walking.short(before.value(walking))})."
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


def _legs(rec: Recommendation) -> tuple[Leg, Leg, Leg]:
    """Your design as posed, your lengths re-posed, the recommended leg."""
    return rec.yours, rec.reposed, rec.best


def _leg_rows(rec: Recommendation) -> list[tuple[str, ...]]:
    """The legs' lengths, postures, body heights and scores."""
    legs = _legs(rec)
    height = METRICS.nominal_height
    heights = [leg.evaluation.metrics.value(height) for leg in legs]
    scores = [leg.score for leg in legs]
    return [
        ("lengths l1, l2, l3 [m]", *(", ".join(f"{v:.3f}" for v in leg.design.lengths)
                                     for leg in legs), ""),
        ("posture θ1, θ2, θ3 [rad]", *(_angles(leg) for leg in legs), ""),
        (height.described, *(height.cell(h) for h in heights), change(heights[0], heights[2])),
        ("score [-] (geometric mean of the paper's metrics, each relative to yours)",
         *(_score(s) for s in scores), change(scores[0], scores[2])),
    ]  # fmt: skip


def _score(value: float) -> str:
    """A score, or why a leg has none."""
    return f"{value:.4f}" if math.isfinite(value) else "none: fails the constraint"


def _metric_rows(rec: Recommendation, design: HexapodDesign) -> list[tuple[str, ...]]:
    """Every metric of the three legs; a joint's torque beside its rating."""
    rated = dict(zip(LEG_JOINTS, design.rated_torques or (math.nan,) * 3, strict=True))
    metrics = [leg.evaluation.metrics for leg in _legs(rec)]
    rows = []
    for spec in decision_metrics(design):
        label = spec.described
        if spec.joint is not None:  # a joint's torque: beside its rating
            label = f"{label}, rated {rated[spec.joint]:g} N·m"
        values = [m.value(spec) for m in metrics]
        rows.append((label, *(_cell(spec, v) for v in values), change(values[0], values[2])))
    return rows


def _cell(spec: MetricSpec, value: float) -> str:
    """A metric's cell; a dash where a leg has no value of it."""
    return spec.cell(value) if math.isfinite(value) else "—"


_WITHOUT_REQUIREMENTS = (
    "*Without your requirements*, ranking legs by walking the gait first and then by "
    "workspace, manipulability and flexibility alike, each at its best posture, one leg is "
    "recommended:"
)


def _leg_json(leg: Leg, leg_length: float) -> dict[str, Any]:
    """A leg: its lengths [m], posture [rad], metrics (SI) and score (null: none)."""
    return {
        "lengths_m": list(leg.design.lengths),
        "ratios": [v / leg_length for v in leg.design.lengths],
        "nominal_angles": list(leg.design.nominal_angles),
        "metrics": leg.evaluation.metrics.to_dict(),
        "score": leg.score if math.isfinite(leg.score) else None,
    }


def to_json(record: DecisionRecord) -> dict[str, Any]:
    """``decision`` (the rule and the three legs), ``requirements_decision`` if any."""
    rec, total = record.recommendation, record.leg_length
    out: dict[str, Any] = {
        "decision": {
            "rule": RANKING_RULE,
            "metrics": ranked_columns(),
            "yours": _leg_json(rec.yours, total),
            "reposed": _leg_json(rec.reposed, total),
            "recommended": _leg_json(rec.best, total),
        }
    }
    if record.requirements is not None:
        out["requirements_decision"] = record.requirements.to_dict()
    return out


def headline(data: ReportData) -> tuple[str, ...]:
    """The recommended ratios and posture, this design's FB, the requirements' lengths."""
    record = data[DecisionRecord]
    rec = record.recommendation
    fb = data[FlexibilityRecord].axis.fb
    return (
        f"recommended l1 : l2 : l3 = {rec.l1_ratio:.3f} : {rec.l2_ratio:.3f} : "
        f"{rec.l3_ratio:.3f} at θ = ({_angles(rec.best)}) rad (tibia ratio band "
        f"{rec.l3_band[0]:.3f}-{rec.l3_band[1]:.3f}); this design: FB = {fb:.4f}",
        *answer_lines(record.requirements, ".3f"),
    )


PART = Part(
    DecisionRecord,
    compute,
    section,
    needs=(RecommendationRecord, YoursRecord),
    step="decision",
    json=to_json,
    level=0,
    holds=RANKED_GRID,
    headline=headline,
)
