"""Report part (``report --simulate``): the planned gait walked in MuJoCo, and a still of it.

The part walks the report's gait (:attr:`~.options.ReportOptions.gait`) with the report's
design for :data:`CYCLES` periods
(:func:`~hexaleg.sim.simulate_gait`), sets the measures beside the plan's, and shows the
robot half a period into the last one, one tripod in mid-swing: MuJoCo's own picture
where an offscreen OpenGL works (EGL or OSMesa), else the links drawn as lines from the
same simulated configuration.
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pinocchio as pin

from hexaleg.limits import LEG_JOINTS
from hexaleg.output.figures.canvas import COLORS, FULL_WIDTH, drawn, new_figure, save
from hexaleg.output.report.document import Figure, Section, table
from hexaleg.output.report.part import Part, ReportData
from hexaleg.robot.model import HexapodModel, joint_name
from hexaleg.sim.result import SimulationResult
from hexaleg.sim.simulate import DEFAULT_CYCLES, simulate_gait

if TYPE_CHECKING:
    from matplotlib.figure import Figure as PlotFigure

CYCLES = DEFAULT_CYCLES
"""Gait periods the report walks."""
STILL = "simulated_walk"
"""The still's file name, without extension."""


@dataclass(frozen=True)
class SimulationRecord:
    """The simulated walk of the report's design.

    Attributes:
        result: The walk, its measures and the tripod standing check.

    """

    result: SimulationResult


def compute(data: ReportData) -> SimulationRecord:
    """Walk the report's gait for :data:`CYCLES` periods in MuJoCo."""
    gait = data.options.gait
    return SimulationRecord(simulate_gait(data.design, gait, cycles=CYCLES, model=data.model))


def section(data: ReportData) -> Section:
    """The measures beside the plan's, the standing forces beside the statics', the still."""
    result = data[SimulationRecord].result
    gait = result.gait
    stiffness = zip(LEG_JOINTS, result.gains.stiffness, strict=True)
    kp = ", ".join(f"{joint} {k:.0f}" for joint, k in stiffness)
    return Section(
        "Simulated walk: the plan in a physics engine",
        (
            f"The design walked {gait.named} ({gait.pattern}, T = {gait.period:g} s, "
            f"S = {gait.stride:g} m, H = {gait.step_height:g} m: v = {gait.speed:.3g} m/s) "
            f"for {result.cycles} periods in MuJoCo, from rest: hexaleg's URDF on a free "
            f"body, foot spheres on a floor (μ = {result.friction:g}), joint servos fed the "
            "planned joint trajectory with its inverse-dynamics torques as feed-forward "
            f"(stiffness {kp} N·m/rad). Measured over the periods after the first:",
            table(["quantity", "simulated", "planned"], _walk_rows(result)),
            "The plan shares each instant's load among the standing feet with the least "
            "forces; feet planted in the simulation and held by stiff servos also push "
            "against each other, so the simulated torques, the roots' most, carry forces "
            "the plan does not.",
            "Standing 2 s on one tripod with the other feet lifted 2 cm, each standing "
            "foot's vertical force beside the statics' (`loads --stance tripod`):",
            table(
                ["foot", "MuJoCo f_z [N]", "statics f_z [N]", "difference"], _standing_rows(result)
            ),
            Figure(
                STILL,
                f"The simulated robot at t = {result.mid_stride_frame / result.frame_rate:.2f} s, "
                "half a period into its last period: one tripod in mid-swing, the other "
                "standing.",
            ),
        ),
    )


def _walk_rows(result: SimulationResult) -> list[tuple[str, str, str]]:
    metrics, design = result.metrics, result.design
    rows = [
        (
            "distance [m]",
            f"{metrics.distance:.3f} ({100 * metrics.distance_ratio:.1f} %)",
            f"{metrics.planned_distance:.3f}",
        ),
        ("max \\|roll\\|, \\|pitch\\| [°]", f"{math.degrees(metrics.max_roll):.2f}, "
         f"{math.degrees(metrics.max_pitch):.2f}", "0, 0"),
        ("lowest body height [m]", f"{metrics.min_height:.3f}", f"{design.nominal_height:.3f}"),
        ("fell", "yes" if metrics.fell else "no", "no"),
        ("RMS joint tracking error [rad]", f"{metrics.tracking_rms:.4f}", "0"),
        ("standing-foot slip [m]", f"{metrics.slip:.4f}", "0"),
    ]  # fmt: skip
    for joint, rated in zip(LEG_JOINTS, design.rated_torques or (None,) * 3, strict=True):
        rows.append(
            (
                f"peak \\|τ\\| {joint} [N·m] "
                + (f"(rated {rated:g})" if rated is not None else "(rating not given)"),
                f"{metrics.peak_torque[joint]:.1f}",
                f"{result.planned_peak_torque[joint]:.1f}",
            )
        )
    return rows


