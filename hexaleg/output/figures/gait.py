"""Walking figures: a gait period's joints and feet, and the study's walking columns.

Drawn for the page as every figure of :mod:`hexaleg.output.figures`: torque, speed and power
against the phase per joint type (one curve per leg, each drawn solid while it stands,
thin while it swings, under a footfall diagram with each leg's stance shaded); the feet's
paths in the body frame over the legs' reach; and the study's peak torque and cost of
transport against the tibia ratio per coxa ratio.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.evaluation.metrics import METRICS
from hexaleg.gait.analysis import STUDY_GAIT, GaitAnalysis
from hexaleg.gait.spec import Gait
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.figures.canvas import COLORS, drawn, magnitude_axis, new_figure, save
from hexaleg.output.figures.marks import Mark, draw_marks, rating_line

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

LEG_COLORS = COLORS
"""One colour per leg, in ``leg_names`` order."""
QUANTITIES = (
    ("torque", "τ [N·m]"),
    ("speed", "q̇ [rad/s]"),
    ("power", "τ·q̇ [W]"),
)


def _series(analysis: GaitAnalysis, quantity: str) -> ArrayF:
    if quantity == "torque":
        return analysis.joint_torques
    if quantity == "speed":
        return analysis.joint_velocities
    return analysis.joint_torques * analysis.joint_velocities


@drawn
def joint_figure(analysis: GaitAnalysis) -> Figure:
    """Torque, speed and power against the phase, per joint type, one curve per leg."""
    fig = new_figure(8.5)
    grid = fig.add_gridspec(4, 3, height_ratios=(0.55, 1, 1, 1))
    phase = analysis.times / analysis.gait.period
    _footfalls(fig.add_subplot(grid[0, :]), analysis, phase)
    rated = {"torque": analysis.design.rated_torques, "speed": analysis.design.rated_speeds}
    for row, (quantity, label) in enumerate(QUANTITIES, start=1):
        values = _series(analysis, quantity)
        for j, joint in enumerate(LEG_JOINTS):
            ax = fig.add_subplot(grid[row, j])
            for i, leg in enumerate(analysis.legs):
                stand = np.where(analysis.stance[:, i], values[:, i, j], np.nan)
                ax.plot(phase, values[:, i, j], color=LEG_COLORS[i], lw=0.6, alpha=0.6)
                ax.plot(phase, stand, color=LEG_COLORS[i], lw=1.5, label=leg)
            ratings = rated.get(quantity)
            if ratings is not None:  # a design's ratings, if it gives them
                limit = ratings[j]
                for sign in (1, -1):
                    ax.axhline(sign * limit, color="k", ls="--", lw=1)
            ax.set_title(f"{joint} {quantity}")
            ax.set_xlim(0, 1)
            ax.grid(True, alpha=0.3)
            if j == 0:
                ax.set_ylabel(label)
            if row == len(QUANTITIES):
                ax.set_xlabel("phase t/T [-]")
    fig.legend(
        *ax.get_legend_handles_labels(),
        loc="outside lower center",
        ncols=6,
        title="one curve per leg, thick while it stands; dashed: the ratings",
    )
    fig.suptitle(_title(analysis))
    return fig


def _footfalls(ax: Axes, analysis: GaitAnalysis, phase: ArrayF) -> None:
    """Each leg's stance shaded in its colour: the footfall diagram."""
    step = 1.0 / len(phase)
    for i in range(len(analysis.legs)):
        standing = analysis.stance[:, i]
        starts = np.flatnonzero(standing & ~np.roll(standing, 1))
        ends = np.flatnonzero(standing & ~np.roll(standing, -1))
        if standing.all():
            starts, ends = np.array([0]), np.array([len(phase) - 1])
        for start, end in zip(starts, ends, strict=True):
            stop = phase[end] + step
            spans = [(phase[start], stop)] if start <= end else [(phase[start], 1), (0, stop)]
            for lo, hi in spans:
                ax.axvspan(
                    lo,
                    hi,
                    ymin=(5 - i) / 6 + 0.02,
                    ymax=(6 - i) / 6 - 0.02,
                    color=LEG_COLORS[i],
                    alpha=0.7,
                )
    ax.set_yticks((5.5 - np.arange(len(analysis.legs))) / 6, analysis.legs)
    ax.set_ylim(0, 1)
    ax.set_xlim(0, 1)
    ax.set_title(
        f"stance (shaded), {analysis.gait.pattern}, duty factor {analysis.gait.duty_factor:.3g}"
    )


def _title(analysis: GaitAnalysis) -> str:
    gait, (l1, l2, l3) = analysis.gait, analysis.design.lengths
    return (
        f"l = ({l1:.3g}, {l2:.3g}, {l3:.3g}) m, {gait.pattern}: T = {gait.period:.3g} s, "
        f"S = {gait.stride:.3g} m, H = {gait.step_height:.3g} m,\nv = {gait.speed:.3g} m/s, "
        f"payload {analysis.payload.mass:g} kg"
    )


