"""The report as one PDF, for a design review that circulates one file.

Engine: WeasyPrint (PyPI ``weasyprint``, the ``[pdf]`` extra). Chosen over Chromium's
print-to-PDF because it installs with pip like the rest of hexaleg (Chromium is a system
package, absent on most servers and CI images), it draws SVG figures as vectors into the
PDF, and it implements CSS paged media: A4 pages with numbered footers and
``break-inside: avoid`` honoured for tables and figures, so no table is cut across pages;
its layout can be read back (each block's page and position), which the page mending uses.
It needs Pango (a system library present on common Linux distributions).

The PDF is made from the same sections as ``report.html``, with the print stylesheet of
:mod:`~hexaleg.output.report.document` and each figure's SVG instead of its PNG, laid out
on pages by :mod:`~hexaleg.output.report.pages` (headings kept with what follows them, no
page but the last left mostly blank where a figure can be moved or shrunk).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from hexaleg.exceptions import HexalegError
from hexaleg.output.report.document import Section
from hexaleg.output.report.pages import lay_out

REPORT_PDF = "report.pdf"

MISSING = (
    "--pdf needs WeasyPrint: pip install 'hexaleg[pdf]' (it also needs the Pango library, "
    "e.g. apt-get install libpango-1.0-0 libpangoft2-1.0-0)"
)
"""The one-line error when the PDF engine cannot be loaded."""


def require_pdf_engine() -> None:
    """Fail with :data:`MISSING` if WeasyPrint (or the Pango it loads) is not installed."""
    try:
        import weasyprint  # noqa: F401
    except (ImportError, OSError) as err:  # OSError: Pango missing
        raise HexalegError(MISSING) from err


def write_pdf(report: Sequence[Section], folder: Path) -> Path:
    """Write ``report.pdf`` into ``folder``, whose figures (PNG and SVG) are written already.

    The pages are laid out by :func:`~hexaleg.output.report.pages.lay_out`.
    """
    require_pdf_engine()
    _, document = lay_out(report, folder)
    path = folder / REPORT_PDF
    document.write_pdf(path)
    return path
