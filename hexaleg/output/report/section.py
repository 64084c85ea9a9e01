"""What a report part shows: a section of markdown blocks and figures (pure data).

The parts make :class:`Section` records; :mod:`~hexaleg.output.report.document` is the
only place that decides how they look.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Figure:
    """A figure block: ``<name>.png`` and ``<name>.svg`` in the report folder.

    Attributes:
        name: The file name without extension.
        caption: What the figure shows, in plain words.

    """

    name: str
    caption: str


Block = str | Figure
"""A markdown block (text or a table) or a figure."""


@dataclass(frozen=True)
class Section:
    """One ``##`` section of the report: a title and its blocks.

    The title has no number: the report adds it from the parts' reading order
    (:attr:`~hexaleg.output.report.part.Part.level`).
    """

    title: str
    blocks: tuple[Block, ...]
