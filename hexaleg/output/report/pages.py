"""The PDF's pages: the print blocks laid out on A4, then mended where a page is left blank.

WeasyPrint lays the blocks of :func:`~hexaleg.output.report.document.print_blocks` out on
A4 (CSS paged media): a block that must stay on one page (a heading with what follows it, a
paragraph with its table, a table, a figure) moves whole to the next page when it does not
fit in what is left of this one. Where that leaves a page (not the last) more than
:data:`FIX_BLANK` blank, the layout mends it, then lays the pages out again (at most
:data:`MAX_PASSES` times):

1. a figure that moved is drawn smaller, down to :data:`MIN_SCALE` of the size it was drawn, if that
   makes its block fit in the gap; else
2. the text after it in its section fills the gap and the figure follows that text (a float,
   as LaTeX places figures), never past another figure nor into another section.

3. a table at least :data:`LONG_TABLE` of a page tall that moved whole to the next page
   starts in the gap instead, cut between two rows, its header repeated on the next page.

A gap before a short table or a heading is left: moving those would change what the text
says "below". Figures keep their numbers (reading order); only where they are printed
changes.
"""

from __future__ import annotations

import itertools
import logging
import re
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexaleg.output.report.document import PrintBlock, print_blocks, print_html
from hexaleg.output.report.section import Section

if TYPE_CHECKING:
    from weasyprint import Document

FIX_BLANK = 0.35
"""A page (not the last) blank over more than this share of its height is mended [-]."""

MIN_SCALE = 0.85
"""The smallest share of its drawn size a figure is printed at [-]: its smallest text, 7.5 pt
as drawn, prints at 6.4 pt."""

MAX_PASSES = 8
"""Layouts at most (the first, then one per mend)."""

LONG_TABLE = 0.4
"""A table at least this share of a page tall may be cut between rows (its header repeated)
where moving it whole would leave a page mostly blank [-]."""

SAFETY_PX = 32.0
"""Room left when a figure is shrunk to fit a gap [CSS px]: its top margin (1.5 rem), cut
at the top of a page, is kept under the text above it."""


@dataclass(frozen=True)
class Layout:
    """The order blocks are printed in and the share of its size each figure is drawn at.

    Attributes:
        order: Block indices in print order (a permutation of reading order).
        scales: Figure name → share of its drawn size [-].
        mended: Figure names already shrunk or floated (each is mended once).
        long_tables: Tables (``t<n>``, in reading order) that may be cut across pages.

    """

    order: tuple[int, ...]
    scales: dict[str, float] = field(default_factory=dict)
    mended: frozenset[str] = frozenset()
    long_tables: frozenset[str] = frozenset()


@dataclass(frozen=True)
class Page:
    """One laid-out page, as the mending reads it.

    Attributes:
        blocks: The blocks on it, top to bottom: (index, top, height) [CSS px].
        blank: The height left under its last line, row or image [CSS px].
        usable: The height of its content area [CSS px].
        top: The top of its content area [CSS px].
        tables: The tables on it: (``t<n>``, top, height) [CSS px].

    """

    blocks: tuple[tuple[int, float, float], ...]
    blank: float
    usable: float
    top: float = 0.0
    tables: tuple[tuple[str, float, float], ...] = ()


def lay_out(report: Sequence[Section], folder: Path) -> tuple[str, Document]:
    """The print HTML of ``report`` and its WeasyPrint layout, mended (see the module)."""
    import weasyprint

    logging.getLogger("weasyprint").setLevel(logging.ERROR)  # font-subsetting chatter
    logging.getLogger("fontTools").setLevel(logging.ERROR)
    layout = Layout(tuple(range(len(print_blocks(report, folder)))))
    for _ in range(MAX_PASSES):
        blocks = print_blocks(report, folder, layout.scales, layout.long_tables)
        page = print_html(blocks, layout.order)
        document = weasyprint.HTML(string=page, base_url=str(folder)).render()
        mended = mend(blocks, layout, pages(document))
        if mended is None:
            break
        layout = mended
    return page, document


def pages(document: Document) -> list[Page]:
    """Each page's blocks, tables and blank height, from WeasyPrint's boxes."""
    found = []
    for laid_out in document.pages:
        box = laid_out._page_box
        top, usable = float(box.content_box_y()), float(box.height)
        blocks = tuple(
            (int(child.element.get("id")[1:]), float(child.position_y), _height(child))
            for child in _boxes_of(box, "div", r"b\d+")
        )
        tables = tuple(
            (str(child.element.get("id")), float(child.position_y), _height(child))
            for child in _boxes_of(box, "table", r"t\d+")
        )
        bottom = max((_bottom(leaf) for leaf in _leaves(box)), default=top)
        found.append(Page(blocks, top + usable - bottom, usable, top, tables))
    return found


