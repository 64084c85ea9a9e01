"""Labels that cover no data: each put, when its figure is drawn, where it hides nothing.

A label added by :func:`clear_label` carries a list of candidate spots (an anchor and an
offset from it), nearest first. When the figure is drawn, after the layout has placed
every axes, the label takes the first spot where its box, padded by :data:`PAD_PT`, lies
inside the axes and holds no point of a curve or a scatter marker, no bar, no legend and
no other text of its axes, and where its leader line (drawn back to a point it has moved
away from) crosses no marker or curve either; if every spot hides something, the one hiding
the fewest points. The label takes no part in the layout, so placing it moves nothing else.
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

PAD_PT = 2.0
"""Clearance kept around a label's box and along its leader line [pt]: in points, so the
PNG (150 dpi) and the SVG (72 dpi) of a figure put the label at the same spot."""

STEP_PT = 1.0
"""Curves and leader lines are checked every this many points along their length [pt]."""

LEADER = {"arrowstyle": "-", "lw": 0.6, "color": "0.3"}
"""The leader line from a label moved away from its point to the point."""

LEADER_PT = 8.0
"""A label further than this from its point [pt] gets a leader line."""

FAINT = 0.3
"""Shading and lines fainter than this opacity (a band, a flat top) are background [-]."""

_SHARE = {"left": 0.0, "right": 1.0, "bottom": 0.0, "top": 1.0, "center": 0.5}
"""Where the anchor sits along the text's box, for each alignment; the leader line leaves
the box there too (the box's side or corner nearest its point)."""


def _alignment(dx: float, dy: float) -> tuple[HAlign, VAlign]:
    """The text's alignment for an offset (dx, dy): the text lies away from its point."""
    ha: HAlign = "right" if dx < 0 else "left" if dx > 0 else "center"
    va: VAlign = "top" if dy < 0 else "bottom" if dy > 0 else "center"
    return ha, va


def around(reach_pt: float = 320.0, step_pt: float = 8.0) -> list[Spot]:
    """Offsets around a point, nearest first: beside it, then ever further, up to a reach.

    The first spots are the eight sides at 6 pt (left first, as a reader expects a name
    beside its point); then a lattice of offsets every ``step_pt`` out to ``reach_pt``
    [pt] either way, sorted by distance (ties: left before right, above before below).
    """
    near = [(-6.0, 0.0), (-6.0, 6.0), (-6.0, -6.0), (0.0, 6.0), (0.0, -6.0), (6.0, 0.0),
            (6.0, 6.0), (6.0, -6.0)]  # fmt: skip
    steps = np.arange(-reach_pt, reach_pt + step_pt / 2, step_pt)
    lattice = sorted(
        ((float(dx), float(dy)) for dx in steps for dy in steps if np.hypot(dx, dy) > 8.5),
        key=lambda o: (round(float(np.hypot(*o)), 6), o[0] > 0, o[1] < 0),
    )
    return [((0.0, 0.0), offset, *_alignment(*offset)) for offset in near + lattice]


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
        spots: Candidate spots, nearest first; by default :func:`around` the point.
        xycoords: ``"data"`` or ``"axes fraction"``: the coordinates of ``xy`` and of the
            spots' anchors.
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
            self._put(self.spots[0])
            self.update_positions(renderer)
            size = np.asarray(Text.get_window_extent(self, renderer).size, dtype=float)
            at = (ax.transData if self.xycoords == "data" else ax.transAxes).transform
            anchors = at(np.array([spot[0] for spot in self.spots], dtype=float))
            px_per_pt = float(np.asarray(renderer.points_to_pixels(1.0), dtype=float))
            points, others = _obstacles(ax, renderer, self, px_per_pt)
            boxes = _boxes(self.spots, anchors, size, px_per_pt)  # the words' boxes
            frame = ax.get_window_extent(renderer)
            hidden = _hidden(boxes, points, others, frame, PAD_PT * px_per_pt)
            tree = cKDTree(points) if len(points) else None
            best = int(np.argmin(hidden))  # the nearest of the least hidden, unless ...
            for k in np.flatnonzero(hidden == hidden.min()):
                spot = self.spots[k]
                if tree is None or not _leads(spot):
                    best = int(k)
                    break
                share = np.array([_SHARE[spot[2]], _SHARE[spot[3]]])
                start = boxes[k, :2] + share * (boxes[k, 2:] - boxes[k, :2])
                if _under_leader(tree, start, anchors[k], px_per_pt) == 0:  # ... a clear leader
                    best = int(k)
                    break
            self._put(self.spots[best])
            self.arrow_patch.set_visible(_leads(self.spots[best]))

        def _put(self, spot: Spot) -> None:
            anchor, offset, ha, va = spot
            self.xy = anchor
            self.set_position(offset)
            self.set_horizontalalignment(ha)
            self.set_verticalalignment(va)
            self._arrow_relpos = (_SHARE[ha], _SHARE[va])

    return ClearLabel


def _leads(spot: Spot) -> bool:
    """Whether a label at ``spot`` is far enough from its point to need a leader line."""
    return float(np.hypot(*spot[1])) > LEADER_PT


def _boxes(spots: Sequence[Spot], anchors: ArrayF, size: ArrayF, px_per_pt: float) -> ArrayF:
    """The text's box (x0, y0, x1, y1) [display px] at each spot, (N, 4)."""
    offsets = np.array([spot[1] for spot in spots], dtype=float) * px_per_pt
    share = np.array([(_SHARE[spot[2]], _SHARE[spot[3]]) for spot in spots])
    low = anchors + offsets - share * np.asarray(size, dtype=float)
    return np.hstack([low, low + np.asarray(size, dtype=float)])


def _under_leader(tree: Any, start: ArrayF, end: ArrayF, px_per_pt: float) -> int:
    """How many obstacle points lie on the leader from ``start`` to ``end`` [display px].

    The stretch within :data:`LEADER_PT` of its point is left out: that is the point
    labelled.
    """
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    length, spared = float(np.hypot(*(end - start))), LEADER_PT * px_per_pt
    if length <= spared:
        return 0
    samples = max(int(length // (STEP_PT * px_per_pt)), 2)
    t = np.linspace(0.0, 1.0 - spared / length, samples)
    near = tree.query_ball_point(start + t[:, None] * (end - start), r=PAD_PT * px_per_pt)
    return len(set().union(*near))


def _obstacles(
    ax: Axes, renderer: RendererBase, label: object, px_per_pt: float
) -> tuple[ArrayF, list[Bbox]]:
    """What a label must not hide on ``ax``, in display pixels: points, and boxes."""
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.patches import Rectangle

    points: list[ArrayF] = []
    for line in ax.get_lines():
        if line.get_visible() and _opaque(line.get_alpha()):
            xy = line.get_transform().transform(line.get_xydata())
            points.append(_along(xy, STEP_PT * px_per_pt))
    for collection in ax.collections:
        if not collection.get_visible():
            continue
        if isinstance(collection, PathCollection):
            centres = collection.get_offset_transform().transform(collection.get_offsets())
            sizes = np.resize(np.asarray(collection.get_sizes(), dtype=float), len(centres))
            points.append(_disks(centres, np.sqrt(sizes) / 2 * px_per_pt))
        elif isinstance(collection, LineCollection):
            transform = collection.get_transform()
            for segment in collection.get_segments():
                points.append(_along(transform.transform(segment), STEP_PT * px_per_pt))
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


def _along(xy: ArrayF, step: float) -> ArrayF:
    """Points every ``step`` along a polyline [display px]; NaN breaks it."""
    xy = np.asarray(xy, dtype=float)
    if len(xy) < 2:
        return xy
    pieces = [xy]
    for a, b in itertools.pairwise(xy):
        if not (np.isfinite(a).all() and np.isfinite(b).all()):
            continue
        n = int(np.hypot(*(b - a)) // step)
        if n > 1:
            t = np.linspace(0.0, 1.0, n + 1)[1:-1, None]
            pieces.append(a + t * (b - a))
    return np.vstack(pieces)


def _disks(centres: ArrayF, radius: ArrayF) -> ArrayF:
    """Each marker as its centre and eight points on its rim [display px]."""
    angles = np.linspace(0.0, 2 * np.pi, 8, endpoint=False)
    rim = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    ring = centres[:, None, :] + radius[:, None, None] * rim[None, :, :]
    return np.vstack([centres, ring.reshape(-1, 2)])


def _hidden(
    boxes: ArrayF, points: ArrayF, others: Sequence[Bbox], frame: Bbox, pad: float
) -> ArrayF:
    """How much each candidate box (N, 4) [display px], padded by ``pad``, hides.

    The obstacle points under it, 10 for each box it overlaps, 1e6 if it leaves the frame.
    """
    x0, y0 = boxes[:, 0] - pad, boxes[:, 1] - pad
    x1, y1 = boxes[:, 2] + pad, boxes[:, 3] + pad
    hidden = np.zeros(len(boxes))
    for chunk in np.array_split(np.arange(len(boxes)), max(1, len(boxes) // 256)):
        px, py = points[None, :, 0], points[None, :, 1]
        inside = (px >= x0[chunk, None]) & (px <= x1[chunk, None])
        inside &= (py >= y0[chunk, None]) & (py <= y1[chunk, None])
        hidden[chunk] = inside.sum(axis=1)
    for b in others:
        hidden += 10.0 * ((b.x0 < x1) & (x0 < b.x1) & (b.y0 < y1) & (y0 < b.y1))
    outside = (boxes[:, 0] < frame.x0) | (boxes[:, 2] > frame.x1)
    outside |= (boxes[:, 1] < frame.y0) | (boxes[:, 3] > frame.y1)
    return hidden + 1e6 * outside
