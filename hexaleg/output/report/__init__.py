"""``hexaleg report``: everything hexaleg can tell a leg designer, in one folder.

Data first, then presentation, in three steps:

1. :func:`compute_report` ``(robot, options) -> ReportData``: runs the ``compute`` of
   every part that holds for the robot once, each after the parts it needs, into frozen
   records;
2. each part's ``section(data) -> Section``: pure text, tables and figure references;
3. one renderer (:mod:`.content`, :mod:`.document`) writes each part's files, then
   ``report.md``, ``report.html`` and ``report.json``; :func:`render_report` builds them
   in a staging folder and swaps it in only when complete.

Adding a section
----------------
Write one module here, e.g. ``walking.py``, holding:

- a frozen record, ``@dataclass(frozen=True) class WalkingRecord``;
- ``compute(data: ReportData) -> WalkingRecord``: read the design (``data.design``),
  the options, the model and the records of the parts you need (``data[StaticsRecord]``);
- ``section(data: ReportData) -> Section``: the title (without its number) and blocks —
  markdown text, tables made with :func:`~.document.table`, and
  :class:`~.section.Figure` ``(name, caption)``
  for a figure your ``files`` writes as ``<name>.png`` and ``<name>.svg``
  (``save(figure, out / "<name>.png", svg=data.options.svg)``);
- optionally ``write_files(data, out)`` (figures, CSV) and ``to_json(record) -> dict``
  (your top-level keys of ``report.json``, SI units);
- ``PART = Part(WalkingRecord, compute, section, needs=(StaticsRecord,), step="walking",
  files=write_files, json=to_json, level=2)``: level 1 is a numbered section, 2 a
  subsection of the one before, 0 unnumbered; refer to another section by its number,
  ``data.number(StaticsRecord)``, never by a typed one.

Then add ``walking.PART`` to :data:`~.registry.PARTS` where the section should appear.
``compute`` sees only the records listed in ``needs`` (a missing one fails with its
name); ``section`` sees them all. A part that holds only for some robots says so with
``holds=`` (:data:`~.part.Holds`: ``where_legs_are_the_designs(section, why)`` for the
paper's leg, ``where_legs_are_their_own`` for a robot file's); the report of a robot it
does not hold for leaves it out and, where it gives a why, says so. Nothing else
changes: numbering, the HTML and PDF layout, the links to each figure's PNG and SVG all
follow.
"""

from __future__ import annotations

import os

from hexaleg.design import HexapodDesign
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.part import LeftOut, Part, ReportData, compute_parts, headline
from hexaleg.output.report.pdf import REPORT_PDF, require_pdf_engine
from hexaleg.output.report.registry import PARTS, refused_options
from hexaleg.output.report.render import (
    REPORT_HTML,
    REPORT_JSON,
    REPORT_MD,
    check_target,
    render_report,
)
from hexaleg.output.report.section import Figure, Section
from hexaleg.robot.robot import Robot

__all__ = [
    "PARTS",
    "REPORT_HTML",
    "REPORT_JSON",
    "REPORT_MD",
    "REPORT_PDF",
    "Figure",
    "LeftOut",
    "Part",
    "ReportData",
    "ReportOptions",
    "Section",
    "build_report",
    "compute_report",
    "headline",
    "refused_options",
    "render_report",
]


def compute_report(robot: Robot | HexapodDesign, options: ReportOptions) -> ReportData:
    """Run every part of the report that holds for ``robot``, with a progress bar on a terminal.

    A design is hexaleg's template at it.
    """
    return compute_parts(robot, options, PARTS)


def build_report(
    out_dir: str | os.PathLike[str],
    robot: Robot | HexapodDesign | None = None,
    options: ReportOptions | None = None,
) -> ReportData:
    """Run every analysis on ``robot`` and write the report folder; return what it computed.

    ``robot``: the robot reported on (a design: hexaleg's template at it; the default
    design's if omitted). The returned record's :meth:`~ReportData.to_dict` is
    ``report.json``. With ``options.pdf``, the folder also holds ``report.pdf`` (the
    ``[pdf]`` extra).
    """
    options = options or ReportOptions()
    check_target(out_dir)  # before the minutes of computing, not after
    if options.pdf:
        require_pdf_engine()
    if options.simulate:
        from hexaleg.sim._mujoco import require_mujoco

        require_mujoco()
    data = compute_report(HexapodDesign() if robot is None else robot, options)
    render_report(data, out_dir)
    return data
