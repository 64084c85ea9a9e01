"""The report as a reader sees it: figures legible in a 1400 px browser window, and one PDF
with the same sections and figures, no table or figure cut across pages.

Slow: one reduced report with its PDF (~1 min), then Chromium and WeasyPrint layouts.
"""

from __future__ import annotations

import html
import itertools
import json
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

from hexaleg import HexapodDesign
from hexaleg.output.figures.canvas import SMALLEST_TEXT_KEY
from hexaleg.output.report import PARTS, ReportOptions, compute_report, render_report
from hexaleg.output.report.document import sections
from hexaleg.output.report.pages import LONG_TABLE, lay_out

pytestmark = pytest.mark.slow

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
WINDOW_WIDTH = 1400
SMALLEST_SHOWN_SHARE = 0.60  # of a figure's natural pixel width
SMALLEST_TEXT_PX = 9.0  # on screen, in the page and inside every figure
OPTIONS = ReportOptions(l3_points=10, sensitivity_points=4, workers=1, progress=False, pdf=True)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("layout") / "r"
    data = compute_report(HexapodDesign(), OPTIONS)
    render_report(data, out)
    return out, data


def _figures_in_html(out: Path) -> list[str]:
    return re.findall(r"<figure><a href='([^']+\.png)'>", (out / "report.html").read_text())


# -- the page in a browser ------------------------------------------------------------------

MEASURE = """<script>
window.addEventListener('load', () => {
  const figures = [...document.querySelectorAll('figure img')].map(img => ({
    src: img.getAttribute('src'), natural: img.naturalWidth,
    shown: img.getBoundingClientRect().width}));
  const text = [...document.querySelectorAll('p, td, th, figcaption, li, h1, h2, h3')].map(
    e => parseFloat(getComputedStyle(e).fontSize));
  const pre = document.createElement('pre');
  pre.id = 'hexaleg-measure';
  pre.textContent = JSON.stringify({figures, smallest_text: Math.min(...text),
                                    width: window.innerWidth});
  document.body.appendChild(pre);
});
</script>"""


def _measure_in_chromium(out: Path) -> dict:
    """Load report.html at 1400 px in headless Chromium; sizes as the page lays them out."""
    probe = out / ".measure.html"
    probe.write_text((out / "report.html").read_text().replace("</body>", MEASURE + "</body>"))
    try:
        with tempfile.TemporaryDirectory() as profile:
            dom = subprocess.run(
                [
                    CHROMIUM,
                    "--headless",
                    "--no-sandbox",
                    "--disable-gpu",
                    "--disable-background-networking",
                    "--no-first-run",
                    f"--user-data-dir={profile}",
                    f"--window-size={WINDOW_WIDTH},1000",
                    "--virtual-time-budget=10000",
                    "--dump-dom",
                    probe.as_uri(),
                ],
                capture_output=True,
                text=True,
                timeout=180,
                check=True,
            ).stdout
    finally:
        probe.unlink()
    found = re.search(r'<pre id="hexaleg-measure">(.*?)</pre>', dom, re.S)
    assert found, "the page never finished loading"
    return json.loads(html.unescape(found.group(1)))


def test_every_figure_is_legible_at_1400_px(report):
    from PIL import Image

    if CHROMIUM is None:
        if os.environ.get("CI"):
            pytest.fail("chromium is not installed: .ci/run must install it")
        pytest.skip("chromium is not installed: cannot lay the page out")
    out, _ = report
    measured = _measure_in_chromium(out)
    assert measured["width"] == WINDOW_WIDTH
    figures = {f["src"]: f for f in measured["figures"]}
    assert (
        sorted(figures)
        == sorted(_figures_in_html(out))
        == sorted(p.name for p in out.glob("*.png"))
    )  # every figure written is shown, once
    for name, figure in figures.items():
        with Image.open(out / name) as image:
            natural = image.width
            smallest = float(image.text[SMALLEST_TEXT_KEY])
        assert figure["natural"] == natural
        share = figure["shown"] / natural
        assert share >= SMALLEST_SHOWN_SHARE, f"{name} shown at {share:.0%} of its width"
        assert smallest * min(share, 1.0) >= SMALLEST_TEXT_PX, (
            f"{name}: its smallest text is {smallest * share:.1f} px on screen"
        )
    assert measured["smallest_text"] >= SMALLEST_TEXT_PX