@drawn
def foot_paths_figure(analysis: GaitAnalysis, reach: Mapping[str, ArrayF] | None = None) -> Figure:
    """The feet's paths in the body frame: from above and from the side.

    Args:
        analysis: The gait period.
        reach: Per leg, points of its foot's reach in the body frame (K, 3) [m] (for
            instance its Monte Carlo workspace within the stance limits), drawn faintly.

    """
    fig = new_figure(8.5)
    top, side = fig.subplots(2, 1, height_ratios=(2.2, 1))
    ground = -analysis.frames.height
    for i, leg in enumerate(analysis.legs):
        color = LEG_COLORS[i]
        if reach is not None and leg in reach:
            cloud = reach[leg]
            near = np.abs(cloud[:, 2] - ground) < 0.02  # the ground's slice, seen from above
            top.scatter(cloud[near, 0], cloud[near, 1], s=2, color=color, alpha=0.25, lw=0)
        feet = analysis.feet[:, i]
        standing = analysis.stance[:, i]
        for ax, (a, b) in ((top, (0, 1)), (side, (0, 2))):
            ax.plot(feet[:, a], feet[:, b], color=color, lw=0.9, alpha=0.7)
            ax.plot(feet[standing, a], feet[standing, b], ".", ms=2, color=color)
        top.plot(*analysis.frames.footholds[i, :2], "x", color="k", ms=5)
        top.plot(*analysis.frames.root_positions[i, :2], "o", color=color, ms=5, label=leg)
    top.set_aspect("equal")
    top.set_xlabel("x, body frame [m]")
    top.set_ylabel("y [m]")
    top.set_title("from above (o: leg root, x: nominal foothold, thick: standing, shade: reach)")
    top.legend(ncols=3, loc="center", title="leg (its root)")  # between the rows of feet
    side.axhline(ground, color="k", lw=1)
    side.set_xlabel("x, body frame [m]")
    side.set_ylabel("z, body frame [m]")
    side.set_title("from the side (each right leg behind its left twin; the line: the ground)")
    for ax in (top, side):
        ax.grid(True, alpha=0.3)
    fig.suptitle(_title(analysis))
    return fig


@drawn
def walking_study_figure(
    table: pd.DataFrame,
    rated: Mapping[str, float] | None = None,
    marks: Sequence[Mark] = (),
    gait: Gait = STUDY_GAIT,
    standing: str = "",
) -> Figure:
    """The study's walking against tibia ratio: hip and knee peaks, CoT, walking payload.

    The hip's and knee's peak |τ| [N·m] beside their ratings, the mechanical cost of
    transport [-] and the walking payload capacity [kg], one curve per coxa ratio.

    Args:
        table: The study's rows (its walking columns).
        rated: Rated torque per joint type [N·m] (``hip``, ``knee``), drawn as lines.
        marks: Designs marked on every panel (your design, the recommended one).
        gait: The gait the study's designs walk (named in the title).
        standing: The posture and ground they walk it at, in words (in the title).

    """
    import pandas as pd  # heavy: only where a study is drawn

    fig = new_figure(6.2)
    panels = fig.subplots(2, 2, sharex=True).ravel()
    columns = (
        (METRICS.gait_peak_hip_torque.name, "peak hip |τ| [N·m]"),
        (METRICS.gait_peak_knee_torque.name, "peak knee |τ| [N·m]"),
        (METRICS.mechanical_cost_of_transport.name, "mechanical CoT [-]"),
        (METRICS.walking_payload_capacity.name, "walking payload [kg]"),
    )
    walks = table["walks"].astype(bool) if "walks" in table else pd.Series(True, table.index)
    for ax, (column, label) in zip(panels, columns, strict=True):
        values = table[column].where(walks)  # a leg that cannot walk the gait: a gap, not a 0
        for (r1, group), color in zip(table.groupby("l1_ratio", sort=True), COLORS, strict=False):
            ax.plot(group["l3_ratio"], values[group.index], color=color,
                    label=f"coxa ratio {r1:.2f}")  # fmt: skip
        draw_marks(ax, marks, "l3_ratio", column)
        magnitude_axis(ax, values)
        marked = [float(m.values[column]) for m in marks if column in m.values]
        finite = [v for v in marked if math.isfinite(v)]
        if finite and 1.06 * max(finite) > ax.get_ylim()[1]:  # a mark off the curves: shown
            ax.set_ylim(0.0, 1.06 * max(finite))
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    for ax, joint in zip(panels[:2], ("hip", "knee"), strict=True):
        if rated:  # none drawn where the design gives no ratings
            rating_line(ax, rated[joint], joint)
    for ax in panels[2:]:
        ax.set_xlabel("tibia ratio l3 / L [-]")
    fig.legend(*panels[0].get_legend_handles_labels(), loc="outside lower center", ncols=4,
               fontsize=7.5)  # fmt: skip
    posed = f"\n{standing}" if standing else ""
    fig.suptitle(
        f"Walking {gait.named}, a {gait.pattern} at {gait.speed:.2g} m/s{posed}\n(gaps: "
        "designs that cannot walk it unloaded within their ratings)"
    )
    return fig


def write_gait_figures(
    analysis: GaitAnalysis, out_dir: str | os.PathLike[str], reach: Mapping[str, ArrayF] | None
) -> list[Path]:
    """Write ``gait_joints.png`` and ``gait_feet.png`` into ``out_dir``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    return [
        save(joint_figure(analysis), out / "gait_joints.png"),
        save(foot_paths_figure(analysis, reach), out / "gait_feet.png"),
    ]
