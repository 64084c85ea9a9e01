"""Report part: the analysed design, and its URDF."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from hexaleg._io import write_text
from hexaleg.output.report.document import Section, table
from hexaleg.output.report.part import Part, ReportData

URDF = "hexapod.urdf"


@dataclass(frozen=True)
class DesignRecord:
    """The design's robot description.

    Attributes:
        urdf: The URDF text its model was built from.

    """

    urdf: str


def compute(data: ReportData) -> DesignRecord:
    """The URDF of the design's model."""
    return DesignRecord(data.model.urdf)


def section(data: ReportData) -> Section:
    """The analysed design."""
    d = data.design
    rows = [
        ("coxa l1, femur l2, tibia l3 [m]", f"{d.l1:.4g}, {d.l2:.4g}, {d.l3:.4g}"),
        ("leg length L [m]", f"{d.leg_length:.4g}"),
        ("body", d.body_description),
        ("nominal joint angles θ1, θ2, θ3 [rad]", ", ".join(f"{a:.4f}" for a in d.nominal_angles)),
        ("nominal body height [m]", f"{d.nominal_height:.4f}"),
        (
            "legs (x, y, yaw)",
            "; ".join(f"{m.name} ({m.x:g}, {m.y:g}, {math.degrees(m.yaw):.0f}°)" for m in d.legs),
        ),
    ]
    return Section(
        "Design",
        (
            "The analysed design; every other number follows from it. The URDF is "
            f"[{URDF}]({URDF}); the full design is in [report.json](report.json).",
            table(["field", "value"], rows),
        ),
    )


def write_files(data: ReportData, out: Path) -> None:
    """The URDF."""
    write_text(out / URDF, data[DesignRecord].urdf)


PART = Part(DesignRecord, compute, section, step="URDF", files=write_files, level=0)
