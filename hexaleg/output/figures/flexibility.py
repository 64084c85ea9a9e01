"""Body-flexibility figures of one design (paper §6): the twelve extremes."""

from __future__ import annotations

import textwrap
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.output.figures.canvas import COLORS, drawn, new_figure
from hexaleg.stance.constraints import AXES
from hexaleg.stance.extremes import Extreme, FlexibilityResult

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


LABEL_WIDTH = 34
"""Characters per line of a bar's cause in the extremes figure (three bars share a row)."""

AXIS_WORDS = {
    "x": "along x (forward)",
    "y": "along y (left)",
    "z": "along z (up)",
    "roll": "roll (about x)",
    "pitch": "pitch (about y)",
    "yaw": "yaw (about z)",
}
"""How a figure names each body coordinate (body frame, REP 103)."""

MODE_WORDS = {
    "axis": "axis-locked: one coordinate moves, the other five held",
    "free": "free-coupled: the other five coordinates free to help",
}
"""How a figure names each flexibility mode."""


@drawn
def extremes_figure(result: FlexibilityResult) -> Figure:
    """The twelve body extremes of a :class:`~hexaleg.stance.extremes.FlexibilityResult`.

    Translations above, rotations below; each bar names what stops the body there.
    """
    fig = new_figure(7.6)
    translation_ax, rotation_ax = fig.subplots(2, 1)
    for ax, axes, scale, unit in (
        (translation_ax, AXES[:3], 1.0, "m"),
        (rotation_ax, AXES[3:], 180 / np.pi, "°"),
    ):
        for k, axis in enumerate(axes):
            for sign, color in ((1, COLORS[0]), (-1, COLORS[1])):
                _extreme_bar(ax, k, result.extreme(axis, sign), scale, color)
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xticks(range(3), [AXIS_WORDS.get(a, a) for a in axes])
        ax.set_ylabel(f"furthest from nominal [{unit}]")
        ax.margins(y=0.3)
        ax.grid(True, axis="y", alpha=0.3)
    translation_ax.set_title("Body translations (blue: + direction, orange: − direction)")
    rotation_ax.set_title("Body rotations")
    feet = "all six feet" if len(result.legs) == 6 else "feet " + ", ".join(result.legs)
    fig.suptitle(
        f"How far the body moves with {feet} planted, and what stops it; FB = {result.fb:.4f}"
        f"\n({MODE_WORDS.get(result.mode, result.mode)})"
    )
    return fig


def _extreme_bar(ax: Axes, k: int, extreme: Extreme, scale: float, color: str) -> None:
    value = extreme.value * scale
    ax.bar(k, value, color=color, width=0.6)
    ax.annotate(
        textwrap.fill(extreme.label, LABEL_WIDTH),
        (k, value),
        xytext=(0, 4 if extreme.sign > 0 else -4),
        textcoords="offset points",
        ha="center",
        va="bottom" if extreme.sign > 0 else "top",
        fontsize=7.5,
    )
