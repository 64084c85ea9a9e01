"""Report part (``report --simulate``): the planned gait walked in MuJoCo, and a still of it.

The part walks the report's gait (:attr:`~.options.ReportOptions.gait`) with the report's
design for :data:`CYCLES` periods (:func:`~hexaleg.sim.simulate_gait`) twice — with stiff
position servos and torque-controlled — sets both walks' measures beside the plan's, and
shows the servo robot half a period into the last one, one tripod in mid-swing: MuJoCo's
own picture where an offscreen OpenGL works (EGL or OSMesa), else the links drawn as lines
from the same simulated configuration.
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
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.part import LeftOut, Part, ReportData
from hexaleg.robot.model import HexapodModel, joint_name
from hexaleg.robot.robot import Robot
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
    """The simulated walks of the report's design.

    Attributes:
        result: The walk with stiff position servos (the still's), its measures and the
            tripod standing check.
        torque: The same walk torque-controlled (the plan's torques, a low-gain PD).

    """

    result: SimulationResult
    torque: SimulationResult

    @property
    def walks(self) -> dict[str, SimulationResult]:
        """Each walk by its controller, servos first."""
        return {walk.controller: walk for walk in (self.result, self.torque)}


def compute(data: ReportData) -> SimulationRecord:
    """Walk the report's gait for :data:`CYCLES` periods in MuJoCo, with each controller."""
    gait = data.options.gait
    walks = (
        simulate_gait(data.design, gait, cycles=CYCLES, model=data.model, controller=controller)
        for controller in ("servo", "torque")
    )
    return SimulationRecord(*walks)


def section(data: ReportData) -> Section:
    """Both walks' measures beside the plan's, the standing feet beside the statics', the still."""
    record = data[SimulationRecord]
    result = record.result
    gait = result.gait
    stiffness = zip(LEG_JOINTS, result.gains.stiffness, strict=True)
    kp = ", ".join(f"{joint} {k:.0f}" for joint, k in stiffness)
    diverged = [f"The {c}-controlled walk diverged {w.diverged}: its measures are left out."
                for c, w in record.walks.items() if w.diverged]  # fmt: skip
    return Section(
        "Simulated walk: the plan in a physics engine",
        (
            f"The design walked {gait.named} ({gait.pattern}, T = {gait.period:g} s, "
            f"S = {gait.stride:g} m, H = {gait.step_height:g} m: v = {gait.speed:.3g} m/s) "
            f"for {result.cycles} periods in MuJoCo: hexaleg's URDF on a free body, foot "
            f"spheres on a floor (μ = {result.friction:g}), the planned joint trajectory "
            "followed twice — by stiff position servos fed its inverse-dynamics torques "
            f"(stiffness {kp} N·m/rad), from rest, as hobby servos are; and torque-controlled, "
            "its torques with a low-gain PD, from the plan's velocities. Measured over the "
            "periods after the first:",
            table(["quantity", "servos", "torque control", "planned"], _walk_rows(record)),
            *diverged,
            "The plan hands each instant's load to the standing feet with the least forces. "
            "Stiff servos planted on three feet also push them against each other (the "
            "internal force), and a lifting foot still pressed into MuJoCo's soft floor is "
            "dragged by its swing: their torques, the roots' most, carry forces the plan does "
            "not. Torque control needs what the plan says: size motors on the plan for a "
            "torque-controlled robot, and give stiff servos the margin the servo column shows.",
            *_standing_blocks(result),
            Figure(
                STILL,
                f"The simulated robot at t = {result.mid_stride_frame / result.frame_rate:.2f} s, "
                "half a period into its last period: one tripod in mid-swing, the other "
                "standing.",
            ),
        ),
    )


def _walk_rows(record: SimulationRecord) -> list[tuple[str, ...]]:
    """Each measure with both controllers (``-``: that walk diverged) and the plan's."""
    design, result = record.result.design, record.result
    columns = [_measures(walk) for walk in record.walks.values()]
    planned = [
        f"{result.gait.speed * result.gait.period * (result.cycles - 1):.3f}", "0, 0",
        f"{design.nominal_height:.3f}", "no", "0", "0", "0",
        *(f"{result.planned_peak_torque[joint]:.1f}" for joint in LEG_JOINTS),
    ]  # fmt: skip
    names = [
        "distance [m]", "max \\|roll\\|, \\|pitch\\| [°]", "lowest body height [m]", "fell",
        "RMS joint tracking error [rad]", "standing-foot slip [m]",
        "internal force, standing feet [N]",
        *(f"peak \\|τ\\| {joint} [N·m] ({_rating(r)})"
          for joint, r in zip(LEG_JOINTS, design.rated_torques or (None,) * 3, strict=True)),
    ]  # fmt: skip
    return [
        (name, *(column[k] if column else "-" for column in columns), planned[k])
        for k, name in enumerate(names)
    ]


def _rating(rated: float | None) -> str:
    """A joint's rated torque [N·m] in a row's name, or that the design gives none."""
    return "rating not given" if rated is None else f"rated {rated:g}"


def _measures(result: SimulationResult) -> list[str]:
    """A walk's measures as :func:`_walk_rows` lists them (none: it diverged)."""
    metrics = result.metrics
    if metrics is None:
        return []
    return [
        f"{metrics.distance:.3f} ({100 * metrics.distance_ratio:.1f} %)",
        f"{math.degrees(metrics.max_roll):.2f}, {math.degrees(metrics.max_pitch):.2f}",
        f"{metrics.min_height:.3f}", "yes" if metrics.fell else "no",
        f"{metrics.tracking_rms:.4f}", f"{metrics.slip:.4f}", f"{metrics.internal_force:.1f}",
        *(f"{metrics.peak_torque[joint]:.1f}" for joint in LEG_JOINTS),
    ]  # fmt: skip


def _standing_blocks(result: SimulationResult) -> tuple[str, ...]:
    """The tripod standing check's sentence and table (none if it diverged)."""
    standing = result.standing
    if standing is None:
        return ()
    rows = []
    for leg in standing.legs:
        simulated, statics = standing.foot_forces_z[leg], standing.statics_foot_forces_z[leg]
        difference = 100 * (simulated - statics) / statics
        rows.append((leg, f"{simulated:.1f}", f"{statics:.1f}", f"{difference:+.2f} %"))
    return (
        "Standing 2 s on one tripod with the other feet lifted 2 cm, each standing "
        "foot's vertical force beside the statics' (`loads --stance tripod`):",
        table(["foot", "MuJoCo f_z [N]", "statics f_z [N]", "difference"], rows),
    )


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
    """``simulation``: each controller's walk as the simulate command's JSON, no design."""
    return {
        "simulation": {
            controller: {key: value for key, value in walk.to_dict().items() if key != "design"}
            for controller, walk in record.walks.items()
        }
    }


def simulated(robot: Robot, options: ReportOptions) -> LeftOut | None:
    """Where the section holds: asked for (``simulate``), legs the design's.

    A robot file's walk is ``simulate --urdf FILE``'s, not yet this report's.
    """
    if not options.simulate:
        return LeftOut()
    if robot.own_legs is None:
        return None
    return LeftOut(
        "Simulated walk",
        "not yet in this report of an imported robot: `simulate --urdf FILE` walks it",
    )


PART = Part(
    SimulationRecord,
    compute,
    section,
    step="simulated walk",
    files=write_files,
    json=to_json,
    level=2,
    holds=simulated,
)