def _standing_rows(result: SimulationResult) -> list[tuple[str, str, str, str]]:
    standing = result.standing
    rows = []
    for leg in standing.legs:
        simulated, statics = standing.foot_forces_z[leg], standing.statics_foot_forces_z[leg]
        difference = 100 * (simulated - statics) / statics
        rows.append((leg, f"{simulated:.1f}", f"{statics:.1f}", f"{difference:+.2f} %"))
    return rows


def write_files(data: ReportData, out: Path) -> None:
    """The still: MuJoCo's picture where it can render offscreen, else the links as lines."""
    from hexaleg.sim.video import write_still

    result = data[SimulationRecord].result
    q = result.frames[result.mid_stride_frame]
    title = f"Simulated in MuJoCo, t = {result.mid_stride_frame / result.frame_rate:.2f} s"
    with tempfile.TemporaryDirectory(prefix="hexaleg-still-") as tmp:
        outcome = write_still(result.sim_model(), q, Path(tmp) / "still.png")
        if outcome.path is not None:
            figure = picture_figure(np.asarray(_read_png(outcome.path)), title)
        else:
            figure = stick_figure(data.model, q, f"{title} (no offscreen OpenGL: links as lines)")
    save(figure, out / f"{STILL}.png", svg=data.options.svg)


def _read_png(path: Path) -> Any:
    from PIL import Image

    with Image.open(path) as image:
        return image.convert("RGB")


@drawn
def picture_figure(pixels: np.ndarray, title: str) -> PlotFigure:
    """A rendered picture (H, W, 3) under ``title``, without axes."""
    height, width = pixels.shape[:2]
    figure = new_figure(FULL_WIDTH * height / width * 0.75, FULL_WIDTH * 0.75)
    axes = figure.add_subplot()
    axes.imshow(pixels, interpolation="antialiased")
    axes.set_axis_off()
    axes.set_title(title)
    return figure


@drawn
def stick_figure(model: HexapodModel, q: np.ndarray, title: str) -> PlotFigure:
    """The body's outline through the leg roots and every leg's links as lines, 3-D [m]."""
    pin.forwardKinematics(model.model, model.data, q)
    pin.updateFramePlacements(model.model, model.data)
    figure = new_figure(4.0)
    axes = figure.add_subplot(projection="3d")
    legs = np.array([_leg_points(model, leg) for leg in model.leg_names])  # (6, 4, 3)
    for points in legs:
        axes.plot(*points.T, lw=2.5, color=COLORS[0])
    roots = legs[:, 0]
    around = roots - roots.mean(axis=0)
    order = np.argsort(np.arctan2(around[:, 1], around[:, 0]))
    axes.plot(*roots[np.r_[order, order[:1]]].T, lw=2.0, color=COLORS[-1])
    axes.set_xlabel("x [m]")
    axes.set_ylabel("y [m]")
    axes.set_zlabel("z [m]")
    axes.set_aspect("equal")
    axes.set_title(title)
    return figure


def _leg_points(model: HexapodModel, leg: str) -> np.ndarray:
    """Root, hip, knee and foot of ``leg`` (4, 3), world frame [m], after forward kinematics."""
    joints = [model.model.getJointId(joint_name(leg, joint)) for joint in LEG_JOINTS]
    points = [model.data.oMi[j].translation for j in joints]
    return np.array([*points, model.data.oMf[model.foot_frame_id(leg)].translation])


def to_json(record: SimulationRecord) -> dict[str, Any]:
    """``simulation``: the simulate command's JSON, without the design (stated once)."""
    fields = record.result.to_dict()
    return {"simulation": {key: value for key, value in fields.items() if key != "design"}}


PART = Part(
    SimulationRecord,
    compute,
    section,
    step="simulated walk",
    files=write_files,
    json=to_json,
    level=2,
)
