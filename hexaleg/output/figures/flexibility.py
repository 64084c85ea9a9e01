"""Body-flexibility figures of one design (paper §6): the twelve extremes."""

from __future__ import annotations

import textwrap
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.output.figures.canvas import COLORS, new_figure
from hexaleg.stance.constraints import AXES
from hexaleg.stance.extremes import FlexibilityResult

if TYPE_CHECKING:
    from matplotlib.figure import Figure


LABEL_WIDTH = 26
"""Characters per line of a bar's cause in the extremes figure (three bars share an axis)."""


def extremes_figure(result: FlexibilityResult) -> Figure:
    """The twelve body extremes of a :class:`~hexaleg.flexibility.FlexibilityResult`."""
    fig = new_figure(11, 4.8)
    translation_ax, rotation_ax = fig.subplots(1, 2)
    for ax, axes, scale, unit in (
        (translation_ax, AXES[:3], 1.0, "m"),
        (rotation_ax, AXES[3:], 180 / np.pi, "°"),
    ):
        for k, axis in enumerate(axes):
            for sign, color in ((1, COLORS[0]), (-1, COLORS[1])):
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
