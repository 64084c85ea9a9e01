"""Matplotlib figures of the paper, written as PNG files without a display.

Uses matplotlib's object API (``Figure`` with the Agg canvas): no pyplot, no
global state, safe in worker processes. Axes carry units; angles are plotted
in degrees and lengths in metres, as labelled.
"""

from __future__ import annotations

import io
import os
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from hexaleg._io import atomic_write_bytes
from hexaleg._typing import Lengths
from hexaleg.design import l3_ratio_grid
from hexaleg.kinematics import manipulability, planar_foot_position
from hexaleg.limits import JointLimits
from hexaleg.paper import CLAIMED_L3_RATIO_PEAK, L1_RATIOS, TABLE5
from hexaleg.stance.constraints import AXES
from hexaleg.stance.extremes import FlexibilityResult
from hexaleg.statics.loads import LoadsAnalysis
from hexaleg.study.sweep import peak_table
from hexaleg.swing.manipulability import (
    AverageManipulabilityMap,
    ManipulabilityAnalysis,
    joint_grid,
)
from hexaleg.swing.workspace import (
    MonteCarloWorkspace,
    PlanarWorkspace,
    WorkspaceAnalysis,
    improved_area_by_l3_ratio,
    planar_workspace,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

DPI = 150
_COLORS = ("#1b6ca8", "#e07b00", "#2f9e44", "#c92a2a", "#7048e8", "#495057")


def _figure(width: float = 7.0, height: float = 5.0) -> Figure:
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), dpi=DPI, layout="constrained")


def _shade_paper_claim(ax: Axes) -> None:
    """Shade the tibia-ratio band the paper claims is best (§5.4, §6.3)."""
    lo, hi = CLAIMED_L3_RATIO_PEAK
    ax.axvspan(lo, hi, color="k", alpha=0.08, label=f"paper's claim {lo:.2f}–{hi:.2f}")


def save(figure: Figure, path: str | os.PathLike[str]) -> Path:
    """Render ``figure`` to PNG and write it atomically."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=DPI)
    return atomic_write_bytes(path, buffer.getvalue())


def monte_carlo_figure(cloud: MonteCarloWorkspace) -> Figure:
    """Fig 5: the Monte Carlo point cloud of the foot in the leg-root frame."""
    fig = _figure(7, 6)
    ax = fig.add_subplot(projection="3d")
    points = cloud.points
    cloud_art = ax.scatter(
        points[:, 0], points[:, 1], points[:, 2], s=0.4, c=points[:, 2], cmap="viridis"
    )
    ax.scatter([0], [0], [0], s=40, c="k", marker="^", label="leg root")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    limits = LIMIT_SET_TITLES.get(cloud.limits.name, cloud.limits.name)
    ax.set_title(f"Foot workspace, Monte Carlo, N = {len(points):,} ({limits})")
    ax.set_box_aspect(np.ptp(points, axis=0) + 1e-9)
    ax.legend(loc="upper left")
    fig.colorbar(cloud_art, ax=ax, shrink=0.6, label="foot height z [m] (leg-root frame)")
    return fig


LIMIT_SET_TITLES = {
    "workspace_limits": "Table 2 limits",
    "improved_limits": "Table 4 limits",
    "manipulability_limits": "eq 26 limits",
    "stance_limits": "stance limits",
}
"""How a figure names each of the design's joint-limit sets."""


