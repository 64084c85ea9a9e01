"""Report part: walking, the grid walking the report's gait against the sequel's claim.

Presentation only: the numbers come from the study's ``gait_*`` columns and from
:func:`hexaleg.study.walking.walking_comparison` (the grid's least-torque and least-energy
legs against the paper's 0.2/0.4/0.4 leg, pure data).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.evaluation.metrics import METRICS
from hexaleg.output.figures.canvas import save
from hexaleg.output.figures.gait import walking_study_figure
from hexaleg.output.report.document import Figure, Section, table
from hexaleg.output.report.marks import rated_torques, study_marks
from hexaleg.output.report.motors import MotorsRecord, summary
from hexaleg.output.report.part import Part, ReportData, where_legs_are_the_designs
from hexaleg.output.report.study_record import StudyRecord
from hexaleg.output.report.yours import standing_text
from hexaleg.study.rows import StudyRow
from hexaleg.study.walking import ENERGY, TORQUE, WalkingComparison, walking_or_none

FIGURE = "study_walking"


@dataclass(frozen=True)
class WalkingRecord:
    """The grid's best walking legs against the paper's (None: no design walks the gait).

    Attributes:
        comparison: The comparison, or None.

    """

    comparison: WalkingComparison | None


def compute(data: ReportData) -> WalkingRecord:
    """Compare the study's walking columns with the paper's leg on this design's body."""
    study = data[StudyRecord]
    return WalkingRecord(walking_or_none(study.table, study.spec, study.yours))


def section(data: ReportData) -> Section:
    """The gait, the best walking legs against the paper's, the claim, and the figure."""
    comparison = data[WalkingRecord].comparison
    title = "Walking: what a gait period costs"
    named = data.options.gait.named
    if comparison is None:
        return Section(title, (f"No design of the grid walks {named}.",))
    gait = comparison.gait
    rows = [
        _row("the paper's leg", comparison.reference),
        _row("least peak torque", comparison.least_torque),
        _row("least cost of transport", comparison.least_energy),
    ]
    return Section(
        title,
        (
            f"Every design of the grid, {standing_text(data[StudyRecord].spec)}, walks one "
            f"period of {named}: a "
            f"{gait['pattern']} at {gait['speed']:.2g} m/s (period {gait['period']:g} s, stride "
            f"{gait['stride']:g} m, step height {gait['step_height']:g} m), no payload; "
            f"{comparison.walking} of the {comparison.designs} designs walk it within every "
            "rating (the others break a stance limit, their reach or a rating on the way); the "
            "legs below are chosen among those. Torques from Pinocchio's inverse dynamics on "
            "the whole robot, the standing feet sharing the load by least forces; `hexaleg "
            "gait` walks any gait with any payload.",
            table(
                [
                    "leg",
                    "l1/L",
                    "l3/L",
                    "peak torque [N·m]",
                    "cost of transport",
                    "max speed [m/s]",
                ],
                rows,
            ),
            _claim(comparison),
            *_motors(data),
            Figure(
                FIGURE,
                f"Walking {named}, {standing_text(data[StudyRecord].spec)}: peak hip and knee "
                "torque beside their ratings, "
                "mechanical cost of transport and walking payload capacity against the tibia "
                "ratio, for each coxa ratio (gaps: designs that cannot walk it unloaded); your "
                "design and the recommended leg (at its own posture) marked",
            ),
        ),
    )


def _motors(data: ReportData) -> tuple[str, ...]:
    """The user's design through its motors, in one sentence (none without actuators)."""
    line = summary(data[MotorsRecord])
    return (line + " The next section has every margin to the motors' ratings.",) if line else ()


def _row(name: str, row: StudyRow) -> list[str]:
    metrics = row.metrics
    return [
        name,
        f"{row.l1_ratio:.3g}",
        f"{row.l3_ratio:.3g}",
        f"{metrics.value(TORQUE):.1f}",
        f"{metrics.value(ENERGY):.4f}",
        f"{metrics.value(METRICS.max_speed):.3f}",
    ]


