"""Labels that cover no data: each put, when its figure is drawn, where it hides nothing.

A label added by :func:`clear_label` carries a list of candidate spots (an anchor and an
offset from it). When the figure is drawn, after the layout has placed every axes, the
label takes the first spot where its box, padded by :data:`PAD_PX`, holds no point of a
curve or a scatter, no bar and no other text of its axes, and lies inside the axes; if
every spot hides something, the one hiding the fewest points. A label away from its
anchor is tied to it by a thin leader line. The label takes no part in the layout, so
placing it moves nothing else.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Literal, cast

import numpy as np

from hexaleg._typing import ArrayF

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.backend_bases import RendererBase
    from matplotlib.text import Annotation
    from matplotlib.transforms import Bbox

HAlign = Literal["left", "center", "right"]
VAlign = Literal["bottom", "center", "top"]
Spot = tuple[tuple[float, float], tuple[float, float], HAlign, VAlign]
"""A candidate spot: the anchor (in the label's ``xycoords``), the text's offset from it
[pt], and the text's horizontal and vertical alignment."""

PAD_PX = 2.0
"""Clearance kept around a label's box [px]."""

STEP_PX = 2.0
"""A curve is checked every this many pixels along its length [px]."""

LEADER = {"arrowstyle": "-", "lw": 0.6, "color": "0.3"}
"""The leader line from a label moved away from its point to the point."""

LEADER_PT = 8.0
"""A label further than this from its point [pt] gets a leader line."""

FAINT = 0.3
"""Shading fainter than this opacity (a band, a flat top) is background, not data [-]."""

_SIDES: tuple[tuple[int, int, HAlign, VAlign], ...] = (
    (-1, 0, "right", "center"),
    (-1, 1, "right", "bottom"),
    (-1, -1, "right", "top"),
    (0, 1, "center", "bottom"),
    (0, -1, "center", "top"),
    (1, 0, "left", "center"),
    (1, 1, "left", "bottom"),
    (1, -1, "left", "top"),
)


_RELPOS = {"left": 0.0, "right": 1.0, "bottom": 0.0, "top": 1.0, "center": 0.5}
"""Where along the text's box the leader line leaves it, for each alignment."""


def around(distances: Sequence[float] = (6, 16, 32, 56, 88)) -> list[Spot]:
    """Spots around an anchor at each distance [pt]: left first, then above, below, right."""
    return [((0.0, 0.0), (dx * d, dy * d), ha, va) for d in distances for dx, dy, ha, va in _SIDES]


CORNERS: list[Spot] = [
    ((0.01, 0.03), (0.0, 0.0), "left", "bottom"),
    ((0.99, 0.03), (0.0, 0.0), "right", "bottom"),
    ((0.01, 0.97), (0.0, 0.0), "left", "top"),
    ((0.99, 0.97), (0.0, 0.0), "right", "top"),
    ((0.01, 0.5), (0.0, 0.0), "left", "center"),
    ((0.99, 0.5), (0.0, 0.0), "right", "center"),
    ((0.5, 0.03), (0.0, 0.0), "center", "bottom"),
    ((0.5, 0.97), (0.0, 0.0), "center", "top"),
]
"""Spots for a note anchored in ``axes fraction``: the corners, then the sides' middles."""


def clear_label(
    ax: Axes,
    text: str,
    xy: tuple[float, float],
    spots: Sequence[Spot] | None = None,
    xycoords: str = "data",
    **style: Any,
) -> Annotation:
    """Add ``text`` for the point ``xy`` to ``ax``, at the first spot that hides nothing.

    Args:
        ax: The axes.
        text: The label.
        xy: The point labelled (``spots`` anchor at it) in ``xycoords``; for ``"axes
            fraction"`` notes each spot's own anchor is used instead.
        spots: Candidate spots; by default :func:`around` the point.
        xycoords: The coordinates of ``xy`` and of the spots' anchors.
        style: Text properties (``fontsize``, ``bbox``, ...).

    """
    candidates = list(spots) if spots is not None else around()
    if xycoords == "data":  # anchored at the point itself
        candidates = [(xy, offset, ha, va) for _, offset, ha, va in candidates]
    label = _label_class()(text, candidates, xycoords=xycoords, **style)
    ax.add_artist(label)
    return label


@functools.cache
def _label_class() -> type:
    """The label's class, built on first use (matplotlib is imported lazily)."""
    from matplotlib.text import Annotation, Text
    from scipy.spatial import cKDTree

    class ClearLabel(Annotation):
        """An annotation that picks its spot among candidates when drawn."""

        def __init__(self, text: str, spots: list[Spot], **kwargs: Any) -> None:
            anchor, offset, ha, va = spots[0]
            super().__init__(text, anchor, xytext=offset, textcoords="offset points",
                             ha=ha, va=va, arrowprops=LEADER, **kwargs)  # fmt: skip
            self.spots = spots
            self.set_in_layout(False)

        def draw(self, renderer: RendererBase) -> None:
            if self.axes is not None and self.get_visible():
                self._choose(renderer)
            super().draw(renderer)

        def _choose(self, renderer: RendererBase) -> None:
            ax = cast("Axes", self.axes)
            assert self.arrow_patch is not None
            at = (ax.transData if self.xycoords == "data" else ax.transAxes).transform
            points, boxes = _obstacles(ax, renderer, self)
            tree = cKDTree(points) if len(points) else None
            frame = ax.get_window_extent(renderer)
            best: tuple[float, int] | None = None
            for k, spot in enumerate(self.spots):
                self._put(spot)
                self.update_positions(renderer)
                box = Text.get_window_extent(self, renderer)  # the text's box, no leader
                hidden = _hidden(box, points, boxes, frame)
                if tree is not None and _leads(spot):
                    start = box.p0 + box.size * np.array(self._arrow_relpos)
                    hidden += _under_leader(tree, start, at(self.xy))
                if best is None or hidden < best[0]:
                    best = (hidden, k)
                if hidden == 0:
                    break
            assert best is not None
            self._put(self.spots[best[1]])
            self.arrow_patch.set_visible(_leads(self.spots[best[1]]))

        def _put(self, spot: Spot) -> None:
            anchor, offset, ha, va = spot
            self.xy = anchor
            self.set_position(offset)
            self.set_horizontalalignment(ha)
            self.set_verticalalignment(va)
            self._arrow_relpos = (_RELPOS[ha], _RELPOS[va])  # the corner nearest its point

    return ClearLabel


def _leads(spot: Spot) -> bool:
    """Whether a label at ``spot`` is far enough from its point to need a leader line."""
    return float(np.hypot(*spot[1])) > LEADER_PT


def _under_leader(tree: Any, start: ArrayF, end: ArrayF) -> float:
    """How many obstacle points lie on the leader from ``start`` to ``end`` (display px).

    The stretch within :data:`LEADER_PT` px of its point is left out: that is the point
    labelled.
    """
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    length = float(np.hypot(*(end - start)))
    if length <= LEADER_PT:
        return 0.0
    t = np.linspace(0.0, 1.0 - LEADER_PT / length, max(int(length // STEP_PX), 2))
    near = tree.query_ball_point(start + t[:, None] * (end - start), r=PAD_PX)
    return float(len(set().union(*near)))


def _obstacles(ax: Axes, renderer: RendererBase, label: object) -> tuple[ArrayF, list[Bbox]]:
    """What a label must not hide on ``ax``, in display pixels: points, and boxes."""
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.patches import Rectangle

    points: list[ArrayF] = []
    for line in ax.get_lines():
        if line.get_visible() and _opaque(line.get_alpha()):
            points.append(_along(line.get_transform().transform(line.get_xydata())))
    for collection in ax.collections:
        if not collection.get_visible():
            continue
        if isinstance(collection, PathCollection):
            centres = collection.get_offset_transform().transform(collection.get_offsets())
            sizes = np.resize(np.asarray(collection.get_sizes(), dtype=float), len(centres))
            radius = np.sqrt(sizes) / 2 * np.asarray(renderer.points_to_pixels(1.0), dtype=float)
            points.append(_disks(centres, radius))
        elif isinstance(collection, LineCollection):
            transform = collection.get_transform()
            for segment in collection.get_segments():
                points.append(_along(transform.transform(segment)))
    boxes = [
        patch.get_window_extent(renderer)
        for patch in ax.patches
        if isinstance(patch, Rectangle) and patch.get_visible() and _opaque(patch.get_alpha())
    ]
    boxes += [
        text.get_window_extent(renderer)
        for text in ax.texts
        if text is not label and text.get_visible() and text.get_text().strip()
    ]
    legend = ax.get_legend()
    if legend is not None and legend.get_visible():
        boxes.append(legend.get_window_extent(renderer))
    finite = [p[np.isfinite(p).all(axis=1)] for p in points if len(p)]
    return (np.vstack(finite) if finite else np.empty((0, 2))), boxes


def _opaque(alpha: float | None) -> bool:
    return alpha is None or alpha >= FAINT


def _along(xy: ArrayF) -> ArrayF:
    """Points every :data:`STEP_PX` along a polyline (display px); NaN breaks it."""
    xy = np.asarray(xy, dtype=float)
    if len(xy) < 2:
        return xy
    pieces = [xy]
    for a, b in itertools.pairwise(xy):
        if not (np.isfinite(a).all() and np.isfinite(b).all()):
            continue
        n = int(np.hypot(*(b - a)) // STEP_PX)
        if n > 1:
            t = np.linspace(0.0, 1.0, n + 1)[1:-1, None]
            pieces.append(a + t * (b - a))
    return np.vstack(pieces)


def _disks(centres: ArrayF, radius: ArrayF) -> ArrayF:
    """Each marker as its centre and eight points on its rim (display px)."""
    angles = np.linspace(0.0, 2 * np.pi, 8, endpoint=False)
    rim = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    ring = centres[:, None, :] + radius[:, None, None] * rim[None, :, :]
    return np.vstack([centres, ring.reshape(-1, 2)])


def _hidden(box: Bbox, points: ArrayF, boxes: Sequence[Bbox], frame: Bbox) -> float:
    """How much a label's box hides: points under it, boxes it overlaps, leaving the axes."""
    x0, y0, x1, y1 = box.x0 - PAD_PX, box.y0 - PAD_PX, box.x1 + PAD_PX, box.y1 + PAD_PX
    inside = (points[:, 0] >= x0) & (points[:, 0] <= x1) & (points[:, 1] >= y0)
    count = float(np.count_nonzero(inside & (points[:, 1] <= y1)))
    count += sum(10.0 for b in boxes if b.x0 < x1 and x0 < b.x1 and b.y0 < y1 and y0 < b.y1)
    outside = box.x0 < frame.x0 or box.x1 > frame.x1 or box.y0 < frame.y0 or box.y1 > frame.y1
    return count + (1e6 if outside else 0.0)