_INKED = ("LineBox", "TableRowBox", "BlockReplacedBox", "InlineReplacedBox")
"""The boxes that print something: lines of text, table rows, images (a block that goes on
to the next page stretches to the foot of this one, so it cannot say where the ink ends)."""


def _leaves(box: Any) -> list[Any]:
    """The printed boxes under ``box`` (text lines, table rows, images), but its margins'."""
    found = []
    for child in getattr(box, "children", None) or []:
        kind = type(child).__name__
        if kind == "MarginBox":  # the page number
            continue
        found += [child] if kind in _INKED else _leaves(child)
    return found


def _bottom(box: Any) -> float:
    return float(box.position_y) + float(box.height)


def _height(box: Any) -> float:
    return float(box.margin_height())


def _boxes_of(box: Any, tag: str, ids: str) -> list[Any]:
    """The outermost boxes of the ``tag`` elements with an id matching ``ids``, in order."""
    found = []
    for child in getattr(box, "children", None) or []:
        element = getattr(child, "element", None)
        name = element.get("id", "") if element is not None else ""
        if getattr(child, "element_tag", None) == tag and re.fullmatch(ids, name):
            found.append(child)
        else:
            found += _boxes_of(child, tag, ids)
    return found


def mend(blocks: Sequence[PrintBlock], layout: Layout, laid: Sequence[Page]) -> Layout | None:
    """The layout with the first mendable blank page mended, or None if none is."""
    for page, after in itertools.pairwise(laid):
        if page.blank <= FIX_BLANK * page.usable or not after.blocks:
            continue
        mended = _mend_figure(blocks, layout, laid, page, after) or _long_table(layout, page, after)
        if mended is not None:
            return mended
    return None


def _mend_figure(
    blocks: Sequence[PrintBlock], layout: Layout, laid: Sequence[Page], page: Page, after: Page
) -> Layout | None:
    """Shrink or float the figure that opens the page after ``page``, if one does."""
    k, _, height = after.blocks[0]
    block = blocks[k]
    if not block.figure or block.figure in layout.mended:
        return None
    if any(index == k for index, _, _ in page.blocks):  # continued from this page
        return None
    return _shrink(block, height, page.blank, layout) or _float(blocks, k, page.blank, layout, laid)


def _long_table(layout: Layout, page: Page, after: Page) -> Layout | None:
    """Let a long table that moved whole to the next page start in the gap it left."""
    on_page = {name for name, _, _ in page.tables}
    for name, top, height in after.tables:
        if name in on_page or name in layout.long_tables:
            continue
        above = top - after.top  # the introduction's last lines, moved with it
        moved = above < 0.25 * after.usable and above + height > page.blank
        if moved and height >= LONG_TABLE * after.usable:
            return replace(layout, long_tables=layout.long_tables | {name})
        return None
    return None


def _shrink(block: PrintBlock, height: float, gap: float, layout: Layout) -> Layout | None:
    """The figure of ``block`` drawn small enough for the block to fit ``gap``, if it may be."""
    drawn = _figure_height(block)  # at its present scale
    scale = layout.scales.get(block.figure, 1.0)
    if drawn <= 0:
        return None
    shrink = 1.0 - (height - gap + SAFETY_PX) / drawn
    if shrink * scale < MIN_SCALE or shrink >= 1.0:
        return None
    scales = layout.scales | {block.figure: shrink * scale}
    return replace(layout, scales=scales, mended=layout.mended | {block.figure})


def _figure_height(block: PrintBlock) -> float:
    """The drawn height of the figure of ``block`` [CSS px] (its ``<img>`` style, at scale)."""
    found = re.search(r"height:([\d.]+)in", block.html)
    return float(found.group(1)) * 96.0 if found else 0.0


def _float(
    blocks: Sequence[PrintBlock], k: int, gap: float, layout: Layout, laid: Sequence[Page]
) -> Layout | None:
    """Block ``k`` moved after the text of its section that fills ``gap``, if there is some."""
    heights: dict[int, float] = {}
    for page in laid:
        for index, _, height in page.blocks:
            heights[index] = heights.get(index, 0.0) + height
    order = list(layout.order)
    at = order.index(k)
    passed, filled = 0, 0.0
    for index in order[at + 1 :]:
        block = blocks[index]
        if block.section != blocks[k].section or block.figure or block.heading:
            break
        if filled + heights.get(index, 0.0) > gap and block.keep:
            break
        passed += 1
        filled += heights.get(index, 0.0)
        if filled >= gap:
            break
    if passed == 0:
        return None
    order.insert(at + passed, order.pop(at))
    return replace(layout, order=tuple(order), mended=layout.mended | {blocks[k].figure})
