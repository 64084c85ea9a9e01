"""What a reviewer looks for on a study figure: your design, the recommended one, the ratings.

A :class:`Mark` is one design drawn over a study's curves, at its own tibia ratio and its
own values (a study row of that design: the same columns as the curves), so the reader
sees where the design under review sits; :func:`rating_line` draws a joint's rating on a
torque axis, and :func:`flat_top` thickens the stretch of a curve within 1 % of its peak,
where the choice of tibia ratio hardly matters.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from matplotlib.axes import Axes

FLAT_SHARE = 0.01
"""A curve's flat top: where it stays within this share of its peak [-]."""

FLAT_LABEL = "within 1 % of its peak"
"""The legend of a curve's flat top."""


@dataclass(frozen=True)
class Mark:
    """One design marked on a study's figures.

    Attributes:
        label: What the legend calls it: ``"your design"``, ``"recommended"``.
        values: Its study row: ``l3_ratio`` and the columns the figures plot [their units].
        marker: Matplotlib marker.
        color: Its colour.

    """

    label: str
    values: Mapping[str, Any]
    marker: str = "D"
    color: str = "#d62728"

    def draw(self, ax: Axes, x: str, y: str, scale: float = 1.0, labelled: bool = True) -> None:
        """The mark at (row[x], scale·row[y]) if the row has both, finite.

        ``labelled`` False leaves it out of the legend (a mark drawn on several curves of
        one axes is named once).
        """
        if x not in self.values or y not in self.values:
            return
        px, py = float(self.values[x]), float(self.values[y]) * scale
        if not (math.isfinite(px) and math.isfinite(py)):
            return
        filled = self.marker == "*"
        ax.scatter(
            [px], [py], s=150 if filled else 70, marker=self.marker, zorder=5,
            facecolor=self.color if filled else "none", edgecolor=self.color, linewidth=1.8,
            label=self.label if labelled else "_nolegend_",
        )  # fmt: skip


def your_and_recommended(yours: Mapping[str, Any], recommended: Mapping[str, Any]) -> list[Mark]:
    """The two marks every study figure carries: your design and the recommended one."""
    return [
        Mark("your design", yours),
        Mark("recommended (at its own posture)", recommended, marker="*", color="k"),
    ]


def draw_marks(
    ax: Axes, marks: Sequence[Mark], x: str, y: str, scale: float = 1.0, labelled: bool = True
) -> None:
    """Each mark on ``ax`` at its ``x`` and ``y`` columns (in the legend if ``labelled``)."""
    for mark in marks:
        mark.draw(ax, x, y, scale, labelled)


def rating_line(ax: Axes, rated: float, what: str) -> None:
    """A dashed horizontal line at the rating ``rated`` of ``what`` (``"hip"``), labelled.

    Draw it after the curves: where the line runs near the top of the axes, the axes grow
    so that its label stays inside them.
    """
    ax.axhline(rated, color="k", ls="--", lw=1.1, label="rating")
    low, high = ax.get_ylim()
    if rated > high - 0.1 * (high - low):
        ax.set_ylim(low, rated + 0.12 * (max(high, rated) - low))
    ax.annotate(f"{what} rating {rated:g}", (1.0, rated), xycoords=("axes fraction", "data"),
                xytext=(-4, 3), textcoords="offset points", ha="right", va="bottom",
                fontsize=7.5)  # fmt: skip


def flat_top(
    ax: Axes, x: npt.ArrayLike, y: npt.ArrayLike, color: str, label: str | None = None
) -> None:
    """Thicken the stretch of the curve (x, y) within :data:`FLAT_SHARE` of its peak."""
    xs, ys = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if not np.isfinite(ys).any():
        return
    near = ys >= (1 - FLAT_SHARE) * np.nanmax(ys)
    ax.plot(np.where(near, xs, np.nan), np.where(near, ys, np.nan), color=color, lw=7,
            alpha=0.25, solid_capstyle="butt")  # fmt: skip
    if label is not None:  # one grey entry for every curve's flat top
        ax.plot([], [], color="0.5", lw=7, alpha=0.3, label=label)
