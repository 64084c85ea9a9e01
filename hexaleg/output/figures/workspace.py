"""Swing-phase workspace figures (paper §4, Fig 5–8)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.kinematics import planar_foot_position
from hexaleg.output.figures.canvas import COLORS, LIMIT_SET_TITLES, drawn, new_figure, save
from hexaleg.paper import L1_RATIOS
from hexaleg.swing.workspace import (
    CoxaSeries,
    MonteCarloWorkspace,
    PlanarWorkspace,
    WorkspaceAnalysis,
    coxa_series,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


@drawn
def monte_carlo_figure(cloud: MonteCarloWorkspace) -> Figure:
    """Fig 5: the Monte Carlo point cloud of the foot in the leg-root frame."""
    fig = new_figure(5.4)
    ax = fig.add_subplot(projection="3d")
    points = cloud.points
    cloud_art = ax.scatter(
        points[:, 0],
        points[:, 1],
        points[:, 2],
        s=0.4,
        c=points[:, 2],
        cmap="viridis",
        rasterized=True,  # 20 000 dots: an image inside the SVG, the axes stay vector
    )
    ax.scatter([0], [0], [0], s=40, c="k", marker="^", label="leg root")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    limits = LIMIT_SET_TITLES.get(cloud.limits.name, cloud.limits.name)
    ax.set_title(
        f"Reachable foot positions in the leg-root frame, {len(points):,} random poses ({limits})"
    )
    ax.set_box_aspect(np.ptp(points, axis=0) + 1e-9, zoom=0.85)  # labels stay inside
    ax.legend(loc="upper left")
    fig.colorbar(cloud_art, ax=ax, shrink=0.6, label="foot height z [m] (leg-root frame)")
    return fig


@drawn
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
    fig = new_figure(5.2)
    ax = fig.add_subplot()
    for ws, color, label in (
        (rectangular, COLORS[0], "rectangular joint domain (Table 3)"),
        (improved, COLORS[1], "improved joint domain (Table 4)"),
    ):
        closed = np.vstack([ws.boundary, ws.boundary[:1]])
        ax.fill(closed[:, 0], closed[:, 1], color=color, alpha=0.25)
        ax.plot(closed[:, 0], closed[:, 1], color=color, label=f"{label}: {ws.area:.4f} m²")
    ax.plot([0, rectangular.lengths[0]], [0, 0], "k-", lw=3, label="coxa")
    if nominal_foot is not None:
        _draw_ground(ax, nominal_foot)
    ax.set_xlabel("distance from the leg root along the leg [m]")
    ax.set_ylabel("height above the leg root [m]")
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2)
    l1, l2, l3 = rectangular.lengths
    ax.set_title(f"Foot workspace in the leg's plane, l1, l2, l3 = {l1:.3f}, {l2:.3f}, {l3:.3f} m")
    return fig


def _draw_ground(ax: Axes, nominal_foot: tuple[float, float]) -> None:
    """The ground through the nominal foot, the foot, and the standing height."""
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
        bbox={
            "boxstyle": "round,pad=0.2",
            "facecolor": "white",
            "edgecolor": "none",
            "alpha": 0.85,
        },
    )  # on a white ground: the workspace's boundaries may pass behind it
    ax.plot([0, 0], [0, z_foot], color="#8a5a00", ls=":", lw=1)


@drawn
def l1_series_figure(series: CoxaSeries) -> Figure:
    """Fig 8: improved workspace per coxa ratio (top), its area, and area against l3 ratio."""
    fig = new_figure(6.4)
    panels = fig.subplot_mosaic([["shapes", "bars"], ["shapes", "curve"]], width_ratios=(1.0, 1.25))
    shapes, bars, curve = panels["shapes"], panels["bars"], panels["curve"]
    for ws, ratio, color in zip(series.workspaces, series.l1_ratios, COLORS, strict=False):
        closed = np.vstack([ws.boundary, ws.boundary[:1]])
        shapes.plot(closed[:, 0], closed[:, 1], color=color, label=f"coxa ratio {ratio:.2f}")
    shapes.set_xlabel("along the leg [m]")
    shapes.set_ylabel("height [m]")
    shapes.set_aspect("equal")
    shapes.grid(True, alpha=0.3)
    shapes.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncols=2)
    shapes.set_title("Improved workspace per coxa ratio\n(femur = tibia)")
    bars.bar(
        [f"{r:.2f}" for r in series.l1_ratios],
        [ws.area for ws in series.workspaces],
        color=COLORS[0],
    )
    bars.set_xlabel("coxa ratio l1 / L [-]")
    bars.set_ylabel("improved area [m²]")
    bars.set_title("Area falls as the coxa grows")
    l3_ratios, areas = series.l3_ratios, series.areas
    curve.plot(l3_ratios, areas, color=COLORS[1])
    best = int(np.argmax(areas))
    curve.axvline((1 - series.fixed_l1_ratio) / 2, color="k", ls="--", lw=1, label="l2 = l3")
    curve.plot(l3_ratios[best], areas[best], "o", color=COLORS[3], label="largest area")
    curve.set_xlabel("tibia ratio l3 / L [-]")
    curve.set_ylabel("improved area [m²]")
    curve.set_title(f"Coxa ratio {series.fixed_l1_ratio:.2f}: peak at femur = tibia")
    curve.legend()
    curve.grid(True, alpha=0.3)
    return fig


def write_workspace_figures(
    analysis: WorkspaceAnalysis,
    out_dir: str | os.PathLike[str],
    series: CoxaSeries | None = None,
    svg: bool = False,
) -> list[Path]:
    """Fig 5–8 of a :class:`~hexaleg.swing.workspace.WorkspaceAnalysis`; returns the PNGs.

    ``series`` is Fig 8's data (computed for the paper's coxa ratios if omitted); ``svg``
    writes an SVG beside each PNG.
    """
    out = Path(out_dir)
    design = analysis.design
    series = series or coxa_series(design, L1_RATIOS)
    return [
        save(monte_carlo_figure(analysis.monte_carlo), out / "workspace_monte_carlo.png", svg),
        save(
            planar_workspace_figure(
                analysis.rectangular,
                analysis.improved,
                tuple(planar_foot_position(design.lengths, *design.nominal_angles[1:])),
            ),
            out / "workspace_planar.png",
            svg,
        ),
        save(l1_series_figure(series), out / "workspace_l1_series.png", svg),
    ]
