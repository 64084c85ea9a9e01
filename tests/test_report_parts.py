"""The report's machinery: parts computed in dependency order from only what they need,
figures numbered and linked, the slopes as one line when headings agree, a clear error
when the PDF engine is missing."""

from __future__ import annotations

import dataclasses
import math
import sys
from types import SimpleNamespace

import numpy as np
import pytest

from hexaleg.exceptions import HexalegError
from hexaleg.output.report import PARTS, Figure, Part, ReportData, ReportOptions, Section
from hexaleg.output.report.document import png_size, report_html, report_markdown
from hexaleg.output.report.part import compute_order


@dataclasses.dataclass(frozen=True)
class A:
    value: int


@dataclasses.dataclass(frozen=True)
class B:
    value: int


@dataclasses.dataclass(frozen=True)
class C:
    value: int


def _section(data: ReportData) -> Section:
    return Section("t", ())


def _part(record, compute, needs=()):
    return Part(record, compute, _section, needs=needs)


def test_parts_are_computed_after_what_they_need_and_see_only_that(default_design):
    seen = []

    def make_c(data):
        seen.append(sorted(kind.__name__ for kind in data.records))
        return C(data[A].value + data[B].value)

    parts = [
        _part(C, make_c, needs=(A, B)),  # shown first, computed last
        _part(B, lambda data: B(2)),
        _part(A, lambda data: A(1)),
    ]
    assert [p.record for p in compute_order(parts)] == [A, B, C]  # needs first, in their order
    data = ReportData(default_design, ReportOptions(), model=None)
    for part in compute_order(parts):
        data = data.with_record(part.compute(data.only(part.needs)))
    assert data[C] == C(3) and seen == [["A", "B"]]
    with pytest.raises(HexalegError, match="B is not computed"):
        data.only((A,))[B]


def test_a_missing_or_circular_need_is_named():
    with pytest.raises(HexalegError, match="no report part makes B"):
        compute_order([_part(A, lambda d: A(0), needs=(B,))])
    with pytest.raises(HexalegError, match="circle"):
        compute_order([_part(A, lambda d: A(0), needs=(B,)), _part(B, lambda d: B(0), needs=(A,))])


def test_the_registry_shows_the_decision_first_and_computes_it_last():
    from hexaleg.output.report.decision import DecisionRecord

    records = [part.record for part in PARTS]
    assert len(set(records)) == len(records)
    shown = [part.record for part in PARTS if part.section is not None]
    assert shown[0] is DecisionRecord  # what it reads first shows no section of its own
    order = [part.record for part in compute_order(PARTS)]
    for need in PARTS[0].needs:
        assert order.index(need) < order.index(DecisionRecord)


def test_figures_are_numbered_in_reading_order_and_shown_at_their_size(tmp_path):
    from PIL import Image

    Image.new("RGB", (640, 360), "white").save(tmp_path / "a.png")
    Image.new("RGB", (1080, 500), "white").save(tmp_path / "b.png")
    (tmp_path / "b.svg").write_text("<svg/>")
    report = [
        Section("One", ("text", Figure("b", "the second file, shown first"))),
        Section("Two", (Figure("a", "no SVG beside it"),)),
    ]
    text = report_markdown(report, tmp_path)
    assert text.index("Figure 1: the second file") < text.index("Figure 2: no SVG")
    assert "(full size: [PNG](b.png), for print: [SVG](b.svg))" in text
    assert "(full size: [PNG](a.png))" in text  # no link to a file that is not there
    page = report_html(report, tmp_path)
    assert "width='1080' height='500'" in page and "width='640' height='360'" in page
    assert png_size(tmp_path / "b.png") == (1080, 500)
    printed = report_html(report, tmp_path, medium="print")
    assert f"width:{1080 / 150:.3f}in" in printed and "src='b.svg'" in printed


def _slopes(*values):
    return SimpleNamespace(
        slopes=tuple(
            SimpleNamespace(heading=math.radians(h), max_slope=math.radians(a), limited_by=c)
            for h, a, c in values
        )
    )


def test_slopes_are_one_table_line_when_every_heading_agrees():
    from hexaleg.output.figures.statics import slopes_differ
    from hexaleg.output.report.statics import _slope_table

    same = _slopes((0, 31.0, "slide"), (90, 31.0, "slide"), (180, 31.0, "slide"))
    table = _slope_table(same, slopes_differ(same))
    assert table.count("\n") == 2  # header, rule, one row
    assert "every heading (+0°, +90°, +180°)" in table and "| 31.0 |" in table
    tipping = _slopes((0, 31.0, "slide"), (90, 24.5, "tip"))
    table = _slope_table(tipping, slopes_differ(tipping))
    assert table.count("\n") == 3 and "tipping over" in table and "| 24.5 |" in table


def test_the_loads_figure_draws_slopes_only_where_headings_differ(default_design):
    from hexaleg.output.figures import loads_figure
    from hexaleg.statics.loads import analyze_loads

    loads = analyze_loads(default_design)
    assert len({round(s.max_slope, 6) for s in loads.slopes}) == 1  # μ binds every way
    assert len(loads_figure(loads).axes) == 1
    first = loads.slopes[0]
    steeper = dataclasses.replace(first, max_slope=first.max_slope / 2, limited_by="tip")
    differing = dataclasses.replace(loads, slopes=(steeper, *loads.slopes[1:]))
    assert len(loads_figure(differing).axes) == 2


