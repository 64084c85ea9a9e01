"""What every figure shares: page size, type sizes, palette, the paper's claims, saving.

Figures are drawn for the page they are shown on: at most :data:`FULL_WIDTH` inches wide
at :data:`DPI`, so the report shows each PNG at its natural pixel size on a 1400 px screen
and the PDF prints each SVG at the size it was drawn, its text at the sizes of
:data:`STYLE` (none below 7.5 pt). Panels that do not fit side by side in that width go
one under another.
"""

from __future__ import annotations

import functools
import io
import json
import os
import zlib
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, ParamSpec

import numpy as np
import numpy.typing as npt

from hexaleg._io import write_bytes
from hexaleg.output.figures.labels import CORNERS, clear_label
from hexaleg.paper import CLAIMED_L3_RATIO_PEAK, CLAIMED_W_A_PEAK

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.text import Text

P = ParamSpec("P")

DPI = 150
"""Pixels per inch of the PNG files."""

FULL_WIDTH = 7.2
"""Width of a full-width figure [in]: 1080 px at :data:`DPI`, 183 mm on an A4 page."""

STYLE: dict[Any, Any] = {
    "font.size": 9.0,
    "axes.titlesize": 10.0,
    "axes.labelsize": 9.0,
    "xtick.labelsize": 8.0,
    "ytick.labelsize": 8.0,
    "legend.fontsize": 8.0,
    "figure.titlesize": 10.5,
    "svg.fonttype": "path",
}
"""Type sizes [pt] of every figure; the smallest text is 7.5 pt (bar annotations)."""

SMALLEST_TEXT_KEY = "hexaleg:smallest-text-px"
TEXTS_KEY = "hexaleg:texts"
"""PNG text key holding every visible text of the figure (titles, labels, legend, annotations),
as a JSON list: what a reader sees, for checks that the figures agree with the report."""
"""PNG text chunk giving the height of the figure's smallest text [px at natural size]."""

COLORS = ("#1b6ca8", "#e07b00", "#2f9e44", "#c92a2a", "#7048e8", "#495057")
"""The palette, one colour per coxa ratio or series."""

LIMIT_SET_TITLES = {
    "workspace_limits": "Table 2 limits",
    "improved_limits": "Table 4 limits",
    "manipulability_limits": "eq 26 limits",
    "stance_limits": "stance limits",
}
"""How a figure names each of the design's joint-limit sets."""


def drawn(draw: Callable[P, Figure]) -> Callable[P, Figure]:
    """Draw the decorated figure with the type sizes of :data:`STYLE`."""

    @functools.wraps(draw)
    def styled(*args: P.args, **kwargs: P.kwargs) -> Figure:
        import matplotlib

        with matplotlib.rc_context(STYLE):
            return draw(*args, **kwargs)

    return styled


def new_figure(height: float, width: float = FULL_WIDTH) -> Figure:
    """A figure of ``width`` × ``height`` [in] on the Agg canvas (no pyplot)."""
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), dpi=DPI, layout="constrained")


def shade_paper_band(ax: Axes, what: str) -> None:
    """Shade the tibia ratios 0.40–0.45 the paper names for ``what`` (§4.3, §6.3)."""
    lo, hi = CLAIMED_L3_RATIO_PEAK
    ax.axvspan(lo, hi, color="k", alpha=0.08, label=f"paper: {what} at {lo:.2f}–{hi:.2f}")


def mark_paper_w_a_peak(ax: Axes) -> None:
    """Mark the tibia ratio ≈ 0.45 where the paper says w_A peaks (§5.4)."""
    ax.axvline(
        CLAIMED_W_A_PEAK,
        color="k",
        ls="--",
        lw=1.2,
        label=f"paper (§5.4): peak at ≈ {CLAIMED_W_A_PEAK}",
    )


def log_scale(ax: Axes, which: str) -> None:
    """A logarithmic ``"x"`` or ``"y"`` axis ticked 1, 2, 5 per decade in plain numbers."""
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    axis = ax.xaxis if which == "x" else ax.yaxis
    (ax.set_xscale if which == "x" else ax.set_yscale)("log")
    axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    formatter = ScalarFormatter()
    formatter.set_scientific(False)
    axis.set_major_formatter(formatter)
    axis.set_minor_formatter(NullFormatter())


