"""Report part: the decision, first in the report — what to build, beside the user's design.

With requirements, the best design meeting them comes first
(:func:`hexaleg.study.decide.decide`, presented by :mod:`.requirements`). Then, or
alone without requirements, the one recommendation of the grid (its own section) beside the
user's design, metric by metric, scored by the one ranking rule
(:mod:`hexaleg.study.ranking`), and the rule itself.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg.output.report.document import Section, change, table
from hexaleg.output.report.pareto import ParetoRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.recommendation import RecommendationRecord
from hexaleg.output.report.requirements import requirement_blocks
from hexaleg.study.decide import DecideResult, decide
from hexaleg.study.executors import local_pool
from hexaleg.study.metrics import METRICS
from hexaleg.study.ranking import RANKED_METRICS, RANKING_RULE, score
from hexaleg.study.recommendation import BAND, Recommendation


@dataclass(frozen=True)
class DecisionRecord:
    """The recommendation beside the user's design, and the answer to their requirements.

    Attributes:
        recommendation: The grid's one recommendation, with the user's
            design's metrics it is scored against.
        leg_length: The user's leg length, at which the ratios are lengths [m].
        requirements: The best design meeting the user's requirements, and the user's
            checked against them; ``None`` when none were given.

    """

    recommendation: Recommendation
    leg_length: float
    requirements: DecideResult | None = None


def compute(data: ReportData) -> DecisionRecord:
    """Decide from the user's requirements, on the report's workers, if they gave some."""
    grid = data[RecommendationRecord]
    requirements = data.options.requirements
    if requirements is None:
        return DecisionRecord(grid.recommendation, grid.leg_length)
    with local_pool(data.options.workers) as pool:
        answer = decide(data.design, requirements, executor=pool, progress=False)
    return DecisionRecord(grid.recommendation, grid.leg_length, answer)


def section(data: ReportData) -> Section:
    """The answer first: the requirements' if any, then the recommended design beside yours."""
    rec = data[DecisionRecord].recommendation
    design = data.design
    total = design.leg_length
    lengths = ", ".join(f"{r * total:.3f}" for r in (rec.l1_ratio, rec.l2_ratio, rec.l3_ratio))
    yours = ", ".join(f"{length:.3f}" for length in design.lengths)
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
            "designs keep your body, mounts and posture.",
            table(["metric", "your design", "recommended", "recommended vs yours"], _rows(rec)),
            f"*How designs are ranked.* One rule for this section, the recommendation "
            f"(section {data.number(RecommendationRecord)}) and the Pareto front (section "
            f"{data.number(ParetoRecord)}): {RANKING_RULE}.",
        ),
    )


def _rows(rec: Recommendation) -> list[tuple[str, str, str, str]]:
    yours, theirs = rec.reference, rec.metrics
    rows = [
        (
            METRICS[name].described,
            f"{yours[name]:.4g}",
            f"{theirs[name]:.4g}",
            change(yours[name], theirs[name]),
        )
        for name in RANKED_METRICS
    ]
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
            "yours": {"metrics": rec.reference, "score": score(rec.reference, rec.reference)},
            "recommended": {
                "lengths_m": [r * leg_length for r in (rec.l1_ratio, rec.l2_ratio, rec.l3_ratio)],
                "metrics": rec.metrics,
                "score": rec.score,
            },
            "metrics": list(RANKED_METRICS),
        }
    }
    if record.requirements is not None:
        out["requirements_decision"] = record.requirements.to_dict()
    return out


PART = Part(
    DecisionRecord,
    compute,
    section,
    needs=(RecommendationRecord,),
    step="decision",
    json=to_json,
    level=0,
)
