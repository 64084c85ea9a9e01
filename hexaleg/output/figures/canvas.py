"""What every figure shares: the canvas, the palette, the paper's claims, and saving."""

from __future__ import annotations

import io
import os
from pathlib import Path
from typing import TYPE_CHECKING

from hexaleg._io import atomic_write_bytes
from hexaleg.paper import CLAIMED_L3_RATIO_PEAK

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

DPI = 150
"""Pixels per inch of the PNG files."""

COLORS = ("#1b6ca8", "#e07b00", "#2f9e44", "#c92a2a", "#7048e8", "#495057")
"""The palette, one colour per coxa ratio or series."""


def new_figure(width: float = 7.0, height: float = 5.0) -> Figure:
    """A figure of ``width`` × ``height`` [in] on the Agg canvas (no pyplot)."""
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), dpi=DPI, layout="constrained")


def shade_paper_claim(ax: Axes) -> None:
    """Shade the tibia-ratio band the paper claims is best (§5.4, §6.3)."""
    lo, hi = CLAIMED_L3_RATIO_PEAK
    ax.axvspan(lo, hi, color="k", alpha=0.08, label=f"paper's claim {lo:.2f}–{hi:.2f}")


def save(figure: Figure, path: str | os.PathLike[str], svg: bool = False) -> Path:
    """Render ``figure`` to PNG (and, if ``svg``, to SVG beside it), atomically.

    Returns the PNG's path.
    """
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=DPI)
    written = atomic_write_bytes(path, buffer.getvalue())
    if svg:
        vector = io.BytesIO()
        figure.savefig(vector, format="svg", metadata={"Date": None})
        atomic_write_bytes(Path(path).with_suffix(".svg"), vector.getvalue())
    return written


LIMIT_SET_TITLES = {
    "workspace_limits": "Table 2 limits",
    "improved_limits": "Table 4 limits",
    "manipulability_limits": "eq 26 limits",
    "stance_limits": "stance limits",
}
"""How a figure names each of the design's joint-limit sets."""