NARROW_SPREAD = 0.25
"""Values spreading less than this share of their largest look flat on an axis from zero [-]."""


def magnitude_axis(ax: Axes, values: npt.ArrayLike, what: str = "") -> None:
    """Read a magnitude (a torque, a cost, a payload: ≥ 0) on ``ax``'s y axis against zero.

    The rule for every such axis: it starts at 0 and ends a little above the largest value,
    so a curve's height is its share of the largest and a 10 % spread looks like 10 %, not
    like the whole axis; matplotlib's offset notation (``+8.8e-2`` above the axis, the ticks
    read as differences) is off. Where the finite ``values`` spread less than
    :data:`NARROW_SPREAD` of their largest, the curves look nearly flat from zero, so the
    panel states their range in numbers (after ``what``, if given), in a corner where
    the note hides no data.
    """
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    high = float(finite.max()) if finite.size else 0.0
    top = max(ax.get_ylim()[1], 1.06 * high)
    ax.set_ylim(0.0, top if top > 0 else 1.0)
    ax.ticklabel_format(axis="y", style="plain", useOffset=False)
    if high > 0 and high - float(finite.min()) < NARROW_SPREAD * high:
        low = float(finite.min())
        clear_label(
            ax,
            f"{what} {low:.3g} to {high:.3g}: all within {100 * (high - low) / high:.0f} %".strip(),
            (0.0, 0.0),
            CORNERS,
            xycoords="axes fraction",
            fontsize=8,
        )


def name_largest(
    ax: Axes, x: Sequence[float], y: Sequence[float], labels: Sequence[str], by: str = "y"
) -> None:
    """Name the point of largest ``by`` (``"x"`` or ``"y"``) beside it, where it hides no data.

    The outlier that stretches an axis over decades, named so the reader knows what it is;
    the name goes at its left if that hides nothing, else at the nearest clear spot
    (:func:`~hexaleg.output.figures.labels.clear_label`).
    """
    xs, ys = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    k = int(np.nanargmax(xs if by == "x" else ys))
    clear_label(ax, labels[k], (float(xs[k]), float(ys[k])), fontsize=8)


def _visible_texts(figure: Figure) -> list[Text]:
    from matplotlib.text import Text

    return [
        text
        for text in figure.findobj(Text)
        if isinstance(text, Text) and text.get_visible() and text.get_text().strip()
    ]


def smallest_text_px(figure: Figure) -> float:
    """Height of the smallest visible text of ``figure`` [px at :data:`DPI`]."""
    return float(min(text.get_fontsize() for text in _visible_texts(figure))) * DPI / 72.0


def save(figure: Figure, path: str | os.PathLike[str], svg: bool = False) -> Path:
    """Render ``figure`` to PNG (and, if ``svg``, to SVG beside it), atomically.

    The PNG records its smallest text height under :data:`SMALLEST_TEXT_KEY` and its texts
    under :data:`TEXTS_KEY`. Returns the PNG's path.
    """
    import matplotlib

    with matplotlib.rc_context(STYLE):  # ticks made while drawing take the same sizes
        buffer = io.BytesIO()
        figure.savefig(buffer, format="png", dpi=DPI)  # lays out, so every text exists
        smallest = f"{smallest_text_px(figure):.2f}"
        texts = json.dumps([text.get_text() for text in _visible_texts(figure)])  # ASCII
        png = _with_text(buffer.getvalue(), SMALLEST_TEXT_KEY, smallest)
        written = write_bytes(path, _with_text(png, TEXTS_KEY, texts))
        if svg:
            vector = io.BytesIO()
            figure.savefig(vector, format="svg", metadata={"Date": None})
            write_bytes(Path(path).with_suffix(".svg"), vector.getvalue())
    return written


def _with_text(png: bytes, key: str, value: str) -> bytes:
    """``png`` with a ``tEXt`` chunk ``key`` = ``value`` after its header chunk."""
    header_end = 8 + 4 + 4 + 13 + 4  # signature, then IHDR: length, type, 13 bytes, CRC
    body = b"tEXt" + key.encode("latin-1") + b"\0" + value.encode("latin-1")
    chunk = (len(body) - 4).to_bytes(4, "big") + body + zlib.crc32(body).to_bytes(4, "big")
    return png[:header_end] + chunk + png[header_end:]