def _claim(comparison: WalkingComparison) -> str:
    """The sequel's claim, and what the grid shows, whatever it is."""
    torque, energy = comparison.torque_saving, comparison.energy_saving
    if math.isnan(torque) or math.isnan(energy):
        return (
            "The paper's 0.2/0.4/0.4 leg cannot walk this gait, so the sequel's claim (an "
            "optimized leg cutting peak joint torque and energy by over 20 %) has no "
            "reference here."
        )
    energy_of_torque, torque_of_energy = comparison.cross_savings
    return (
        "The sequel (Liu et al., *Dynamic Modeling and Dimensional Optimization of Legged "
        "Mechanisms for Construction Robots*) reports that optimizing the segment lengths "
        "cuts peak joint torque and energy by over 20 %. On this grid, walking this gait, "
        f"the least-torque leg needs {_less(torque)} peak torque than the paper's leg and "
        f"{_less(energy_of_torque)} energy (cost of transport), the least-energy leg "
        f"{_less(energy)} energy and {_less(torque_of_energy)} peak torque: "
        f"{_verdict(torque, energy)}.{_reference_rated(comparison)} {_why(comparison)}"
    )


def _less(saving: float) -> str:
    """A saving [-] in words: ``"64 % less"``, or ``"157 % more"`` when it is a cost."""
    percent = 100 * saving
    return f"{abs(percent):.0f} % " + ("less" if percent >= 0 else "more")


def _verdict(torque: float, energy: float) -> str:
    """Which of the two savings reach the sequel's 20 %."""
    if torque > 0.2 and energy > 0.2:
        return "both savings exceed the sequel's 20 %"
    if torque > 0.2:
        return "the torque saving exceeds the sequel's 20 %, the energy saving does not"
    if energy > 0.2:
        return "the energy saving exceeds the sequel's 20 %, the torque saving does not"
    return "neither saving reaches the sequel's 20 %"


def _reference_rated(comparison: WalkingComparison) -> str:
    """A sentence if the paper's leg itself walks the gait only beyond its ratings."""
    if bool(comparison.reference.columns.get("walks", True)):
        return ""
    return " (The paper's leg walks this gait only beyond its own ratings.)"


def _why(comparison: WalkingComparison) -> str:
    """Which joint carries the peak, how the best leg differs, and what it gives up."""
    reference, best = comparison.reference, comparison.least_torque
    peaks = reference.metrics.joint_torques("peak")
    joint = max(peaks, key=lambda j: peaks[j] or 0.0)  # the paper's leg walks: each is a number
    femur = 1 - best.l1_ratio - best.l3_ratio
    paper_femur = 1 - reference.l1_ratio - reference.l3_ratio
    speed, paper_speed = (row.metrics.value(METRICS.max_speed) for row in (best, reference))
    return (
        f"The paper's leg's peak is at its {joint}; the least-torque leg's femur is "
        f"{femur:.2f} of the leg against {paper_femur:.2f}, and it walks "
        + ("slower" if speed < paper_speed else "at least as fast")
        + f" within its ratings ({speed:.2f} against {paper_speed:.2f} m/s, "
        f"{best.columns['max_speed_limited_by']})."
    )


def write_files(data: ReportData, out: Path) -> None:
    """The study's peak torque and cost of transport against tibia ratio."""
    study = data[StudyRecord]
    figure = walking_study_figure(
        study.table,
        rated_torques(data),
        study_marks(data),
        data.options.gait,
        standing_text(study.spec).replace("standing ", "", 1),
    )
    save(figure, out / f"{FIGURE}.png", svg=data.options.svg)


def to_json(record: WalkingRecord) -> dict[str, Any]:
    """``walking``: the comparison (null when no design walks the gait)."""
    return {"walking": None if record.comparison is None else record.comparison.to_dict()}


PART = Part(
    WalkingRecord,
    compute,
    section,
    needs=(StudyRecord, MotorsRecord),
    step="walking",
    files=write_files,
    json=to_json,
    level=2,
    holds=where_legs_are_the_designs(
        "Walking comparison with the paper's leg", "there is no paper's leg on your robot's body"
    ),
)
