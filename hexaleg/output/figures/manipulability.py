"""Manipulability figures (paper §5, Fig 10–11)."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.output.figures.canvas import COLORS, drawn, mark_paper_w_a_peak, new_figure, save
from hexaleg.output.figures.marks import FLAT_LABEL, flat_top
from hexaleg.paper import TABLE5
from hexaleg.ratios import ratio_text
from hexaleg.swing.manipulability import (
    AverageManipulabilityMap,
    ManipulabilityAnalysis,
    ManipulabilitySurface,
    manipulability_surface,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure


@drawn
def manipulability_surface_figure(
    surfaces: Sequence[ManipulabilitySurface], labels: Sequence[str]
) -> Figure:
    """Fig 10: w over (θ2, θ3) for several designs, as 3-D surfaces on one colour scale."""
    from matplotlib.ticker import MaxNLocator

    columns = 2 if len(surfaces) > 1 else 1
    rows = int(np.ceil(len(surfaces) / columns))
    fig = new_figure(4.6, 5.6) if rows == 1 else new_figure(3.3 * rows + 0.3)
    top = max(float(surface.w.max()) for surface in surfaces)
    for k, (surface, label) in enumerate(zip(surfaces, labels, strict=True)):
        ax = fig.add_subplot(rows, columns, k + 1, projection="3d")
        t2, t3 = np.meshgrid(surface.theta2, surface.theta3, indexing="ij")
        ax.plot_surface(
            np.degrees(t2),
            np.degrees(t3),
            surface.w,
            cmap="viridis",
            vmin=0,
            vmax=top,
            rasterized=True,  # 14 641 facets: an image inside the SVG, the axes stay vector
        )
        ax.set_zlim(0, top)
        ax.set_box_aspect(None, zoom=0.82)  # room for the z label inside the panel
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            axis.set_major_locator(MaxNLocator(4))
        ax.set_xlabel("hip θ2 [°]")
        ax.set_ylabel("knee θ3 [°]")
        ax.set_zlabel("w [m³]")
        ax.set_title(label)
    fig.suptitle("Manipulability w = |det J| over the hip and knee angles (eq 26 limits)")
    return fig


@drawn
def average_manipulability_figure(result: AverageManipulabilityMap) -> Figure:
    """Fig 11: w_A against l3 ratio, one curve per l1 ratio, on both domains, peaks marked.

    The paper's claim (§5.4: w_A peaks at l3 ≈ 0.45) is drawn as that one line.
    """
    fig = new_figure(6.8)
    axes = fig.subplots(2, 1, sharex=True)
    panels = (
        (result.rectangular, result.peak_rectangular, "on eq 26's rectangular joint domain"),
        (result.improved, result.peak_improved, "on the improved domain (eq 26 and Table 4)"),
    )
    for ax, (values, peaks, where) in zip(axes, panels, strict=True):
        curves = zip(result.l1_ratios, values, peaks, COLORS, strict=False)
        for k, (r1, row, peak, color) in enumerate(curves):
            ax.plot(
                result.l3_ratios, row, color=color,
                label=f"coxa ratio {r1:.2f}: refined peak at {ratio_text(peak)}",
            )  # fmt: skip
            ax.axvline(peak, color=color, ls=":", lw=1)
            flat_top(ax, result.l3_ratios, row, color, FLAT_LABEL if k == 0 else None)
        mark_paper_w_a_peak(ax)
        ax.set_title(f"Average manipulability {where}")
        ax.set_ylabel("average manipulability w_A [m³]")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5))
    axes[1].set_xlabel(f"tibia ratio l3 / L [-] (leg length L = {result.total:g} m)")
    return fig


def table5_surfaces(analysis: ManipulabilityAnalysis) -> list[ManipulabilitySurface]:
    """The design's own surface, then Table 5's designs scaled to its leg length."""
    design = analysis.design
    scale = design.leg_length / 1000.0  # Table 5 is for a 1000 mm leg
    designs = [design.lengths] + [
        (r.l1_mm * scale, r.l2_mm * scale, r.l3_mm * scale) for r in TABLE5
    ]
    return [manipulability_surface(lengths, design.manipulability_limits) for lengths in designs]


def write_manipulability_figures(
    analysis: ManipulabilityAnalysis,
    average_map: AverageManipulabilityMap,
    out_dir: str | os.PathLike[str],
    surfaces: Sequence[ManipulabilitySurface] | None = None,
    svg: bool = False,
) -> list[Path]:
    """Fig 10–11 of a :class:`~hexaleg.swing.manipulability.ManipulabilityAnalysis`.

    ``surfaces`` are the design's own and Table 5's (:func:`table5_surfaces` if omitted);
    ``svg`` writes an SVG beside each PNG.
    """
    out = Path(out_dir)
    surfaces = list(surfaces or table5_surfaces(analysis))
    scale = analysis.design.leg_length / 1000.0  # Table 5 is for a 1000 mm leg
    l1, l2, l3 = analysis.design.lengths
    labels = [f"this design, l = ({l1:.3g}, {l2:.3g}, {l3:.3g}) m"] + [
        f"Table 5, coxa ratio {r.l1_ratio:.2f} (l2 = l3 = {r.l2_mm * scale:.3g} m)" for r in TABLE5
    ]
    return [
        save(
            manipulability_surface_figure(surfaces[:1], labels[:1]),
            out / "manipulability_surface.png",
            svg,
        ),
        save(
            manipulability_surface_figure(surfaces[1:], labels[1:]),
            out / "manipulability_surfaces_table5.png",
            svg,
        ),
        save(
            average_manipulability_figure(average_map), out / "manipulability_average_map.png", svg
        ),
    ]
