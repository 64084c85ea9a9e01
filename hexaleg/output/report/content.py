"""Step 3 of the report, its content: every part's files, then markdown, HTML and JSON.

:func:`write_content` fills a folder; :mod:`~hexaleg.output.report.render` decides which
folder (a staging folder swapped in when complete).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from hexaleg._io import write_text
from hexaleg.output.report.document import report_html, report_json, report_markdown, sections
from hexaleg.output.report.part import Part, ReportData, compute_order
from hexaleg.output.report.pdf import write_pdf
from hexaleg.output.report.registry import parts_for

REPORT_MD = "report.md"
REPORT_HTML = "report.html"
REPORT_JSON = "report.json"


def write_content(data: ReportData, out: Path, parts: Sequence[Part[Any]] | None = None) -> None:
    """Write every part's files, then ``report.md``, ``report.html`` and ``report.json``.

    ``parts`` are those the report's options ask for unless given.

    With the ``pdf`` option, also ``report.pdf``: the same sections with vector figures.
    """
    parts = parts_for(data.options) if parts is None else parts
    for part in parts:
        part.files(data, out)
    report = sections(data, parts)
    write_text(out / REPORT_MD, report_markdown(report, out))
    write_text(out / REPORT_HTML, report_html(report, out))
    numbers = report_json(data, compute_order(parts))
    write_text(out / REPORT_JSON, json.dumps(numbers, indent=1, allow_nan=True))
    if data.options.pdf:
        write_pdf(report, out)
