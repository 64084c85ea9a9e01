"""Report parts of an imported robot: the study of its segments, the decision over them.

Beside :mod:`~hexaleg.output.report.robot`: the study sweeps the robot's coxa and tibia
ratios at its own leg length, each row its file with every leg's segments changed
(:mod:`~hexaleg.study.robot_designs`); with requirements, the decision searches its
segments around its own (:func:`~hexaleg.study.decide.decide`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from hexaleg.design import l3_ratio_grid
from hexaleg.output.figures import write_study_figures
from hexaleg.output.figures.marks import Mark
from hexaleg.output.report.document import Figure, Section, table
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.requirements import requirement_blocks
from hexaleg.output.report.robot import robot_of
from hexaleg.study.decide import DecideResult, decide
from hexaleg.study.executors import local_pool
from hexaleg.study.rows import StudyRow
from hexaleg.study.sweep import StudySpec, peak_table, study_table, sweep, write_journal
from hexaleg.study.sweep import write_table as write_study_table

# -- the study of its segments ------------------------------------------------------------

STUDY_FOLDER = "study"


@dataclass(frozen=True)
class RobotStudyRecord:
    """The robot's segments at other ratios of its leg length (each row its changed file).

    Attributes:
        spec: What was swept.
        table: One row per design.
        yours: The robot as read, measured as the study measures its rows.

    """

    spec: StudySpec
    table: pd.DataFrame
    yours: StudyRow


def compute_study(data: ReportData) -> RobotStudyRecord:
    """The study of the robot's coxa × tibia ratios at its own leg length."""
    options = data.options
    spec = StudySpec(
        options.swept_l1_ratios,
        tuple(l3_ratio_grid(options.l3_points)),
        data.design.leg_length,
        base=data.design,
        walked=options.gait,
        robot=robot_of(data),
    )
    with local_pool(options.workers) as pool:
        found = study_table(spec, sweep(spec, pool))
    return RobotStudyRecord(spec, found, spec.row_of(data.design))


def study_section(data: ReportData) -> Section:
    """The FB peaks of the robot's study."""
    record = data[RobotStudyRecord]
    peaks = peak_table(record.table).to_dict(orient="records")
    failed = int((record.table["error"] != "").sum())
    return Section(
        "Design study: your robot's segments at other ratios",
        (
            f"{len(record.table)} designs ({len(record.spec.l1_ratios)} coxa ratios × "
            f"{len(record.spec.l3_ratios)} tibia ratios of your robot's leg length "
            f"{record.spec.total:.4g} m), each your robot's file with every leg's segments "
            f"changed along their own lines; {failed} could not be measured. Table: "
            f"[{STUDY_FOLDER}/study.csv]({STUDY_FOLDER}/study.csv).",
            Figure(
                "flexibility_ranges",
                "The six ranges of the body pose against tibia ratio, for the smallest coxa ratio",
            ),
            Figure("flexibility_fb", "FB against tibia ratio for each coxa ratio; yours marked"),
            table(
                ["l1 ratio", "FB peak l3 ratio", "peak FB"],
                [
                    (f"{p['l1_ratio']:.3f}", f"{p['peak_l3_ratio']:.3f}", f"{p['peak_fb']:.4f}")
                    for p in peaks
                ],
            ),
        ),
    )


def study_files(data: ReportData, out: Path) -> None:
    """The study folder (journal and table) and its figures, the robot as read marked."""
    record = data[RobotStudyRecord]
    write_journal(out / STUDY_FOLDER, record.spec, record.table)
    write_study_table(record.spec, record.table, out / STUDY_FOLDER)
    marks = [Mark("your robot", record.yours.to_dict())]
    write_study_figures(record.table, out, svg=data.options.svg, marks=marks)


def study_json(record: RobotStudyRecord) -> dict[str, Any]:
    """``study_peaks`` and ``study_yours`` (the robot as read, as a study row)."""
    return {
        "study_peaks": peak_table(record.table).to_dict(orient="records"),
        "study_yours": record.yours.to_dict(),
    }


STUDY = Part(
    RobotStudyRecord,
    compute_study,
    study_section,
    step="design study",
    files=study_files,
    json=study_json,
    level=2,
)


@dataclass(frozen=True)
class RobotDecisionRecord:
    """The best segments for the user's requirements (``None``: none given)."""

    answer: DecideResult | None


def compute_decision(data: ReportData) -> RobotDecisionRecord:
    """Decide over the robot's segments when the user gave requirements."""
    requirements = data.options.requirements
    if requirements is None:
        return RobotDecisionRecord(None)
    with local_pool(data.options.workers) as pool:
        answer = decide(
            data.design, requirements, executor=pool, progress=False, robot=robot_of(data)
        )
    return RobotDecisionRecord(answer)


def decision_section(data: ReportData) -> Section:
    """The answer to the requirements, or how to ask."""
    answer = data[RobotDecisionRecord].answer
    if answer is None:
        return Section(
            "Your requirements",
            ("None given: `report --urdf FILE --payload KG ...` (or a `[requirements]` table) "
             "adds the best segments of your robot that meet them.",),
        )  # fmt: skip
    return Section("Your requirements", requirement_blocks(answer))


def decision_json(record: RobotDecisionRecord) -> dict[str, Any]:
    """``requirements_decision`` when requirements were given."""
    return {} if record.answer is None else {"requirements_decision": record.answer.to_dict()}


DECISION = Part(RobotDecisionRecord, compute_decision, decision_section, step="decision",
                json=decision_json, level=0)  # fmt: skip


__all__ = ["DECISION", "STUDY"]