def test_a_missing_pdf_engine_is_one_line_before_any_work(tmp_path, monkeypatch, capsys):
    from conftest import run_cli

    from hexaleg.output.report import build_report

    monkeypatch.setitem(sys.modules, "weasyprint", None)  # import weasyprint fails
    with pytest.raises(HexalegError, match=r"pip install 'hexaleg\[pdf\]'"):
        build_report(tmp_path / "r", options=ReportOptions(pdf=True))
    assert run_cli(["report", "--pdf", "-o", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "WeasyPrint" in err
    assert list(tmp_path.iterdir()) == []


def test_payload_axes_are_logarithmic_and_name_the_largest():
    import pandas as pd

    from hexaleg.evaluation.metrics import Metrics
    from hexaleg.output.figures import pareto_figure, statics_study_figure

    l3 = np.linspace(0.1, 0.75, 5)
    table = pd.DataFrame(
        {
            "l1_ratio": 0.2,
            "l3_ratio": l3,
            "l1": 0.2,
            "l2": 0.8 - l3,
            "l3": l3,
            "peak_hip_torque": 50.0,
            "peak_knee_torque": 40.0,
            "payload_capacity": [40.0, 80.0, 150.0, 300.0, 1769.0],
            "fb": [0.1, 0.2, 0.25, 0.2, 0.1],
        }
    )
    figure = statics_study_figure(table)
    payload = figure.axes[2]
    assert payload.get_yscale() == "log"
    assert [t.get_text() for t in payload.texts] == ["1769 kg: coxa 0.20, femur 0.05, tibia 0.75 m"]
    walking = table.assign(walking_payload_capacity=[1.0, 5.0, 9.0, 12.0, 20.0], walks=True)
    front = walking.assign(score=1.0)
    pareto = pareto_figure(walking, front).axes[0]
    assert "walking payload" in pareto.get_xlabel() and "20 kg" in pareto.texts[0].get_text()
    yours = Metrics(walking_payload_capacity=4.0, fb=0.23)
    marked = pareto_figure(walking, front, yours).axes[0]
    (mark,) = [c for c in marked.collections if c.get_label() == "your design"]
    assert mark.get_offsets().tolist() == [[4.0, 0.23]]


def test_the_paper_claims_read_the_same_in_figures_and_text(default_design):
    from hexaleg.output.figures import average_manipulability_figure, fb_figure
    from hexaleg.paper import CLAIMED_L3_RATIO_PEAK, CLAIMED_W_A_PEAK
    from hexaleg.swing.manipulability import average_manipulability_map

    w_map = average_manipulability_map((0.1, 0.2), np.linspace(0.2, 0.7, 6), 1.0)
    for ax in average_manipulability_figure(w_map).axes[:2]:
        claims = [line for line in ax.get_lines() if "paper" in line.get_label()]
        assert len(claims) == 1 and "0.45" in claims[0].get_label()
        assert claims[0].get_xdata()[0] == CLAIMED_W_A_PEAK == 0.45  # §5.4: "approximately 0.45"
        assert not ax.patches  # no 0.40–0.45 band: that is FB's claim, not w_A's
    import pandas as pd

    table = pd.DataFrame({"l1_ratio": 0.1, "l3_ratio": [0.3, 0.4, 0.5], "fb": [0.1, 0.2, 0.15]})
    peaks = pd.DataFrame({"l1_ratio": [0.1], "peak_l3_ratio": [0.4], "peak_fb": [0.2]})
    (ax,) = fb_figure(table, peaks).axes
    (band,) = ax.patches
    x0, x1 = ax.transData.inverted().transform(band.get_window_extent())[:, 0]
    assert (x0, x1) == pytest.approx(CLAIMED_L3_RATIO_PEAK) == (0.40, 0.45)


def test_the_flexibility_table_names_directions_as_everywhere_else(default_design, hexapod_model):
    """The section's rows and ``extremes.csv`` use the one label of a direction: ``x+``."""
    from hexaleg.output.report.flexibility import FlexibilityRecord, extremes_rows, section
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.output.report.part import ReportData
    from hexaleg.stance import AXES, axis_locked_flexibility

    axis = axis_locked_flexibility(default_design, "all", hexapod_model)
    record = FlexibilityRecord(axis, axis)
    data = ReportData(default_design, ReportOptions(), hexapod_model).with_record(record)
    text = next(block for block in section(data).blocks if str(block).startswith("| direction"))
    labels = [line.split(" | ")[0].removeprefix("| ") for line in text.splitlines()[2:]]
    expected = [f"{a}{s}" for a in AXES for s in "+-"]  # written out: x+, x-, ... yaw-
    assert sorted(labels) == sorted(expected)
    assert [row["direction"] for row in extremes_rows(record)] == labels


def test_changes_read_as_an_engineer_writes_them():
    from hexaleg.output.report.document import change

    assert change(2.0, 46.6) == "+2230%"  # 22.3 times: three digits, not "+2230.0%"
    assert change(1.0, 0.865) == "-13.5%"
    assert change(1.0, 1.004) == "+0.4%"
    assert change(1.0, 1.0) == "+0%"
    assert change(0.0, 1.0) == "—" and change(1.0, float("nan")) == "—"
