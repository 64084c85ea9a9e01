"""The report: every section on a reduced sweep, the same numbers as the CLI, atomic output."""

from __future__ import annotations

import json

import pytest

from hexaleg import HexapodDesign
from hexaleg.cli import main
from hexaleg.exceptions import HexalegError
from hexaleg.output.report import ReportOptions, build_report

REDUCED = ReportOptions(l3_points=8, sensitivity_points=4, workers=1, progress=False)
SECTIONS = [
    "## Design",
    "## 1. Swing phase: workspace",
    "## 2. Manipulability",
    "**Table 6 reproduced**",
    "## 3. Body flexibility",
    "## 3.1 Design study",
    "## 3.2 Sensitivity",
    "## 4. 3-D view",
    "## 5. Recommendation",
]
FILES = [
    "report.md",
    "report.html",
    "report.json",
    "hexapod.urdf",
    "viewer.html",
    "table5.csv",
    "table6.csv",
    "average_manipulability.csv",
    "extremes.csv",
    "sensitivity.csv",
    "recommendation_scores.csv",
    "study/study.csv",
    "workspace_monte_carlo.png",
    "workspace_planar.png",
    "workspace_l1_series.png",
    "manipulability_surface.png",
    "manipulability_surfaces_table5.png",
    "manipulability_average_map.png",
    "flexibility_extremes.png",
    "flexibility_fb.png",
    "flexibility_ranges.png",
]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report") / "out"
    data = build_report(out, options=REDUCED)
    return out, data


def test_report_has_every_section_and_file(report):
    out, _ = report
    text = (out / "report.md").read_text()
    for heading in SECTIONS:
        assert heading in text
    for name in FILES:
        assert (out / name).is_file(), name
    html = (out / "report.html").read_text()
    assert "<table>" in html and "workspace_planar.png" in html
    for image in [n for n in FILES if n.endswith(".png")]:
        assert f"]({image})" in text  # every figure is shown in the report
    assert "**misprinted**" in text  # Table 6 row 1, flagged rather than matched


def test_report_numbers_equal_the_cli_json(report, capsys):
    _, data = report
    assert main(["workspace", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["workspace"]
    assert main(["manipulability", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["manipulability"]
    assert main(["flexibility", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["flexibility"]["axis"]
    assert main(["flexibility", "--mode", "free", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["flexibility"]["free"]


def test_report_json_equals_what_was_returned(report):
    out, data = report
    assert json.loads((out / "report.json").read_text())["recommendation"] == json.loads(
        json.dumps(data["recommendation"])
    )
    rec = data["recommendation"]
    assert rec["l1_ratio"] == pytest.approx(0.10)
    assert rec["l3_band"][0] <= rec["l3_ratio"] <= rec["l3_band"][1]
    assert sum(rec["lengths_m"]) == pytest.approx(1.0)


def test_second_run_replaces_and_reproduces_the_numbers(tmp_path):
    out = tmp_path / "again"
    first = build_report(out, options=REDUCED)
    (out / "stale.txt").write_text("left over")
    second = build_report(out, options=REDUCED)
    assert json.dumps(first, sort_keys=True) == json.dumps(second, sort_keys=True)
    assert not (out / "stale.txt").exists()  # nothing stale survives
    assert [p.name for p in tmp_path.iterdir()] == ["again"]  # no staging folders left


@pytest.mark.parametrize(
    ("module", "name"),
    [
        ("hexaleg.output.report.compute", "sensitivity_table"),  # while computing
        ("hexaleg.output.report.render", "write_static_html"),  # half-way through writing
    ],
)
def test_failed_run_leaves_the_previous_report(tmp_path, monkeypatch, module, name):
    import importlib

    out = tmp_path / "kept"
    build_report(out, options=REDUCED)
    before = (out / "report.json").read_text()

    def broken(*args, **kwargs):
        raise RuntimeError("simulated failure in the middle")

    monkeypatch.setattr(importlib.import_module(module), name, broken)
    with pytest.raises(RuntimeError, match="simulated"):
        build_report(out, options=REDUCED)
    assert (out / "report.json").read_text() == before
    assert [p.name for p in tmp_path.iterdir()] == ["kept"]


def test_refuses_a_folder_that_is_not_a_report(tmp_path, capsys):
    (tmp_path / "mine.txt").write_text("user data")
    with pytest.raises(HexalegError, match="not a hexaleg report"):
        build_report(tmp_path, options=REDUCED)
    assert main(["report", "-o", str(tmp_path), "--l3-points", "3"]) == 2
    assert capsys.readouterr().err.count("\n") == 1
    assert [p.name for p in tmp_path.iterdir()] == ["mine.txt"]


def test_report_for_another_design(tmp_path):
    design = HexapodDesign.from_ratios(0.1, 0.45)
    data = build_report(tmp_path / "r", design, REDUCED)
    assert data["design"]["l3"] == pytest.approx(0.45)
    assert "0.1, 0.45, 0.45" in (tmp_path / "r" / "report.md").read_text()


def test_a_killed_report_leaves_no_staging_folder_behind(tmp_path):
    """kill -9 mid-report leaves its staging folder; the next run removes it."""
    import os
    import signal
    import subprocess
    import sys
    import time

    out = tmp_path / "r"
    argv = ["report", "-o", str(out), "--l3-points", "40", "--workers", "1"]
    process = subprocess.Popen(
        [sys.executable, "-m", "hexaleg", *argv],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    deadline = time.monotonic() + 120
    try:
        while time.monotonic() < deadline:
            staged = [p for p in tmp_path.iterdir() if p.name.startswith(".r.staging-")]
            if staged and any(staged[0].iterdir()):
                break  # it has started writing
            assert process.poll() is None, "the report ended before it could be killed"
            time.sleep(0.02)
        else:
            pytest.fail("the report staged nothing within 120 s")
    finally:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait(timeout=30)
    assert not out.exists() and len(staged) == 1
    build_report(out, options=REDUCED)
    assert [p.name for p in tmp_path.iterdir()] == ["r"]
    mask = os.umask(0)
    os.umask(mask)
    assert out.stat().st_mode & 0o777 == 0o777 & ~mask  # a normal folder, not mkdtemp's 0700
