"""The PDF's pages: headings stay with what they introduce, and a page left blank by a figure
that did not fit is mended (the figure drawn smaller, or the text after it moved up).

Small synthetic reports (blank figures of chosen sizes), laid out by WeasyPrint; where each
thing landed is read back from the written PDF's text with pypdf.
"""

from __future__ import annotations

import re

import pytest

from hexaleg.output.figures.canvas import DPI
from hexaleg.output.report.document import Figure, Section, print_blocks
from hexaleg.output.report.pages import MIN_SCALE, lay_out

pytest.importorskip("weasyprint")
USABLE_IN = (297 - 2 * 12) / 25.4  # A4 less the print style's 12 mm margins [in]


def _figure(folder, name: str, height_in: float) -> Figure:
    """A blank full-width figure ``height_in`` tall, as PNG (its size) and SVG (printed)."""
    from PIL import Image

    width, height = round(7.2 * DPI), round(height_in * DPI)
    Image.new("RGB", (width, height), "white").save(folder / f"{name}.png")
    (folder / f"{name}.svg").write_text(
        f"<svg xmlns='http://www.w3.org/2000/svg' width='{width}' height='{height}'>"
        f"<rect width='{width}' height='{height}' fill='#ddd'/></svg>"
    )
    return Figure(name, f"caption of {name}")


def _pages(report, folder) -> tuple[list[str], str]:
    """Each page's text in the PDF laid out for ``report``, and the HTML it was laid from."""
    from pypdf import PdfReader

    page, document = lay_out(report, folder)
    document.write_pdf(folder / "out.pdf")
    reader = PdfReader(folder / "out.pdf")
    return [" ".join(p.extract_text().split()) for p in reader.pages], page


def _page_of(pages: list[str], words: str) -> int:
    (found,) = [k for k, text in enumerate(pages) if words in text]
    return found


def _printed_height_in(page: str, name: str) -> float:
    """The height the print HTML gives figure ``name`` [in]."""
    found = re.search(rf"src='{name}\.svg'[^>]*height:([\d.]+)in", page)
    assert found
    return float(found.group(1))


def test_a_figure_a_little_too_tall_for_the_page_s_gap_is_drawn_smaller_to_fill_it(tmp_path):
    first, second = 0.38 * USABLE_IN, 0.35 * USABLE_IN  # with the title: not both at full size
    report = [Section("Figures", (_figure(tmp_path, "a", first), _figure(tmp_path, "b", second)))]
    pages, page = _pages(report, tmp_path)
    assert _page_of(pages, "Figure 1: caption of a") == _page_of(pages, "Figure 2: caption of b")
    printed = _printed_height_in(page, "b")
    assert MIN_SCALE * second <= printed < second  # smaller, not tiny
    assert _printed_height_in(page, "a") == pytest.approx(first, abs=0.01)


def test_a_figure_far_too_tall_for_the_gap_lets_the_text_after_it_fill_the_page(tmp_path):
    words = " ".join(f"word{k}" for k in range(160))
    report = [
        Section(
            "Figures",
            (
                _figure(tmp_path, "a", 0.4 * USABLE_IN),
                _figure(tmp_path, "b", 0.6 * USABLE_IN),
                f"After b: {words} ENDOFTEXT.",
            ),
        ),
        Section("Next", ("The next section.",)),
    ]
    pages, page = _pages(report, tmp_path)
    a, b = _page_of(pages, "Figure 1: caption"), _page_of(pages, "Figure 2: caption")
    assert a == 0 and b == 1
    assert _page_of(pages, "After b: word0") == 0  # the text moved up under figure a
    assert _page_of(pages, "ENDOFTEXT") <= b
    assert _printed_height_in(page, "b") == pytest.approx(0.6 * USABLE_IN, abs=0.01)
    order = [block.figure for block in print_blocks(report, tmp_path) if block.figure]
    assert order == ["a", "b"]  # the numbers still follow the reading order


def test_a_heading_and_the_words_introducing_a_table_go_with_the_table(tmp_path):
    rows = "\n".join(f"| row{k} | {k} |" for k in range(12))
    report = [
        Section("Big", (_figure(tmp_path, "a", 0.86 * USABLE_IN),)),
        Section("Small", ("The numbers:", f"| name | value |\n|---|---|\n{rows}", "After.")),
    ]
    pages, _ = _pages(report, tmp_path)
    table = _page_of(pages, "row11 11")
    assert _page_of(pages, "Small") == _page_of(pages, "The numbers:") == table == 1


def test_a_long_table_that_would_leave_a_page_mostly_blank_starts_in_it_cut_between_rows(
    tmp_path,
):
    rows = "\n".join(f"| row{k} | {k} |" for k in range(45))  # about 70 % of a page
    report = [
        Section("Big", (_figure(tmp_path, "a", 0.42 * USABLE_IN),)),
        Section("Long", ("The numbers:", f"| name | value |\n|---|---|\n{rows}")),
    ]
    pages, page = _pages(report, tmp_path)
    first, last = _page_of(pages, "row0 0"), _page_of(pages, "row44 44")
    assert first == _page_of(pages, "Figure 1: caption") == 0 and last == 1  # cut, not moved
    assert all("name value" in pages[k] for k in (first, last))  # its header on both pages
    assert "class=long" in page


def test_a_short_table_is_never_cut(tmp_path):
    rows = "\n".join(f"| row{k} | {k} |" for k in range(14))
    report = [
        Section("Big", (_figure(tmp_path, "a", 0.72 * USABLE_IN),)),
        Section("Short", ("The numbers:", f"| name | value |\n|---|---|\n{rows}")),
    ]
    pages, _ = _pages(report, tmp_path)
    assert _page_of(pages, "row0 0") == _page_of(pages, "row13 13") == 1
