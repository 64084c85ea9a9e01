"""Report part: the analysed design (hexaleg's template's, or a robot file's), and its URDF."""

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
    """The analysed robot: its design, what follows from it, where its URDF is."""
    d, model = data.design, data.model
    rows = [
        ("coxa l1, femur l2, tibia l3 [m]", f"{d.l1:.4g}, {d.l2:.4g}, {d.l3:.4g}"),
        ("leg length L [m]", f"{d.leg_length:.4g}"),
        ("body", d.body_description),
        ("nominal joint angles θ1, θ2, θ3 [rad]", ", ".join(f"{a:.4f}" for a in d.nominal_angles)),
        ("nominal body height [m]", f"{model.nominal_height:.4f}"),
        ("mass [kg]", f"{model.total_mass:.4g}"),
        (
            "legs (x, y, yaw)",
            "; ".join(
                f"{m.name} ({m.x:.4g}, {m.y:.4g}, {math.degrees(m.yaw):.0f}°)" for m in d.legs
            ),
        ),
    ]
    return Section(
        "Design",
        (
            f"{data.robot.titled('The analysed design')}; every other number follows from it. "
            f"The URDF analysed is [{URDF}]({URDF}); the full design is in "
            "[report.json](report.json).",
            table(["field", "value"], rows),
        ),
    )


def write_files(data: ReportData, out: Path) -> None:
    """The URDF."""
    write_text(out / URDF, data[DesignRecord].urdf)


PART = Part(DesignRecord, compute, section, step="URDF", files=write_files, level=0)
