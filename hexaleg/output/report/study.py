"""Report part: the design study, FB against segment ratios (Fig 14–15)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

from hexaleg.exceptions import HexalegError
from hexaleg.output.figures import write_study_figures
from hexaleg.output.report.document import Figure, Section, table
from hexaleg.output.report.marks import study_marks
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.study_record import StudyRecord
from hexaleg.output.report.yours import YoursRecord, ratio_key, standing_text
from hexaleg.paper import CLAIMED_L3_RATIO_PEAK
from hexaleg.study.executors import local_pool
from hexaleg.study.rows import Key
from hexaleg.study.sweep import (
    StudySpec,
    peak_table,
    study_table,
    sweep,
    write_journal,
    write_table,
)

FOLDER = "study"
"""The study's own folder inside the report (its table, journal and spec)."""


def compute(data: ReportData) -> StudyRecord:
    """Run the study over the swept coxa ratios × the report's tibia ratios.

    Each design is the report's robot at the row's segment lengths (a robot file's changed
    along its legs' own lines), at its leg length. Where your design is one of them, its
    row is your design's one evaluation, not measured again.
    """
    yours = data[YoursRecord]
    spec, row = yours.spec, yours.row
    mine = _your_key(spec)
    with local_pool(data.options.workers) as pool:
        rows = sweep(spec, pool, skip=mine)
    rows |= {key: replace(row, l1_ratio=key[0], l3_ratio=key[1]) for key in mine}
    return StudyRecord(spec, study_table(spec, rows), row)


def _your_key(spec: StudySpec) -> tuple[Key, ...]:
    """The study's key whose design is your design, if one is (none or one)."""
    design = spec.robot.design
    r1, r3 = ratio_key(design)
    for key in spec.keys():
        if abs(key[0] - r1) < 1e-9 and abs(key[1] - r3) < 1e-9:
            try:
                if spec.robot.at_ratios(*key, spec.total).design == design:
                    return (key,)
            except HexalegError:
                return ()
    return ()


def section(data: ReportData) -> Section:
    """The FB sweep over segment ratios (Fig 14–15)."""
    record = data[StudyRecord]
    study, spec = record.table, record.spec
    peaks = peak_table(study)
    failed = int((study["error"] != "").sum())
    designs = (
        "this design's body and posture"
        if data.robot.own_legs is None
        else "each your robot's file with every leg's segments changed along their own lines"
    )
    blocks: list[str | Figure] = [
        f"{len(study)} designs ({len(spec.l1_ratios)} coxa ratios × "
        f"{len(spec.l3_ratios)} tibia ratios, total {spec.total:.4g} m, {designs}), each "
        f"{standing_text(spec)}; {failed} could not stand. Table: "
        "[study/study.csv](study/study.csv).",
        Figure(
            "flexibility_ranges",
            "The six ranges of the body pose against tibia ratio, for the smallest coxa ratio "
            "(the paper's Fig 14)",
        ),
        Figure(
            "flexibility_fb",
            "Body flexibility FB against tibia ratio, for each coxa ratio, its grid peaks "
            "marked and its flat top (within 1 % of the peak) thickened; the band is the "
            "paper's claim (the paper's Fig 15); your design (and the recommended leg, at its "
            "own posture) marked",
        ),
        table(
            ["l1 ratio", f"FB peak l3 ratio ({data.options.l3_points}-point grid)", "peak FB"],
            [
                (f"{p['l1_ratio']:.2f}", f"{p['peak_l3_ratio']:.3f}", f"{p['peak_fb']:.4f}")
                for p in peaks.to_dict(orient="records")
            ],
        ),
    ]
    if data.robot.body_sweepable:  # the next table varies the body the paper does not give
        blocks.append(
            "The paper reports FB falling as the coxa grows and peaking at l3 ≈ "
            f"{CLAIMED_L3_RATIO_PEAK[0]:.2f}–{CLAIMED_L3_RATIO_PEAK[1]:.2f} (§6.3). "
            "hexaleg confirms the fall; with this posture the peaks lie at "
            f"{peaks['peak_l3_ratio'].min():.3f}–{peaks['peak_l3_ratio'].max():.3f}. The paper "
            "gives no posture or body: the next table shows how the peak moves with them."
        )
    return Section("Design study: FB against segment ratios (Fig 14–15)", tuple(blocks))


def write_files(data: ReportData, out: Path) -> None:
    """The study folder (journal and table) and Fig 14–15."""
    record = data[StudyRecord]
    write_journal(out / FOLDER, record.spec, record.table)
    write_table(record.spec, record.table, out / FOLDER)
    write_study_figures(record.table, out, svg=data.options.svg, marks=study_marks(data))


def to_json(record: StudyRecord) -> dict[str, Any]:
    """``study_peaks`` and ``study_yours``: the FB peaks, the robot as a study row.

    Per coxa ratio, the tibia ratio of the largest FB and that FB; the robot reported on,
    measured as the study measures its rows.
    """
    return {
        "study_peaks": peak_table(record.table).to_dict(orient="records"),
        "study_yours": record.yours.to_dict(),
    }


PART = Part(
    StudyRecord,
    compute,
    section,
    needs=(YoursRecord,),
    step="design study",
    files=write_files,
    json=to_json,
    level=2,
)
