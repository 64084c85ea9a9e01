"""Statics figures: torques against ratings, slopes, payload capacity."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from hexaleg.evaluation.metrics import METRICS
from hexaleg.gait.analysis import STUDY_GAIT
from hexaleg.gait.spec import Gait
from hexaleg.output.figures.canvas import (
    COLORS,
    drawn,
    log_scale,
    magnitude_axis,
    name_largest,
    new_figure,
)
from hexaleg.output.figures.marks import Mark, draw_marks, rating_line
from hexaleg.ratings import NEEDS_RATING
from hexaleg.statics.loads import LoadsAnalysis

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


SLOPE_CAUSES = {"slide": "sliding: tan(slope) reaches μ", "tip": "tipping over"}
"""What stops the robot on a slope, in words."""

DISTRIBUTION_WORDS = {
    "min-norm": "least Σ|f|² (min-norm)",
    "min-torque": "least torque relative to the ratings (min-torque)",
}
"""How a figure names each way of sharing the load between the standing feet."""

SLOPE_TOLERANCE = np.radians(0.05)
"""Steepest slopes closer than this count as equal across headings [rad]."""


def slopes_differ(analysis: LoadsAnalysis) -> bool:
    """Whether the steepest slope or its cause differs between uphill headings."""
    angles = [s.max_slope for s in analysis.slopes]
    causes = {str(s.limited_by) for s in analysis.slopes}
    return len(causes) > 1 or float(np.ptp(angles)) > SLOPE_TOLERANCE


@drawn
def loads_figure(
    analysis: LoadsAnalysis,
    walking: Mapping[str, float] | None = None,
    gait: Gait = STUDY_GAIT,
) -> Figure:
    """Peak |τ| per joint type standing (and walking) against its rating; slopes per heading.

    Args:
        analysis: The statics.
        walking: The peak |τ| per joint type [N·m] walking ``gait`` with the same
            payload, drawn beside the standing peaks if given.
        gait: The gait walked (named in the legend).

    The slope panel is drawn only where the headings differ; else the report states the
    one slope in a table.

    """
    with_slopes = slopes_differ(analysis)
    fig = new_figure(4.2)
    torques, *rest = fig.subplots(1, 2 if with_slopes else 1, squeeze=False)[0]
    _torque_bars(torques, analysis, walking, gait)
    if rest:
        _slope_bars(rest[0], analysis)
    l1, l2, l3 = analysis.design.lengths
    capacity = analysis.capacity
    what = "standing and walking" if walking is not None else "standing"
    held = (
        NEEDS_RATING
        if capacity is None
        else f"{capacity.mass:.1f} kg, limited by {capacity.limited_by}"
    )
    fig.suptitle(
        f"Peak joint torques {what} (l1, l2, l3 = {l1:.3g}, {l2:.3g}, {l3:.3g} m) against "
        f"their ratings\nstanding payload capacity {held}"
    )
    return fig


def _torque_bars(
    ax: Axes, analysis: LoadsAnalysis, walking: Mapping[str, float] | None, gait: Gait
) -> None:
    nominal = analysis.nominal.peak_torques()
    joints = list(nominal)
    x = np.arange(len(joints))
    mode = "axis-locked" if analysis.mode == "axis" else "free-coupled"
    series: list[tuple[str, Mapping[str, float]]] = [
        ("standing, nominal stance", nominal),
        (f"standing, peak over the 12 {mode} extremes", analysis.peak_torques),
    ]
    if walking is not None:
        series.append((f"walking {gait.named}, peak", walking))
    width = 0.8 / len(series)
    for k, (label, peaks) in enumerate(series):
        offset = (k - (len(series) - 1) / 2) * width
        ax.bar(x + offset, [peaks[j] for j in joints], width, color=COLORS[k], label=label)
    ratings = analysis.design.rated_torques or ()  # none drawn where not given
    for k, rated in enumerate(ratings):
        ax.hlines(rated, k - 0.45, k + 0.45, colors="k", linestyles="--", lw=1.5)
    if ratings:
        ax.plot([], [], "k--", label="rated torque")
    ax.set_xticks(x, [f"{joint} joints" for joint in joints])
    ax.set_ylabel("largest |τ| over the legs [N·m]")
    ax.set_title(f"Foot forces shared by {DISTRIBUTION_WORDS.get(analysis.distribution, '?')}")
    tops = [max(peaks.values()) for _, peaks in series]
    ax.set_ylim(0, 1.45 * max(*ratings, *tops))
    ax.legend(loc="upper left", ncols=2, fontsize=7.5)
    ax.grid(True, axis="y", alpha=0.3)


def _slope_bars(ax: Axes, analysis: LoadsAnalysis) -> None:
    labels = [f"{np.degrees(s.heading):+.0f}°" for s in analysis.slopes]
    ax.bar(
        labels,
        [np.degrees(s.max_slope) for s in analysis.slopes],
        color=[COLORS[2] if str(s.limited_by) == "slide" else COLORS[3] for s in analysis.slopes],
    )
    for k, s in enumerate(analysis.slopes):
        ax.annotate(
            str(s.limited_by), (k, np.degrees(s.max_slope)), ha="center", va="bottom", fontsize=8
        )
    ax.set_xlabel("uphill heading in the body frame (0° = forward)")
    ax.set_ylabel("steepest slope it stands on [°]")
    ax.set_title(f"Steepest slope by heading (μ = {analysis.friction:g})")
    ax.grid(True, axis="y", alpha=0.3)


@drawn
def statics_study_figure(
    table: pd.DataFrame,
    rated: Mapping[str, float] | None = None,
    marks: Sequence[Mark] = (),
    gait: Gait = STUDY_GAIT,
) -> Figure:
    """Hip and knee torques over the extremes and the payload capacities, against tibia ratio.

    The hip and knee side by side over the payload, sharing the tibia-ratio axis, each
    joint's rating on its torque panel; the standing payload capacity spans decades over a
    sweep (a short femur lifts tonnes), so its axis is logarithmic, the largest named, and
    the walking payload capacity (walking ``gait``, every rating) is drawn beside it,
    dashed, where the leg walks.

    Args:
        table: The study's rows.
        rated: Rated torque per joint type [N·m] (``hip``, ``knee``), drawn as lines.
        marks: Designs marked on every panel (your design, the recommended one).
        gait: The gait the study's designs walk (named in the title).

    """
    fig = new_figure(6.6)
    grid = fig.add_gridspec(2, 2, height_ratios=(1.0, 1.15))
    hip = fig.add_subplot(grid[0, 0])
    panels = [hip, fig.add_subplot(grid[0, 1], sharex=hip), fig.add_subplot(grid[1, :])]
    standing = METRICS.payload_capacity.name
    columns = (
        ("peak_hip_torque", "hip [N·m]", "Largest hip |τ| standing"),
        ("peak_knee_torque", "knee [N·m]", "Largest knee |τ| standing"),
        (
            standing,
            "payload [kg], log scale",
            f"Payload capacity: standing (solid), walking {gait.named} (dashed)",
        ),
    )
    groups = list(zip(table.groupby("l1_ratio", sort=True), COLORS, strict=False))
    for ax, (column, label, title) in zip(panels, columns, strict=True):
        for (r1, group), color in groups:
            ax.plot(group["l3_ratio"], group[column], color=color, label=f"coxa ratio {r1:.2f}")
        draw_marks(ax, marks, "l3_ratio", column)
        ax.set_ylabel(label)
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    for ax, joint in zip(panels[:2], ("hip", "knee"), strict=True):
        magnitude_axis(ax, table[f"peak_{joint}_torque"])
        if rated:  # none drawn where the design gives no ratings
            rating_line(ax, rated[joint], joint)
    _walking_payload(panels[2], table, groups, marks)
    handles, labels = panels[0].get_legend_handles_labels()
    unique = dict(zip(labels, handles, strict=True))
    fig.legend(unique.values(), unique.keys(), loc="outside lower center", ncols=4, fontsize=7.5)
    for ax in panels:
        ax.set_xlabel("tibia ratio l3 / L [-]")
    fig.suptitle(
        "What each design of the sweep costs (foot forces shared by least Σ|f|²)\ntorques: "
        "the largest over the nominal stance and its 12 extremes"
    )
    return fig


def _walking_payload(
    payload: Axes, table: pd.DataFrame, groups: Sequence[Any], marks: Sequence[Mark]
) -> None:
    """The walking payload capacity, dashed, beside the standing one; the axis logarithmic."""
    standing, walking = METRICS.payload_capacity.name, METRICS.walking_payload_capacity.name
    if walking in table:
        for (_, group), color in groups:
            carried = group[walking].where(group[walking] > 0)
            payload.plot(group["l3_ratio"], carried, color=color, ls="--")
        draw_marks(payload, marks, "l3_ratio", walking)
    log_scale(payload, "y")
    payload.set_ylim(bottom=1.0)  # a leg that walks with less than a kilogram: not drawn
    name_largest(payload, table["l3_ratio"], table[standing], design_names(table, standing))


def design_names(table: pd.DataFrame, column: str) -> list[str]:
    """Each design of a study table named by a capacity (a column [kg]) and its lengths."""
    return [
        f"{row[column]:.0f} kg: coxa {row['l1']:.2f}, femur {row['l2']:.2f}, "
        f"tibia {row['l3']:.2f} m"
        for row in table.to_dict(orient="records")
    ]