def test_each_figure_links_to_its_png_and_svg(report):
    out, _ = report
    page = (out / "report.html").read_text()
    for png in _figures_in_html(out):
        svg = png.replace(".png", ".svg")
        assert f"<a href='{png}'>PNG</a>" in page and f"<a href='{svg}'>SVG</a>" in page
        assert (out / svg).read_text().lstrip().startswith("<?xml")


# -- the PDF ---------------------------------------------------------------------------------


def _outline_titles(reader) -> list[tuple[str, int]]:
    titles = []

    def walk(items):
        for item in items:
            if isinstance(item, list):
                walk(item)
            else:
                titles.append((item.title, reader.get_destination_page_number(item)))

    walk(reader.outline)
    return titles


def test_the_pdf_holds_every_section_and_figure_of_the_html(report):
    from pypdf import PdfReader

    out, _ = report
    reader = PdfReader(out / "report.pdf")
    page_text = [page.extract_text() for page in reader.pages]
    headings = re.findall(r"<h2>(.*?)</h2>", (out / "report.html").read_text())
    outline = _outline_titles(reader)
    assert [title for title, _ in outline] == ["hexaleg report", *map(html.unescape, headings)]
    first_pages = [page for _, page in outline[1:]]
    assert first_pages == sorted(first_pages)  # in reading order
    assert headings[0] == "Decision" and first_pages[0] == 0  # the answer on the first page
    figures = _figures_in_html(out)
    for number in range(1, len(figures) + 1):
        pages = [k for k, text in enumerate(page_text) if f"Figure {number}:" in text]
        assert len(pages) == 1, f"Figure {number} is on pages {pages}"
    assert not any(f"Figure {len(figures) + 1}:" in text for text in page_text)
    # vector figures: no page embeds a whole figure as an image (only rasterized clouds)
    for page in reader.pages:
        for image in page.images:
            assert image.image.width < 1000, f"a {image.image.width} px image in the PDF"


def test_the_pdf_cuts_no_figure_and_only_a_long_table_between_rows(report):
    from pypdf import PdfReader

    out, data = report
    page, document = lay_out(sections(data, PARTS), out)  # as the PDF was laid out
    assert len(document.pages) == len(PdfReader(out / "report.pdf").pages)
    usable = float(document.pages[0]._page_box.height)
    pages_of: dict[int, set[int]] = {}
    heights: dict[int, float] = {}
    elements = {}
    for number, laid_out in enumerate(document.pages):
        for box in _boxes(laid_out._page_box):
            if getattr(box, "element_tag", None) in ("table", "figure"):
                pages_of.setdefault(id(box.element), set()).add(number)
                heights[id(box.element)] = heights.get(id(box.element), 0.0) + box.height
                elements[id(box.element)] = box.element
    assert len(pages_of) == page.count("<table") + page.count("<figure>")  # every one laid out
    for key, pages in pages_of.items():
        if len(pages) > 1:  # only a table, at least LONG_TABLE of a page, marked long
            element = elements[key]
            assert element.tag == "table" and element.get("class") == "long"
            assert heights[key] >= LONG_TABLE * usable * 0.9  # its rows, less repeated headers


def _boxes(box):
    yield box
    for child in getattr(box, "children", None) or []:
        yield from _boxes(child)


PAGE_MARGIN_PT = 12 / 25.4 * 72  # the print style's @page margin
FOOTER_TOP_PT = 25.0  # the page number sits below this height
CSS_PX_PT = 0.75  # WeasyPrint lays out in CSS px


def _text_heights(page) -> list[float]:
    """Heights above the page's foot [pt] of each run of text on a PDF page, but the footer."""
    heights: list[float] = []

    def visit(text, cm, tm, font, size):
        y = cm[5] + tm[5] * cm[3]
        if text.strip() and y > FOOTER_TOP_PT:
            heights.append(y)

    page.extract_text(visitor_text=visit)
    return heights


def test_no_heading_is_left_alone_at_the_foot_of_a_page(report):
    from pypdf import PdfReader

    out, _ = report
    reader = PdfReader(out / "report.pdf")

    def walk(items):
        for item in items:
            yield from walk(item) if isinstance(item, list) else [item]

    headings = [item for item in walk(reader.outline)][1:]  # not the document's title
    assert headings
    for heading in headings:
        page = reader.get_destination_page_number(heading)
        below = [y for y in _text_heights(reader.pages[page]) if y < float(heading.top) - 30]
        assert below, f"'{heading.title}' is the last thing on page {page + 1}"


