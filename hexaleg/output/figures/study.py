"""Design-study figures: FB and the six ranges against tibia ratio (Fig 14–15), Pareto."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from hexaleg.evaluation.metrics import METRICS, Metrics
from hexaleg.output.figures.canvas import (
    COLORS,
    drawn,
    name_largest,
    new_figure,
    save,
    shade_paper_band,
)
from hexaleg.output.figures.marks import FLAT_LABEL, Mark, draw_marks, flat_top
from hexaleg.output.figures.statics import design_names
from hexaleg.ratios import ratio_text
from hexaleg.study.sweep import peak_table

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

FB = METRICS.fb.name
"""The study table's column of FB."""
WALKING_PAYLOAD = METRICS.walking_payload_capacity.name
"""The study table's column of the walking payload capacity."""


@drawn
def fb_figure(table: pd.DataFrame, peaks: pd.DataFrame, marks: Sequence[Mark] = ()) -> Figure:
    """Fig 15: FB against tibia ratio, one curve per coxa ratio, peaks and flat tops marked."""
    fig = new_figure(4.8)
    ax = fig.add_subplot()
    for k, ((r1, group), color) in enumerate(
        zip(table.groupby("l1_ratio", sort=True), COLORS, strict=False)
    ):
        ax.plot(group["l3_ratio"], group[FB], color=color, label=f"coxa ratio {r1:.2f}")
        flat_top(ax, group["l3_ratio"], group[FB], color, FLAT_LABEL if k == 0 else None)
        peak = peaks[np.isclose(peaks["l1_ratio"], r1)].iloc[0]
        ax.plot(peak["peak_l3_ratio"], peak["peak_fb"], "o", color=color)
        ax.annotate(
            ratio_text(peak["peak_l3_ratio"]),
            (peak["peak_l3_ratio"], peak["peak_fb"]),
            xytext=(0, 6),
            textcoords="offset points",
            ha="center",
            fontsize=8,
            color=color,
        )
    shade_paper_band(ax, "FB peaks")
    draw_marks(ax, marks, "l3_ratio", FB)
    ax.set_xlabel("tibia ratio l3 / L [-]")
    ax.set_ylabel("body flexibility FB [-] (eq 29)")
    ax.set_title("Body flexibility against tibia ratio, for each coxa ratio (grid peaks marked)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7.5)
    return fig


@drawn
def ranges_figure(table: pd.DataFrame, l1_ratio: float, marks: Sequence[Mark] = ()) -> Figure:
    """Fig 14: the six ranges S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [°] for one coxa ratio.

    ``marks`` (your design, the recommended one) at this coxa ratio are drawn on each of
    the six curves at their own tibia ratio and ranges, named once per panel; a mark at
    another coxa ratio is not on these curves, so it is not drawn, and the title says so.
    """
    marks, elsewhere = _on_coxa_ratio(marks, l1_ratio)
    fig = new_figure(4.4 if marks else 3.6)
    left, right = fig.subplots(1, 2)
    group = table[np.isclose(table["l1_ratio"], l1_ratio)]
    for k, axis in enumerate(("x", "y", "z")):
        left.plot(
            group["l3_ratio"],
            group[f"range_{axis}"],
            color=COLORS[k],
            label=f"S_{axis} along {axis}",
        )
        draw_marks(left, marks, "l3_ratio", f"range_{axis}", labelled=k == 0)
    for k, (axis, about) in enumerate((("roll", "x"), ("pitch", "y"), ("yaw", "z"))):
        right.plot(
            group["l3_ratio"],
            np.degrees(group[f"range_{axis}"]),
            color=COLORS[k],
            label=f"φ_{about} ({axis})",
        )
        draw_marks(right, marks, "l3_ratio", f"range_{axis}", math.degrees(1.0), k == 0)
    left.set_ylabel("translation range [m]")
    right.set_ylabel("rotation range [°]")
    for ax in (left, right):
        ax.set_xlabel("tibia ratio l3 / L [-]")
        ax.grid(True, alpha=0.3)
        handles, labels = ax.get_legend_handles_labels()
        curves = [k for k, label in enumerate(labels) if label not in {m.label for m in marks}]
        order = curves + [k for k in range(len(labels)) if k not in curves]  # marks last
        if marks:  # under the panel, clear of the curves and the marks
            ax.legend(
                [handles[k] for k in order],
                [labels[k] for k in order],
                ncols=2,
                fontsize=7.5,
                loc="upper center",
                bbox_to_anchor=(0.5, -0.16),
            )
        else:
            ax.legend()
    title = f"How far the body can move (eq 28) against tibia ratio, coxa ratio {l1_ratio:.2f}"
    if elsewhere:
        title += "\n(not drawn, on other coxa ratios: " + ", ".join(elsewhere) + ")"
    fig.suptitle(title)
    return fig


def _on_coxa_ratio(marks: Sequence[Mark], l1_ratio: float) -> tuple[list[Mark], list[str]]:
    """The marks at coxa ratio ``l1_ratio``, and the others named with their own coxa ratio."""
    here: list[Mark] = []
    elsewhere: list[str] = []
    for mark in marks:
        own = float(mark.values.get("l1_ratio", math.nan))
        if math.isclose(own, l1_ratio, rel_tol=1e-9, abs_tol=1e-9):
            here.append(mark)
        else:
            where = f"{own:.2f}" if math.isfinite(own) else "unknown"
            elsewhere.append(f"{mark.label.split(' (')[0]} {where}")
    return here, elsewhere


def write_study_figures(
    table: pd.DataFrame,
    out_dir: str | os.PathLike[str],
    svg: bool = False,
    marks: Sequence[Mark] = (),
) -> list[Path]:
    """Fig 15 (FB curves) and Fig 14 (ranges, for the smallest coxa ratio); the PNGs.

    ``svg`` writes an SVG beside each PNG; ``marks`` are drawn on both.
    """
    out = Path(out_dir)
    valid = table.dropna(subset=[FB]) if FB in table else table.iloc[0:0]
    if valid.empty:
        return []
    return [
        save(fb_figure(valid, peak_table(valid), marks), out / "flexibility_fb.png", svg),
        save(
            ranges_figure(valid, float(valid["l1_ratio"].min()), marks),
            out / "flexibility_ranges.png",
            svg,
        ),
    ]


@drawn
def pareto_figure(table: pd.DataFrame, front: pd.DataFrame, yours: Metrics | None = None) -> Figure:
    """FB against walking payload capacity for every design; the Pareto front and its best.

    Args:
        table: Every design of the sweep (``walking_payload_capacity``, ``fb``).
        front: The front's designs, best first (the same columns).
        yours: The user's design's metrics, marked beside them.

    """
    x, y = WALKING_PAYLOAD, FB
    fig = new_figure(5.6)
    ax = fig.add_subplot()
    walks = table["walks"].fillna(False).astype(bool) if "walks" in table else table[x] > 0
    ax.scatter(
        table.loc[walks, x],
        table.loc[walks, y],
        s=8,
        color="#bbbbbb",
        label="every design that walks",
    )
    if (~walks).any():
        ax.scatter(
            table.loc[~walks, x],
            table.loc[~walks, y],
            s=8,
            marker="x",
            color="#dddddd",
            label=f"{int((~walks).sum())} that cannot walk the gait unloaded (not ranked)",
        )
    for (r1, group), color in zip(front.groupby("l1_ratio", sort=True), COLORS, strict=False):
        ax.scatter(
            group[x], group[y], s=24, color=color, label=f"on the front, coxa ratio {r1:.2f}"
        )
    best = front.iloc[0]
    ax.scatter(
        [best[x]],
        [best[y]],
        s=220,
        marker="*",
        color="k",
        label=f"the front's best grid point: coxa {best['l1_ratio']:.2f}, tibia "
        f"{ratio_text(best['l3_ratio'])}\n(the recommendation refines it)",
    )
    if yours is not None:
        _mark_yours(ax, yours)
    name_largest(ax, table[x], table[y], design_names(table, x), by="x")
    ax.set_xlabel("walking payload capacity [kg] (default tripod gait, every rating)")
    ax.set_ylabel("body flexibility FB [-] (eq 29)")
    ax.set_title("Designs that walk and that no other beats in workspace, w_A and FB at once")
    ax.grid(True, which="both", alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize=7.5)
    return fig


def _mark_yours(ax: Axes, yours: Metrics) -> None:
    """The user's design on the Pareto figure: its walking payload capacity and FB."""
    x, y = yours.value(METRICS.walking_payload_capacity), yours.value(METRICS.fb)
    ax.scatter(
        [x],
        [y],
        s=90,
        marker="D",
        facecolor="none",
        edgecolor="#d62728",
        linewidth=2,
        label="your design",
    )
