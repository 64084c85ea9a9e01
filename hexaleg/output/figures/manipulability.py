"""Manipulability figures (paper §5, Fig 10–11)."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.output.figures.canvas import COLORS, new_figure, save, shade_paper_claim
from hexaleg.paper import TABLE5
from hexaleg.swing.manipulability import (
    AverageManipulabilityMap,
    ManipulabilityAnalysis,
    ManipulabilitySurface,
    manipulability_surface,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def manipulability_surface_figure(
    surfaces: Sequence[ManipulabilitySurface], labels: Sequence[str]
) -> Figure:
    """Fig 10: w over (θ2, θ3) for several designs, as 3-D surfaces on one colour scale."""
    columns = 2 if len(surfaces) > 1 else 1
    rows = int(np.ceil(len(surfaces) / columns))
    fig = new_figure(6 * columns, 4.5 * rows)
    top = max(float(surface.w.max()) for surface in surfaces)
    for k, (surface, label) in enumerate(zip(surfaces, labels, strict=True)):
        ax = fig.add_subplot(rows, columns, k + 1, projection="3d")
        t2, t3 = np.meshgrid(surface.theta2, surface.theta3, indexing="ij")
        ax.plot_surface(np.degrees(t2), np.degrees(t3), surface.w, cmap="viridis", vmin=0, vmax=top)
        ax.set_zlim(0, top)
        ax.set_xlabel("θ2 [°]")
        ax.set_ylabel("θ3 [°]")
        ax.set_zlabel("w [m³]")
        ax.set_title(label)
    return fig


def average_manipulability_figure(result: AverageManipulabilityMap) -> Figure:
    """Fig 11: w_A against l3 ratio, one curve per l1 ratio, on both domains, peaks marked."""
    fig = new_figure(12, 4.8)
    axes = fig.subplots(1, 2, sharey=True)
    panels = (
        (result.rectangular, result.peak_rectangular, "rectangular domain (eq 26)"),
        (result.improved, result.peak_improved, "improved domain (eq 26 ∩ Table 4)"),
    )
    for ax, (values, peaks, title) in zip(axes, panels, strict=True):
        for r1, row, peak, color in zip(result.l1_ratios, values, peaks, COLORS, strict=False):
            ax.plot(result.l3_ratios, row, color=color, label=f"l1 ratio {r1:.2f}: peak {peak:.3f}")
            ax.axvline(peak, color=color, ls=":", lw=1)
        shade_paper_claim(ax)
        ax.set_xlabel(f"l3 ratio [-] (total {result.total:g} m)")
        ax.set_title(title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("average manipulability w_A [m³]")
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
    l1, l2, l3 = analysis.design.lengths
    labels = [f"this design, l = ({l1:.3g}, {l2:.3g}, {l3:.3g}) m"] + [
        f"Table 5, l1 ratio {r.l1_ratio:.2f}" for r in TABLE5
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