def test_no_page_ends_with_a_heading_or_the_words_that_introduce_a_table(report):
    """A heading and what follows it, a paragraph and the table after it: on one page.

    Read from the print page's own elements in print order (not from the blocks hexaleg
    groups them into) and the page WeasyPrint put each on.
    """
    out, data = report
    _, document = lay_out(sections(data, PARTS), out)
    placed: dict = {}  # element → [tag, first page, last page, text], in print order
    parents: dict = {}
    for number, laid_out in enumerate(document.pages):
        for box in _boxes(laid_out._page_box):
            element = getattr(box, "element", None)
            if element is not None and box.element_tag == "html" and not parents:
                parents = {child: parent for parent in element.iter() for child in parent}
            parent = parents.get(element)
            if parent is None or parent.get("class", "").split()[:1] != ["block"]:
                continue
            if element in placed:
                placed[element][2] = number
            else:
                text = " ".join("".join(element.itertext()).split())
                placed[element] = [box.element_tag, number, number, text]
    pairs = 0
    for (tag, _, last, text), (next_tag, first, _, next_text) in itertools.pairwise(
        placed.values()
    ):
        if tag == "h2" or (tag == "p" and next_tag == "table"):
            pairs += 1
            assert last == first, (
                f"'{text[:60]}' ends page {last + 1}, '{next_text[:40]}' is on {first + 1}"
            )
    assert pairs > len(re.findall(r"<h2>", (out / "report.html").read_text()))  # and tables


MOSTLY_BLANK = 0.5
"""A page blank under more than half its height is mostly blank."""


def _blank_shares(pdf: Path) -> list[float]:
    """Each page's share of its text area left blank under its last ink, from its pixels."""
    from PIL import Image

    with tempfile.TemporaryDirectory() as folder:
        subprocess.run(["pdftoppm", "-r", "30", "-gray", str(pdf), f"{folder}/p"], check=True)
        shares = []
        for path in sorted(Path(folder).glob("p-*.pgm")):
            with Image.open(path) as image:
                ink = np.asarray(image) < 200
            height = ink.shape[0]
            margin = round(height * 12 / 297)  # the print style's 12 mm margins on A4
            area = ink[margin : height - margin]  # the footer sits in the bottom margin
            rows = np.flatnonzero(area.any(axis=1))
            shares.append(1.0 - (rows[-1] + 1) / len(area) if rows.size else 1.0)
    return shares


def test_no_page_but_the_last_is_mostly_blank(report):
    out, _ = report
    shares = _blank_shares(out / "report.pdf")
    assert len(shares) > 5
    mostly = [
        (k + 1, f"{share:.0%}") for k, share in enumerate(shares[:-1]) if share > MOSTLY_BLANK
    ]
    assert not mostly, f"pages left mostly blank: {mostly}"


def test_the_pdf_shows_a_still_of_the_3d_view_and_links_to_it(report):
    from pypdf import PdfReader

    out, _ = report
    reader = PdfReader(out / "report.pdf")
    texts = [" ".join(p.extract_text().split()) for p in reader.pages]
    (start,) = [k for k, text in enumerate(texts) if "4. 3-D view" in text]
    (still,) = [k for k, text in enumerate(texts) if "The nominal stance, as viewer" in text]
    assert still in (start, start + 1)  # the section's still: on its page or the next
    assert "viewer.html" in texts[start]
    assert re.search(r"Figure \d+: The nominal stance", texts[still])
    assert "a still of it:" in texts[still]  # its introduction's end beside it
    page = reader.pages[start]
    links = [a.get_object().get("/A", {}).get("/URI", "") for a in page.get("/Annots", [])]
    assert any(str(uri).endswith("viewer.html") for uri in links)


def test_no_table_of_the_report_prints_nan_or_inf(report):
    """A missing number is said in words: every cell of every table is read for nan/inf."""
    out, _ = report
    cells = [
        cell.strip()
        for line in (out / "report.md").read_text().splitlines()
        if line.startswith("|")
        for cell in line.strip("|").split("|")
    ]
    assert len(cells) > 100
    bad = [c for c in cells if re.search(r"\b(nan|inf|infinity)\b", c, re.IGNORECASE)]
    assert not bad, f"table cells {bad}"
