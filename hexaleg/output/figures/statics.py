"""Statics figures: torques against ratings, slopes, payload capacity."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from hexaleg.output.figures.canvas import COLORS, new_figure
from hexaleg.statics.loads import LoadsAnalysis

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def loads_figure(analysis: LoadsAnalysis) -> Figure:
    """Peak |τ| per joint type against its rating, and the steepest slope per heading."""
    fig = new_figure(11, 4.5)
    torques, slopes = fig.subplots(1, 2)
    nominal = analysis.nominal.peak_torques()
    joints = list(nominal)
    x = np.arange(len(joints))
    torques.bar(x - 0.2, [nominal[j] for j in joints], 0.4, color=COLORS[0], label="nominal")
    torques.bar(
        x + 0.2,
        [analysis.peak_torques[j] for j in joints],
        0.4,
        color=COLORS[1],
        label=f"peak over the 12 {analysis.mode} extremes",
    )
    for k, rated in enumerate(analysis.design.rated_torques):
        torques.hlines(rated, k - 0.45, k + 0.45, colors="k", linestyles="--", lw=1.5)
    torques.plot([], [], "k--", label="rated torque")
    torques.set_xticks(x, joints)
    torques.set_ylabel("peak |τ| over the stance legs [N·m]")
    torques.set_title(f"Joint torques ({analysis.distribution} forces)")
    top = max(max(analysis.design.rated_torques), max(analysis.peak_torques.values()))
    torques.set_ylim(0, 1.45 * top)
    torques.legend(fontsize=8, loc="upper left", ncols=3)
    torques.grid(True, axis="y", alpha=0.3)
    labels = [f"{np.degrees(s.heading):+.0f}°" for s in analysis.slopes]
    slopes.bar(
        labels,
        [np.degrees(s.max_slope) for s in analysis.slopes],
        color=[COLORS[2] if s.limited_by == "slide" else COLORS[3] for s in analysis.slopes],
    )
    for k, s in enumerate(analysis.slopes):
        slopes.annotate(s.limited_by, (k, np.degrees(s.max_slope)), ha="center", va="bottom")
    slopes.set_xlabel("uphill heading, body frame")
    slopes.set_ylabel("max slope [°]")
    slopes.set_title(f"Steepest slope (μ = {analysis.friction:g})")
    slopes.grid(True, axis="y", alpha=0.3)
    l1, l2, l3 = analysis.design.lengths
    fig.suptitle(
        f"Statics, l = ({l1:.3g}, {l2:.3g}, {l3:.3g}) m, payload {analysis.payload.mass:g} kg; "
        f"capacity {analysis.capacity.mass:.1f} kg ({analysis.capacity.limited_by})"
    )
    return fig


def statics_study_figure(table: pd.DataFrame) -> Figure:
    """Peak hip and knee torque and payload capacity against tibia ratio, per coxa ratio."""
    fig = new_figure(13, 4.5)
    panels = fig.subplots(1, 3)
    columns = (
        ("peak_hip_torque", "peak hip |τ| over the extremes [N·m]"),
        ("peak_knee_torque", "peak knee |τ| over the extremes [N·m]"),
        ("payload_capacity", "payload capacity at the nominal stance [kg]"),
    )
    for ax, (column, label) in zip(panels, columns, strict=True):
        for (r1, group), color in zip(table.groupby("l1_ratio", sort=True), COLORS, strict=False):
            ax.plot(group["l3_ratio"], group[column], color=color, label=f"l1 ratio {r1:.2f}")
        ax.set_xlabel("l3 ratio [-]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    panels[0].legend(fontsize=8)
    fig.suptitle(
        "What each design costs: torques and payload (axis-locked extremes, min-norm forces)"
    )
    return fig
