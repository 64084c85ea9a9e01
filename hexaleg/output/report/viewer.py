"""Report part: the 3-D view, a self-contained meshcat page beside the report."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from hexaleg.output.figures.canvas import save
from hexaleg.output.figures.stance import stance_figure
from hexaleg.output.report.document import Figure, Section
from hexaleg.output.report.flexibility import FlexibilityRecord
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.robot import RobotStanceRecord
from hexaleg.output.report.statics import StaticsRecord
from hexaleg.output.viewer.scene import write_static_html
from hexaleg.stance.extremes import FlexibilityResult
from hexaleg.statics.loads import LoadsAnalysis

PAGE = "viewer.html"
STILL = "viewer_still"
"""The still of the 3-D view (its PNG and SVG), for print."""


@dataclass(frozen=True)
class ViewerRecord:
    """What the 3-D view shows beside the robot and its extremes.

    Attributes:
        workspace_leg: The leg whose workspace cloud is drawn.

    """

    workspace_leg: str


def compute(data: ReportData) -> ViewerRecord:
    """The first leg's workspace is drawn."""
    return ViewerRecord(data.model.leg_names[0])


def section(data: ReportData) -> Section:
    """Where the 3-D view is and how to use it."""
    leg = data[ViewerRecord].workspace_leg
    return Section(
        "3-D view",
        (
            f"[{PAGE}]({PAGE}) is a self-contained meshcat scene (no server needed): the "
            f"nominal stance, the footholds, the {leg} leg's workspace cloud, and the 12 "
            "extremes under `hexaleg/extremes/` in the scene tree (tick to show; the link whose "
            "joint stops the body is red). Each leg link is coloured by its joint's |τ| / rated "
            "torque at the pose shown; the colour scale stands beside the scene. Open Controls "
            "→ Animations → play to see the body go out to each extreme and back. `hexaleg "
            "view` serves the same scene live on 127.0.0.1. For print, a still of it:",
            Figure(
                STILL,
                f"The nominal stance, as {PAGE} shows it in 3-D (open that page for the "
                "extremes, the workspace and the torque colours)",
            ),
        ),
    )


def write_files(data: ReportData, out: Path) -> None:
    """The static viewer page (torque colours from the statics), and its still for print."""
    locked, loads = _stance(data)
    save(stance_figure(data.model), out / f"{STILL}.png", svg=data.options.svg)
    write_static_html(data.model, locked, out / PAGE, data[ViewerRecord].workspace_leg, loads)


def _stance(data: ReportData) -> tuple[FlexibilityResult, LoadsAnalysis]:
    """The axis-locked extremes and their statics the report computed.

    The paper's sections' (:mod:`.flexibility`, :mod:`.statics`), or where the legs are
    their own, the robot's stance section's (:mod:`.robot`).
    """
    own = data.records.get(RobotStanceRecord)
    if own is not None:
        return own.flexibility, own.loads
    return data[FlexibilityRecord].axis, data[StaticsRecord].axis


PART = Part(ViewerRecord, compute, section, step="3-D view", files=write_files)
