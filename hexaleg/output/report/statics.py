"""Report part: statics, what the design costs (torques, stability, slopes, payload)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.evaluation.metrics import METRICS
from hexaleg.output.figures import loads_figure, save, statics_study_figure
from hexaleg.output.figures.statics import SLOPE_CAUSES, slopes_differ
from hexaleg.output.report.document import Figure, Section, table
from hexaleg.output.report.flexibility import FREE_COUPLED, FlexibilityRecord
from hexaleg.output.report.marks import rated_torques, study_marks
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.study_record import StudyRecord
from hexaleg.output.report.yours import YoursRecord
from hexaleg.ratings import NEEDS_RATING
from hexaleg.statics.loads import LoadsAnalysis, loads_at_extremes
from hexaleg.study.rows import StudyRow


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
    """Statics at the extremes of both modes (the axis-locked ones: your design's evaluation's)."""
    axis = data[YoursRecord].evaluation.loads
    assert axis is not None  # the evaluation keeps its analyses
    return StaticsRecord(axis, loads_at_extremes(data.model, data[FlexibilityRecord].free))


def section(data: ReportData) -> Section:
    """What the design costs: torques against ratings, stability, slopes, payload."""
    loads = data[StaticsRecord].axis
    differ = slopes_differ(loads)
    yours, design = data[StudyRecord].yours, data.design
    motors = 0.0 if design.actuators is None else design.actuators.total_mass
    battery = 0.0 if design.battery is None else design.battery.mass
    leg = (loads.nominal.mass - design.body_mass - motors - battery) / len(design.legs)
    extra = f", the actuators {motors:.2f} kg" if motors else ""
    extra += f", the battery {battery:.2f} kg" if battery else ""
    return Section(
        "Statics: what the design costs",
        (
            f"The robot weighs {loads.nominal.weight:.0f} N ({loads.nominal.mass:.2f} kg: the "
            f"body {design.body_mass:g} kg, each leg's links {leg:.2f} kg at "
            f"{design.link_linear_density:g} kg/m{extra}). Foot forces balance gravity with the "
            "least Σ|f|² (min-norm); joint torques are Pinocchio's τ = g(q) − Σ Jᵀf. Peak |τ| over "
            "the stance legs, in N·m, beside each joint's ratings:",
            _torque_table(data),
            f"Stability margin at the nominal stance: {loads.nominal.stability_margin:.3f} m. "
            f"Payload capacity at the centre of the body's top face, standing: "
            f"{_capacity(loads)}; "
            f"walking {data.options.gait.named}: {_walking_capacity(yours)}. "
            f"Steepest slope the robot stands on, body level with the ground (μ = "
            f"{loads.friction:g}):",
            _slope_table(loads, differ),
            Figure(
                "loads",
                "This design's largest joint torques, standing and walking "
                f"{data.options.gait.named}, against their ratings"
                + (", and the steepest slope by uphill heading" if differ else ""),
            ),
            Figure(
                "study_statics",
                "Every design of the sweep: largest hip and knee torque standing, beside their "
                "ratings, and the standing and walking payload capacity (log scale), against "
                "tibia ratio for each coxa ratio; your design and the recommended leg (at its "
                "own posture) marked",
            ),
        ),
    )


def _capacity(loads: LoadsAnalysis) -> str:
    """The standing payload capacity in words (it may need a rating)."""
    capacity = loads.capacity
    if capacity is None:
        return NEEDS_RATING
    return f"**{capacity.mass:.1f} kg**, limited by {capacity.limited_by}"


def _walking_capacity(yours: StudyRow) -> str:
    """The walking payload capacity in words (it may need a rating)."""
    mass = yours.metrics.value(METRICS.walking_payload_capacity)
    if math.isnan(mass):
        return NEEDS_RATING
    return f"**{mass:.1f} kg**, limited by {yours.columns['walking_payload_limited_by']}"


def _torque_table(data: ReportData) -> str:
    record = data[StaticsRecord]
    nominal = record.axis.nominal.peak_torques()
    design = data.design
    rows = [
        (
            joint,
            f"{rated:g}",
            f"{speed:g}",
            f"{nominal[joint]:.1f}",
            f"{record.axis.peak_torques[joint]:.1f}",
            f"{record.free.peak_torques[joint]:.1f}",
        )
        for joint, rated, speed in zip(
            nominal,
            design.rated_torques or (math.nan,) * 3,
            design.rated_speeds or (math.nan,) * 3,
            strict=True,
        )
    ]
    header = [
        "joint",
        "rated torque",
        "rated speed [rad/s]",
        "nominal stance",
        "over the axis-locked extremes",
    ]
    return table([*header, "over the free-coupled extremes"], rows)


def _slope_table(loads: LoadsAnalysis, differ: bool) -> str:
    """One line when every uphill heading gives the same slope and cause, else one a heading."""
    header = ["uphill heading (body frame, 0° = forward)", "steepest slope [°]", "stopped by"]
    headings = [f"{math.degrees(s.heading):+.0f}°" for s in loads.slopes]
    if not differ:
        first = loads.slopes[0]
        row = (
            f"every heading ({', '.join(headings)})",
            f"{math.degrees(first.max_slope):.1f}",
            SLOPE_CAUSES.get(str(first.limited_by), str(first.limited_by)),
        )
        return table(header, [row])
    rows = [
        (
            heading,
            f"{math.degrees(s.max_slope):.1f}",
            SLOPE_CAUSES.get(str(s.limited_by), str(s.limited_by)),
        )
        for heading, s in zip(headings, loads.slopes, strict=True)
    ]
    return table(header, rows)


def write_files(data: ReportData, out: Path) -> None:
    """The study's torques and payload against tibia ratio, and this design's loads."""
    save(
        statics_study_figure(
            data[StudyRecord].table, rated_torques(data), study_marks(data), data.options.gait
        ),
        out / "study_statics.png",
        svg=data.options.svg,
    )
    yours = data[StudyRecord].yours
    peaks = yours.metrics.joint_torques("peak")
    walking = {joint: math.nan if peak is None else peak for joint, peak in peaks.items()}
    figure = loads_figure(data[StaticsRecord].axis, walking, data.options.gait)
    save(figure, out / "loads.png", svg=data.options.svg)


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
    needs=(FlexibilityRecord, YoursRecord),
    step="statics",
    files=write_files,
    json=to_json,
    level=2,
    holds=FREE_COUPLED,
)
