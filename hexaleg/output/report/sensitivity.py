"""Report part: how the FB peak moves with posture and body (not given by the paper)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from hexaleg._io import write_text
from hexaleg.design import l3_ratio_grid
from hexaleg.output.report.document import Section, table
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.part import LeftOut, Part, ReportData
from hexaleg.output.report.study_record import StudyRecord
from hexaleg.paper import L1_RATIOS
from hexaleg.robot.robot import Robot
from hexaleg.study.sensitivity import sensitivity_table


@dataclass(frozen=True)
class SensitivityRecord:
    """Peak FB per posture/body variant, each relative to the design.

    Attributes:
        table: One row per variant and coxa ratio: peak tibia ratio, peak FB, failures.

    """

    table: pd.DataFrame


def compute(data: ReportData) -> SensitivityRecord:
    """The sensitivity table: the design's variants, or the user's field sweep.

    The study's designs (your body and posture) are not measured again: where the table's
    grid meets the study's, your design's variant takes the study's FB (measured the same
    way unless the study counts collisions).
    """
    design, options = data.design, data.options
    known = None if options.collisions else data[StudyRecord].table
    return SensitivityRecord(
        sensitivity_table(
            _sensitivity_l1_ratios(options.swept_l1_ratios),
            tuple(l3_ratio_grid(options.sensitivity_points)),
            design.leg_length,
            base=design,
            variants=None if options.sweep is None else options.sweep.variants(),
            known=known,
        )
    )


def _sensitivity_l1_ratios(l1_ratios: Sequence[float]) -> tuple[float, ...]:
    """The paper's second and fourth coxa ratios, or the smallest and largest swept."""
    if tuple(l1_ratios) == L1_RATIOS:
        return (L1_RATIOS[1], L1_RATIOS[3])
    return tuple(sorted({min(l1_ratios), max(l1_ratios)}))


def section(data: ReportData) -> Section:
    """How the FB peak moves with posture and body."""
    sensitivity = data[SensitivityRecord].table
    rows = sensitivity.to_dict(orient="records")
    count = len(sensitivity["variant"].unique())
    sweep = data.options.sweep
    what = (
        f"{count} variants of your design's posture and body"
        if sweep is None
        else f"your design with {sweep.field} from {sweep.start:g} to {sweep.stop:g} "
        f"({count} values, --sweep)"
    )
    return Section(
        "Sensitivity to posture and body (not given by the paper)",
        (
            f"Axis-locked FB peak for {what}, {data.options.sensitivity_points} tibia ratios "
            "each. Each variant changes your design by the amount it names.",
            table(
                [
                    "variant",
                    "l1 ratio",
                    f"peak l3 ratio ({data.options.sensitivity_points}-point grid)",
                    "peak FB",
                    "designs that cannot stand",
                ],
                [
                    (
                        r["variant"],
                        f"{r['l1_ratio']:.2f}",
                        f"{r['peak_l3_ratio']:.3f}",
                        f"{r['peak_fb']:.4f}",
                        str(r["failed_designs"]) + (f" ({r['note']})" if r["note"] else ""),
                    )
                    for r in rows
                ],
            ),
        ),
    )


def write_files(data: ReportData, out: Path) -> None:
    """``sensitivity.csv``."""
    write_text(out / "sensitivity.csv", data[SensitivityRecord].table.to_csv(index=False))


def to_json(record: SensitivityRecord) -> dict[str, Any]:
    """``sensitivity``."""
    return {"sensitivity": record.table.to_dict(orient="records")}


def body_sweepable(robot: Robot, options: ReportOptions) -> LeftOut | None:
    """Where the table holds: a robot whose body may be varied (hexaleg's template's)."""
    if robot.body_sweepable:
        return None
    return LeftOut(
        "Posture and body sensitivity",
        "it varies hexaleg's template body and mounts, not your robot's file",
    )


PART = Part(
    SensitivityRecord,
    compute,
    section,
    needs=(StudyRecord,),
    step="posture sensitivity",
    files=write_files,
    json=to_json,
    level=2,
    holds=body_sweepable,
)