def planar_workspace_figure(
    rectangular: PlanarWorkspace,
    improved: PlanarWorkspace,
    nominal_foot: tuple[float, float] | None = None,
) -> Figure:
    """Fig 6–7: planar workspace (θ1 = 0) of the rectangular and improved domains.

    Args:
        rectangular: The rectangular-domain workspace (Table 3).
        improved: The improved-domain workspace (Table 4).
        nominal_foot: The foot (x, z) at the nominal stance in the leg plane [m]; if
            given, the ground line through it and the standing height are drawn.

    """
    fig = _figure()
    ax = fig.add_subplot()
    for ws, color, label in (
        (rectangular, _COLORS[0], "rectangular (Table 3)"),
        (improved, _COLORS[1], "improved (Table 4)"),
    ):
        closed = np.vstack([ws.boundary, ws.boundary[:1]])
        ax.fill(closed[:, 0], closed[:, 1], color=color, alpha=0.25)
        ax.plot(closed[:, 0], closed[:, 1], color=color, label=f"{label}: {ws.area:.4f} m²")
    ax.plot([0, rectangular.lengths[0]], [0, 0], "k-", lw=3, label="coxa")
    if nominal_foot is not None:
        x_foot, z_foot = nominal_foot
        ax.axhline(z_foot, color="#8a5a00", lw=1.5, label="ground at the nominal stance")
        ax.plot([x_foot], [z_foot], "o", color="#8a5a00", label="nominal foot")
        ax.annotate(
            f"leg root {-z_foot:.3f} m above the ground",
            (0.0, z_foot / 2),
            xytext=(6, 0),
            textcoords="offset points",
            fontsize=8,
            va="center",
        )
        ax.plot([0, 0], [0, z_foot], color="#8a5a00", ls=":", lw=1)
    ax.set_xlabel("x in leg plane [m]")
    ax.set_ylabel("z [m]")
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    fig.legend(loc="outside lower center", ncols=3, fontsize=8)
    l1, l2, l3 = rectangular.lengths
    ax.set_title(f"Planar foot workspace, l = ({l1:.3f}, {l2:.3f}, {l3:.3f}) m")
    return fig


def l1_series_figure(
    workspaces: Sequence[PlanarWorkspace],
    l1_ratios: Sequence[float],
    l3_ratios: np.ndarray,
    areas_by_l3: np.ndarray,
    fixed_l1_ratio: float,
) -> Figure:
    """Fig 8: improved workspace per coxa ratio, its area, and the area against l3 ratio."""
    fig = _figure(13, 4.5)
    shapes, bars, curve = fig.subplots(1, 3)
    for ws, ratio, color in zip(workspaces, l1_ratios, _COLORS, strict=False):
        closed = np.vstack([ws.boundary, ws.boundary[:1]])
        shapes.plot(closed[:, 0], closed[:, 1], color=color, label=f"l1 ratio {ratio:.2f}")
    shapes.set_xlabel("x in leg plane [m]")
    shapes.set_ylabel("z [m]")
    shapes.set_aspect("equal")
    shapes.grid(True, alpha=0.3)
    shapes.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0.0, -0.18), ncols=2)
    shapes.set_title("Improved workspace (l2 = l3)")
    bars.bar([f"{r:.2f}" for r in l1_ratios], [ws.area for ws in workspaces], color=_COLORS[0])
    bars.set_xlabel("l1 ratio [-]")
    bars.set_ylabel("improved area [m²]")
    bars.set_title("Area falls as the coxa grows")
    curve.plot(l3_ratios, areas_by_l3, color=_COLORS[1])
    best = int(np.argmax(areas_by_l3))
    curve.axvline((1 - fixed_l1_ratio) / 2, color="k", ls="--", lw=1, label="l2 = l3")
    curve.plot(l3_ratios[best], areas_by_l3[best], "o", color=_COLORS[3], label="largest area")
    curve.set_xlabel("l3 ratio [-]")
    curve.set_ylabel("improved area [m²]")
    curve.set_title(f"l1 ratio {fixed_l1_ratio:.2f}: peak at l2 = l3")
    curve.legend(fontsize=8)
    curve.grid(True, alpha=0.3)
    return fig


