"""The torque colour scale, and its legend beside the 3-D scene in the page.

Leg links are coloured by their joint's |τ| / rated torque (:func:`torque_colour`).
The legend is HTML beside the meshcat canvas (:func:`with_legend`), not geometry in the
scene, so it never hides the robot and keeps its size whatever the camera does; the
static page and the served one carry the same column. What the colours mean depends on
the scene: :data:`STATICS_LEGEND` for the body's extremes, :data:`GAIT_LEGEND` for a gait.
"""

from __future__ import annotations

import functools
import html
from dataclasses import dataclass
from typing import Any

import numpy as np

LEGEND_WIDTH = "13rem"
"""Width of the legend's column at the left of the page; the scene takes the rest."""

STOPS = 11
"""Colours sampled along the legend's bar."""

HIGHLIGHT = (0.9, 0.1, 0.1, 1.0)
"""RGBA of the links whose joint stops an extreme (never a torque colour)."""


def torque_colour(ratio: float) -> tuple[float, float, float, float]:
    """The colour of a link whose joint works at ``ratio`` = |τ| / rated.

    Viridis, from dark blue (idle) to yellow (at its rating): never the highlight red.
    """
    red, green, blue, alpha = _viridis()(float(np.clip(ratio, 0.0, 1.0)))
    return (red, green, blue, alpha)


@functools.cache
def _viridis() -> Any:
    """Matplotlib's viridis, built once.

    Each look-up copies it, and a copy builds its table on first use: an animation asks
    for a colour per link and frame.
    """
    from matplotlib import colormaps

    return colormaps["viridis"]


def _css(colour: tuple[float, ...]) -> str:
    red, green, blue = (round(255 * c) for c in colour[:3])
    return f"rgb({red},{green},{blue})"


@dataclass(frozen=True)
class Legend:
    """What the colours of one scene mean.

    Attributes:
        shows: What a leg link's colour shows (the bar runs from 0 to 1 of it).
        highlight: What a red link means, or ``None`` where no link is red.
        notes: What the scene's other marks are, one line each.

    """

    shows: str
    highlight: str | None = None
    notes: tuple[str, ...] = ()


STATICS_LEGEND = Legend(
    shows="its joint's |τ| / rated torque, at the pose shown",
    highlight="the link whose joint stops an extreme",
    notes=(
        "black balls: the nominal footholds",
        "grey points (--workspace): one leg's reach, lighter higher up",
    ),
)
"""The body's extremes (``hexaleg view``): torques held at each pose, red where it stops."""

GAIT_LEGEND = Legend(
    shows="its joint's |τ| / rated torque at each instant of the gait period "
    "(yellow: at or over its rating)",
)
"""A gait period (``hexaleg view --gait``, ``hexaleg gait --html``): no link is red."""


def torque_legend_html(legend: Legend) -> str:
    """The legend: a vertical colour bar of |τ| / rated from 0 to 1, and what red means."""
    stops = ", ".join(
        f"{_css(torque_colour(ratio))} {100 * k / (STOPS - 1):.0f}%"
        for k, ratio in enumerate(np.linspace(1, 0, STOPS))
    )
    ticks = "".join(
        f"<span style='top:{100 * (1 - v):.0f}%'>{v:g}</span>" for v in (0, 0.25, 0.5, 0.75, 1)
    )
    red = (
        ""
        if legend.highlight is None
        else f"<p><span class='swatch'></span> red: {html.escape(legend.highlight)}</p>"
    )
    return (
        "<aside id='hexaleg-legend'><h2>Leg link colour</h2>"
        f"<p>{html.escape(legend.shows)}</p>"
        f"<div class='bar' style='background:linear-gradient(to bottom, {stops})'></div>"
        f"<div class='ticks'>{ticks}</div>{red}"
        + "".join(f"<p>{html.escape(note)}</p>" for note in legend.notes)
        + "</aside>"
    )


LEGEND_STYLE = f"""
#hexaleg-legend {{position: fixed; left: 0; top: 0; bottom: 0; width: {LEGEND_WIDTH};
  box-sizing: border-box; padding: 1rem; font: 14px/1.35 sans-serif; color: #222;
  background: #f4f4f4; border-right: 1px solid #ccc; overflow: auto}}
#hexaleg-legend h2 {{font-size: 16px; margin: 0 0 .4rem}}
#hexaleg-legend .bar {{display: inline-block; width: 1.6rem; height: 14rem;
  border: 1px solid #555; vertical-align: top}}
#hexaleg-legend .ticks {{display: inline-block; position: relative; height: 14rem;
  width: 3rem; margin-left: .3rem}}
#hexaleg-legend .ticks span {{position: absolute; transform: translateY(-50%)}}
#hexaleg-legend .swatch {{display: inline-block; width: .9rem; height: .9rem;
  background: {_css(HIGHLIGHT)}; vertical-align: middle}}
#meshcat-pane {{margin-left: {LEGEND_WIDTH}; width: calc(100vw - {LEGEND_WIDTH}) !important}}
"""
"""The legend's column, and the scene moved to its right."""


def with_legend(page: str, legend: Legend) -> str:
    """A meshcat page (static or served) with ``legend`` in a column beside the scene."""
    closing = page.rindex("</body>")
    column = f"<style>{LEGEND_STYLE}</style>{torque_legend_html(legend)}\n"
    return page[:closing] + column + page[closing:]
