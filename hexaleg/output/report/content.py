"""Step 3 of the report, its content: every part's files, then markdown, HTML and JSON.

:func:`write_content` fills a folder; :mod:`~hexaleg.output.report.render` decides which
folder (a staging folder swapped in when complete).
"""

from __future__ import annotations

import json
from pathlib import Path

from hexaleg._io import write_text
from hexaleg.output.report.document import report_html, report_markdown, sections
from hexaleg.output.report.part import ReportData
from hexaleg.output.report.pdf import write_pdf

REPORT_MD = "report.md"
REPORT_HTML = "report.html"
REPORT_JSON = "report.json"


def write_content(data: ReportData, out: Path) -> None:
    """Write every part's files, then ``report.md``, ``report.html`` and ``report.json``.

    With the ``pdf`` option, also ``report.pdf``: the same sections with vector figures.
    """
    for part in data.parts:
        part.files(data, out)
    report = sections(data)
    write_text(out / REPORT_MD, report_markdown(report, out))
    write_text(out / REPORT_HTML, report_html(report, out))
    numbers = json.dumps(data.to_dict(), indent=1, allow_nan=True)
    write_text(out / REPORT_JSON, numbers)
    if data.options.pdf:
        write_pdf(report, out)
