"""Report part: statics, what the design costs (torques, stability, slopes, payload)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.output.figures import loads_figure, save, statics_study_figure
from hexaleg.output.report.document import Figure, Section, table
from hexaleg.output.report.flexibility import FlexibilityRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.study import StudyRecord
from hexaleg.statics.loads import LoadsAnalysis, loads_at_extremes


@dataclass(frozen=True)
class StaticsRecord:
    """Statics at the nominal stance and at each mode's extremes.

    Attributes:
        axis: At the nominal stance and the axis-locked extremes (slopes, capacity).
        free: At the free-coupled extremes.

    """

    axis: LoadsAnalysis
    free: LoadsAnalysis


def compute(data: ReportData) -> StaticsRecord:
    """Statics at the extremes of both modes."""
    flexibility = data[FlexibilityRecord]
    return StaticsRecord(
        loads_at_extremes(data.model, flexibility.axis),
        loads_at_extremes(data.model, flexibility.free),
    )


def section(data: ReportData) -> Section:
    """What the design costs: torques against ratings, stability, slopes, payload."""
    record = data[StaticsRecord]
    loads, free = record.axis, record.free
    nominal = loads.nominal.peak_torques()
    rows = [
        (
            joint,
            f"{rated:g}",
            f"{nominal[joint]:.1f}",
            f"{loads.peak_torques[joint]:.1f}",
            f"{free.peak_torques[joint]:.1f}",
        )
        for joint, rated in zip(nominal, data.design.rated_torques, strict=True)
    ]
    slopes = ", ".join(
        f"{math.degrees(s.heading):+.0f}°: {math.degrees(s.max_slope):.1f}° ({s.limited_by})"
        for s in loads.slopes
    )
    return Section(
        "3.3 Statics: what the design costs",
        (
            f"The robot weighs {loads.nominal.mass * 9.81:.0f} N ({loads.nominal.mass:.2f} kg). "
            "Foot forces balance gravity with the least Σ|f|² (min-norm); joint torques are "
            "Pinocchio's τ = g(q) − Σ Jᵀf. Peak |τ| over the stance legs, in N·m:",
            table(
                [
                    "joint",
                    "rated",
                    "nominal stance",
                    "over the axis-locked extremes",
                    "over the free-coupled extremes",
                ],
                rows,
            ),
            f"Stability margin at the nominal stance: {loads.nominal.stability_margin:.3f} m. "
            f"Steepest slope by uphill heading (μ = {loads.friction:g}): {slopes}. Payload "
            f"capacity at the centre of the body's top face: **{loads.capacity.mass:.1f} kg**, "
            f"limited by {loads.capacity.limited_by}. Per design of the sweep:",
            Figure(
                "study_statics",
                "Peak hip and knee torque and payload capacity against tibia ratio",
            ),
            Figure("loads", "This design: peak torques against their ratings, and slopes"),
        ),
    )


def write_files(data: ReportData, out: Path) -> None:
    """The study's torques and payload against tibia ratio, and this design's loads."""
    save(statics_study_figure(data[StudyRecord].table), out / "study_statics.png", svg=True)
    save(loads_figure(data[StaticsRecord].axis), out / "loads.png", svg=True)


def to_json(record: StaticsRecord) -> dict[str, Any]:
    """``loads``: both modes, without the design (the report states it once)."""
    return {
        "loads": {
            "axis": _without_design(record.axis.to_dict()),
            "free": _without_design(record.free.to_dict()),
        }
    }


def _without_design(data: dict[str, Any]) -> dict[str, Any]:
    return {key: value for key, value in data.items() if key != "design"}


PART = Part(
    StaticsRecord,
    compute,
    section,
    needs=(FlexibilityRecord,),
    step="statics",
    files=write_files,
    json=to_json,
)
