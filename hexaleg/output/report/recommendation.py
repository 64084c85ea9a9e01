"""Report part: the recommended leg and the evidence behind it (paper §4–6 combined).

One ranking rule (:mod:`hexaleg.study.ranking`) serves this section, the Pareto front and
the Decision section: what the robot must do first (walk the gait with its payload within
every rating), then the geometric mean of the paper's three metrics relative to the user's
design. The recommended leg and your lengths re-posed are searched with their posture free
(:mod:`hexaleg.study.recommendation`); each leg is measured once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from hexaleg.evaluation.metrics import METRICS
from hexaleg.output.report.document import Section, cell, table, write_csv
from hexaleg.output.report.manipulability import ManipulabilityRecord
from hexaleg.output.report.part import Part, ReportData, where_legs_are_the_designs
from hexaleg.output.report.study_record import StudyRecord
from hexaleg.output.report.yours import YoursRecord, report_metrics
from hexaleg.ratios import proportions_text, ratio_text
from hexaleg.study.best_leg import Leg, ranked_leg
from hexaleg.study.executors import local_pool
from hexaleg.study.ranking import RANKED_METRICS, RANKING_RULE, WalkingConstraint, rule_note
from hexaleg.study.recommendation import (
    BAND,
    CLIFF_MARGIN,
    NothingToRecommend,
    Recommendation,
    Searching,
    grid_ranking,
    recommendation,
)
from hexaleg.study.rows import StudyRow


@dataclass(frozen=True)
class RecommendationRecord:
    """The recommended leg, your lengths re-posed, and the study grid's ranking.

    Attributes:
        recommendation: The recommended leg, the band, the cliffs and the search's legs.
        leg_length: The design's leg length, at which the ratios are lengths [m].
        recommended: The recommended leg as a study row of its metrics (marked on the
            study's figures, at its own posture).

    """

    recommendation: Recommendation
    leg_length: float
    recommended: StudyRow


def compute(data: ReportData) -> RecommendationRecord:
    """Search the recommended leg and your best posture; rank the study's grid.

    Every ranked leg walks the gait carrying the required payload; if no allowed leg can,
    the legs are ranked walking it unloaded, and the recommendation says so.
    """
    constraint = data.options.decision.constraint
    try:
        rec = _recommended(data, constraint)
    except NothingToRecommend:
        if constraint.payload == 0:
            raise
        rec = replace(_recommended(data, WalkingConstraint()), relaxed=constraint)
    best = rec.best
    row = StudyRow(best.l1_ratio, best.l3_ratio, best.design.lengths, best.evaluation.metrics)
    return RecommendationRecord(rec, data.design.leg_length, row)


def _recommended(data: ReportData, constraint: WalkingConstraint) -> Recommendation:
    """The recommendation with every ranked leg meeting ``constraint``."""
    yours, options = data[YoursRecord], data.options.decision
    reference = yours.evaluation.metrics
    mine = ranked_leg(data.robot, yours.evaluation, constraint, reference)
    grid = grid_ranking(
        data[ManipulabilityRecord].average_map,
        data[StudyRecord].table,
        reference,
        constraint,
        data.design.leg_length,
    )
    searching = Searching(yours.spec, report_metrics(data.design), constraint, mine)
    with local_pool(data.options.workers) as pool:
        return recommendation(searching, options, grid, pool)


def section(data: ReportData) -> Section:
    """The rule, the grid's peaks, the legs searched at their best posture, the answer."""
    rec = data[RecommendationRecord].recommendation
    total = data.design.leg_length
    note = rule_note(rec.reference)
    return Section(
        "Recommendation",
        (
            f"Every leg is ranked by one rule: {RANKING_RULE}.{' ' + note if note else ''} "
            f"The design study stands every leg at your posture; among its legs that "
            f"{rec.constraint.describe(plural=True)}, where each metric and the score peak (the "
            "kinematic metrics' own peaks over every leg are in sections "
            f"{data.number(ManipulabilityRecord)} and {data.number(StudyRecord)}), and the "
            "best score each coxa ratio reaches:",
            table(
                [
                    "l1 ratio",
                    *(f"{spec.label} peak l3" for spec in RANKED_METRICS),
                    "score peak l3",
                    "best score",
                ],
                [_peak_row(r) for r in rec.peaks.to_dict(orient="records")],
            ),
            "A leg's lengths are judged at their best posture. At each allowed coxa ratio the "
            "tibia ratio and the hip and knee angles (within the stance limits) were searched "
            f"together, and your lengths with the angles alone ({rec.evaluations} legs "
            "measured, each once; DIRECT, then Nelder–Mead, feasibility first):",
            table(
                [
                    "leg",
                    "l1 : l2 : l3",
                    "θ2, θ3 [rad]",
                    "body height [m]",
                    "walking payload [kg]",
                    "FB",
                    "score",
                ],
                [
                    _leg_row("your lengths re-posed", rec.reposed),
                    *(_leg_row(f"best at coxa {leg.l1_ratio:.2f}", leg) for leg in rec.searched),
                ],
            ),
            _answer(rec, total),
        ),
    )


def _answer(rec: Recommendation, total: float) -> str:
    """The recommended leg, its posture, lengths, band and the cliffs beside it."""
    angles = ", ".join(f"{a:.3f}" for a in rec.nominal_angles)
    lengths = ", ".join(f"{r * total:.3f}" for r in (rec.l1_ratio, rec.l2_ratio, rec.l3_ratio))
    text = (
        f"**Recommended: {proportions_text(rec.l1_ratio, rec.l2_ratio, rec.l3_ratio)}** "
        f"standing at θ = ({angles}) rad (score {rec.score:.4f} against your design's 1; for "
        f"a {total:g} m leg: {lengths} m). {band_text(rec)}"
    )
    return (
        text + " Choose within the band by what these metrics leave out (ground clearance, "
        "speed, mass), or give those as requirements (`hexaleg decide`, `report --payload …`)."
    )


def relaxed_text(rec: Recommendation) -> str:
    """Why the ranking walks the gait unloaded though a payload was required (or nothing)."""
    if rec.relaxed is None:
        return ""
    return (
        f"No allowed leg {rec.relaxed.describe()}, even at its best posture: the legs are "
        f"ranked by what they can do, {rec.constraint.describe()}. "
    )


def band_text(rec: Recommendation) -> str:
    """The band in words, where the cliffs beside it are, and any step back from one."""
    low, high = rec.l3_band
    margin = f"{CLIFF_MARGIN:.2f} ({CLIFF_MARGIN:.0%} of the leg)"
    text = relaxed_text(rec)
    text += (
        f"At this coxa ratio and posture, any tibia ratio in {ratio_text(low)}–"
        f"{ratio_text(high)} keeps ≥ {BAND:.0%} of its score, still {rec.constraint.describe()} "
        f"and lies at least {margin} from a cliff where that stops holding."
    )
    if rec.cliffs:
        text += " The walk stops holding " + "; and ".join(c.describe() for c in rec.cliffs) + "."
    stepped = rec.stepped_back
    if stepped is not None:
        text += (
            f" The search's best at this coxa ratio, tibia ratio {ratio_text(stepped.l3_ratio)} "
            f"(score {stepped.score:.4f}), sat within {margin} of a cliff: the recommendation "
            "steps back to the best leg clear of it."
        )
    return text


NO_WALKER = "no leg at this coxa ratio meets the constraint"
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


def _leg_row(name: str, leg: Leg) -> list[str]:
    """A searched leg: its proportions, posture, height, walking payload, FB and score."""
    design, metrics = leg.design, leg.evaluation.metrics
    ratios = (design.l1, design.l2, design.l3)
    return [
        name,
        " : ".join(ratio_text(v / design.leg_length) for v in ratios),
        ", ".join(f"{a:.3f}" for a in design.nominal_angles[1:]),
        f"{metrics.value(METRICS.nominal_height):.3f}",
        f"{leg.capacity:.1f}",
        f"{metrics.value(METRICS.fb):.4f}",
        cell(leg.score, lambda v: f"{v:.4f}", "not ranked: " + (leg.limited_by or "it fails")),
    ]


def write_files(data: ReportData, out: Path) -> None:
    """``recommendation_scores.csv``: the grid's metrics, relative to yours, and scores."""
    scores = data[RecommendationRecord].recommendation.scores
    write_csv(out / "recommendation_scores.csv", scores.to_dict(orient="records"))


def _leg_json(leg: Leg) -> dict[str, Any]:
    """A leg: its posture [rad], metrics (SI) and score (null: none)."""
    return {
        "nominal_angles": list(leg.design.nominal_angles),
        "lengths_m": list(leg.design.lengths),
        "metrics": leg.evaluation.metrics.to_dict(),
        "score": leg.score if math.isfinite(leg.score) else None,
        "meets_constraint": leg.meets,
    }


def to_json(record: RecommendationRecord) -> dict[str, Any]:
    """``recommendation``: the rule, the leg, its posture and band, the cliffs, your best."""
    rec, total = record.recommendation, record.leg_length
    reposed = _leg_json(rec.reposed)
    return {
        "recommendation": {
            "rule": RANKING_RULE,
            "constraint": {"payload": rec.constraint.payload, "words": rec.constraint.describe()},
            "relaxed_from": None if rec.relaxed is None else rec.relaxed.payload,
            "l1_ratio": rec.l1_ratio,
            "l2_ratio": rec.l2_ratio,
            "l3_ratio": rec.l3_ratio,
            "nominal_angles": list(rec.nominal_angles),
            "l3_band": list(rec.l3_band),
            "cliff_margin": CLIFF_MARGIN,
            "cliffs": [c.to_dict() for c in rec.cliffs],
            "metrics": rec.metrics.to_dict(),
            "score": rec.score,
            "reference": rec.reference.to_dict(),
            "reference_best": {k: reposed[k] for k in ("nominal_angles", "metrics", "score")},
            "searched": [_leg_json(leg) for leg in rec.searched],
            "evaluations": rec.evaluations,
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
    needs=(ManipulabilityRecord, StudyRecord, YoursRecord),
    step="recommendation",
    files=write_files,
    json=to_json,
    holds=RANKED_GRID,
)