def manipulability_surface_figure(
    designs: Sequence[Lengths], limits: JointLimits, labels: Sequence[str]
) -> Figure:
    """Fig 10: w over (θ2, θ3) for several designs, as 3-D surfaces."""
    hip, knee = joint_grid(limits)
    t2, t3 = np.meshgrid(hip, knee, indexing="ij")
    columns = 2 if len(designs) > 1 else 1
    rows = int(np.ceil(len(designs) / columns))
    fig = _figure(6 * columns, 4.5 * rows)
    top = max(float(manipulability(d, t2, t3).max()) for d in designs)
    for k, (lengths, label) in enumerate(zip(designs, labels, strict=True)):
        ax = fig.add_subplot(rows, columns, k + 1, projection="3d")
        w = manipulability(lengths, t2, t3)
        ax.plot_surface(np.degrees(t2), np.degrees(t3), w, cmap="viridis", vmin=0, vmax=top)
        ax.set_zlim(0, top)
        ax.set_xlabel("θ2 [°]")
        ax.set_ylabel("θ3 [°]")
        ax.set_zlabel("w [m³]")
        ax.set_title(label)
    return fig


def average_manipulability_figure(result: AverageManipulabilityMap) -> Figure:
    """Fig 11: w_A against l3 ratio, one curve per l1 ratio, on both domains, peaks marked."""
    fig = _figure(12, 4.8)
    axes = fig.subplots(1, 2, sharey=True)
    panels = (
        (result.rectangular, result.peak_rectangular, "rectangular domain (eq 26)"),
        (result.improved, result.peak_improved, "improved domain (eq 26 ∩ Table 4)"),
    )
    for ax, (values, peaks, title) in zip(axes, panels, strict=True):
        for r1, row, peak, color in zip(result.l1_ratios, values, peaks, _COLORS, strict=False):
            ax.plot(result.l3_ratios, row, color=color, label=f"l1 ratio {r1:.2f}: peak {peak:.3f}")
            ax.axvline(peak, color=color, ls=":", lw=1)
        _shade_paper_claim(ax)
        ax.set_xlabel(f"l3 ratio [-] (total {result.total:g} m)")
        ax.set_title(title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("average manipulability w_A [m³]")
    return fig


def write_workspace_figures(
    analysis: WorkspaceAnalysis, out_dir: str | os.PathLike[str]
) -> list[Path]:
    """Fig 5–8 for a :class:`~hexaleg.workspace.WorkspaceAnalysis`; returns the files."""
    out = Path(out_dir)
    design = analysis.design
    total = design.leg_length
    series = [
        planar_workspace(
            (r * total, (1 - r) * total / 2, (1 - r) * total / 2), design.improved_limits
        )
        for r in L1_RATIOS
    ]
    fixed = design.l1 / total
    l3_ratios = l3_ratio_grid()
    l3_ratios = l3_ratios[l3_ratios < 1 - fixed - 0.02]
    areas = improved_area_by_l3_ratio(fixed, l3_ratios, total, design.improved_limits)
    return [
        save(monte_carlo_figure(analysis.monte_carlo), out / "workspace_monte_carlo.png"),
        save(
            planar_workspace_figure(
                analysis.rectangular,
                analysis.improved,
                tuple(planar_foot_position(design.lengths, *design.nominal_angles[1:])),
            ),
            out / "workspace_planar.png",
        ),
        save(
            l1_series_figure(series, L1_RATIOS, l3_ratios, areas, fixed),
            out / "workspace_l1_series.png",
        ),
    ]


def write_manipulability_figures(
    analysis: ManipulabilityAnalysis,
    average_map: AverageManipulabilityMap,
    out_dir: str | os.PathLike[str],
) -> list[Path]:
    """Fig 10–11 for a :class:`~hexaleg.manipulability.ManipulabilityAnalysis`."""
    out = Path(out_dir)
    design = analysis.design
    scale = design.leg_length / 1000.0  # Table 5 is for a 1000 mm leg
    designs = [design.lengths] + [
        (r.l1_mm * scale, r.l2_mm * scale, r.l3_mm * scale) for r in TABLE5
    ]
    l1, l2, l3 = design.lengths
    labels = [f"this design, l = ({l1:.3g}, {l2:.3g}, {l3:.3g}) m"] + [
        f"Table 5, l1 ratio {r.l1_ratio:.2f}" for r in TABLE5
    ]
    surface = manipulability_surface_figure(designs[1:], design.manipulability_limits, labels[1:])
    own = manipulability_surface_figure(designs[:1], design.manipulability_limits, labels[:1])
    return [
        save(own, out / "manipulability_surface.png"),
        save(surface, out / "manipulability_surfaces_table5.png"),
        save(average_manipulability_figure(average_map), out / "manipulability_average_map.png"),
    ]


LABEL_WIDTH = 26
"""Characters per line of a bar's cause in the extremes figure (three bars share an axis)."""


def extremes_figure(result: FlexibilityResult) -> Figure:
    """The twelve body extremes of a :class:`~hexaleg.flexibility.FlexibilityResult`."""
    fig = _figure(11, 4.8)
    translation_ax, rotation_ax = fig.subplots(1, 2)
    for ax, axes, scale, unit in (
        (translation_ax, AXES[:3], 1.0, "m"),
        (rotation_ax, AXES[3:], 180 / np.pi, "°"),
    ):
        for k, axis in enumerate(axes):
            for sign, color in ((1, _COLORS[0]), (-1, _COLORS[1])):
                extreme = result.extreme(axis, sign)
                value = extreme.value * scale
                ax.bar(k, value, color=color, width=0.6)
                ax.annotate(
                    textwrap.fill(extreme.label, LABEL_WIDTH),
                    (k, value),
                    xytext=(0, 4 if sign > 0 else -4),
                    textcoords="offset points",
                    ha="center",
                    va="bottom" if sign > 0 else "top",
                    fontsize=6.5,
                    rotation=0,
                    wrap=True,
                )
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xticks(range(3), axes)
        ax.set_ylabel(f"extreme displacement from nominal [{unit}]")
        ax.margins(y=0.25)
        ax.grid(True, axis="y", alpha=0.3)
    translation_ax.set_title("translations")
    rotation_ax.set_title("rotations")
    fig.suptitle(
        f"Body extremes ({result.mode}, stance {'+'.join(result.legs)}), FB = {result.fb:.4f}"
    )
    return fig


def fb_figure(table: pd.DataFrame, peaks: pd.DataFrame) -> Figure:
    """Fig 15: FB against tibia ratio, one curve per coxa ratio, peaks marked."""
    fig = _figure()
    ax = fig.add_subplot()
    for (r1, group), color in zip(table.groupby("l1_ratio", sort=True), _COLORS, strict=False):
        ax.plot(group["l3_ratio"], group["fb"], color=color, label=f"l1 ratio {r1:.2f}")
        peak = peaks[np.isclose(peaks["l1_ratio"], r1)].iloc[0]
        ax.plot(peak["peak_l3_ratio"], peak["peak_fb"], "o", color=color)
        ax.annotate(
            f"{peak['peak_l3_ratio']:.3f}",
            (peak["peak_l3_ratio"], peak["peak_fb"]),
            xytext=(0, 6),
            textcoords="offset points",
            ha="center",
            fontsize=8,
            color=color,
        )
    _shade_paper_claim(ax)
    ax.set_xlabel("l3 ratio [-]")
    ax.set_ylabel("body flexibility FB [-] (eq 29)")
    ax.set_title("Body flexibility against tibia ratio (peaks marked)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def ranges_figure(table: pd.DataFrame, l1_ratio: float) -> Figure:
    """Fig 14: the six ranges S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [°] for one coxa ratio."""
    fig = _figure(11, 4.5)
    left, right = fig.subplots(1, 2)
    group = table[np.isclose(table["l1_ratio"], l1_ratio)]
    for k, axis in enumerate(("x", "y", "z")):
        left.plot(group["l3_ratio"], group[f"range_{axis}"], color=_COLORS[k], label=f"S_{axis}")
    for k, axis in enumerate(("roll", "pitch", "yaw")):
        right.plot(
            group["l3_ratio"],
            np.degrees(group[f"range_{axis}"]),
            color=_COLORS[k],
            label=f"φ ({axis})",
        )
    left.set_ylabel("translation range [m]")
    right.set_ylabel("rotation range [°]")
    for ax in (left, right):
        ax.set_xlabel("l3 ratio [-]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"Ranges of the body pose, l1 ratio {l1_ratio:.2f} (eq 28)")
    return fig


def write_study_figures(table: pd.DataFrame, out_dir: str | os.PathLike[str]) -> list[Path]:
    """Fig 14 (ranges, for the smallest coxa ratio) and Fig 15 (FB curves)."""
    out = Path(out_dir)
    valid = table.dropna(subset=["fb"]) if "fb" in table else table.iloc[0:0]
    if valid.empty:
        return []
    return [
        save(fb_figure(valid, peak_table(valid)), out / "flexibility_fb.png"),
        save(ranges_figure(valid, float(valid["l1_ratio"].min())), out / "flexibility_ranges.png"),
    ]


def loads_figure(analysis: LoadsAnalysis) -> Figure:
    """Peak |τ| per joint type against its rating, and the steepest slope per heading."""
    fig = _figure(11, 4.5)
    torques, slopes = fig.subplots(1, 2)
    nominal = analysis.nominal.peak_torques()
    joints = list(nominal)
    x = np.arange(len(joints))
    torques.bar(x - 0.2, [nominal[j] for j in joints], 0.4, color=_COLORS[0], label="nominal")
    torques.bar(
        x + 0.2,
        [analysis.peak_torques[j] for j in joints],
        0.4,
        color=_COLORS[1],
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
        color=[_COLORS[2] if s.limited_by.kind == "slide" else _COLORS[3] for s in analysis.slopes],
    )
    for k, s in enumerate(analysis.slopes):
        slopes.annotate(str(s.limited_by), (k, np.degrees(s.max_slope)), ha="center", va="bottom")
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
    fig = _figure(13, 4.5)
    panels = fig.subplots(1, 3)
    columns = (
        ("peak_hip_torque", "peak hip |τ| over the extremes [N·m]"),
        ("peak_knee_torque", "peak knee |τ| over the extremes [N·m]"),
        ("payload_capacity", "payload capacity at the nominal stance [kg]"),
    )
    for ax, (column, label) in zip(panels, columns, strict=True):
        for (r1, group), color in zip(table.groupby("l1_ratio", sort=True), _COLORS, strict=False):
            ax.plot(group["l3_ratio"], group[column], color=color, label=f"l1 ratio {r1:.2f}")
        ax.set_xlabel("l3 ratio [-]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    panels[0].legend(fontsize=8)
    fig.suptitle(
        "What each design costs: torques and payload (axis-locked extremes, min-norm forces)"
    )
    return fig


def pareto_figure(table: pd.DataFrame, front: pd.DataFrame) -> Figure:
    """FB against payload capacity for every design; the Pareto front and its best marked."""
    fig = _figure(7.5, 5.5)
    ax = fig.add_subplot()
    ax.scatter(table["payload_capacity"], table["fb"], s=8, color="#bbbbbb", label="every design")
    for (r1, group), color in zip(front.groupby("l1_ratio", sort=True), _COLORS, strict=False):
        ax.scatter(
            group["payload_capacity"],
            group["flexibility"],
            s=24,
            color=color,
            label=f"Pareto front, l1 ratio {r1:.2f}",
        )
    best = front.iloc[0]
    ax.scatter(
        [best["payload_capacity"]],
        [best["flexibility"]],
        s=220,
        marker="*",
        color="k",
        label=f"recommended: l3 ratio {best['l3_ratio']:.3f}, l1 ratio {best['l1_ratio']:.2f}",
    )
    ax.set_xlabel("payload capacity [kg]")
    ax.set_ylabel("body flexibility FB [-] (eq 29)")
    ax.set_title("Pareto front of improved area, w_A, FB and payload capacity")
    ax.grid(True, alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize=8)
    return fig
