"""Progress of long runs: a line every few seconds off a terminal, a bar on one."""

from __future__ import annotations

import io
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import pytest

from hexaleg.study import StudySpec, run_study
from hexaleg.study import progress as progress_module
from hexaleg.study.progress import INTERVAL, Progress


class Clock:
    """Seconds that pass only when the test says so."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_lines_come_at_most_every_interval_with_done_total_and_time_left(monkeypatch):
    monkeypatch.setattr(progress_module, "INTERVAL", 5.0)
    clock, stream = Clock(), io.StringIO()
    with Progress(1600, done=100, stream=stream, clock=clock) as shown:
        clock.now += 1.0
        shown.update(8)  # too soon for a line
        clock.now += 5.0
        shown.update(12)  # 20 designs in 6 s: 1480 more take 444 s
        clock.now += 2.0
        shown.update(8)  # too soon again; at the end: 1472 more take 1472 × 8 / 28 s
    assert stream.getvalue().splitlines() == [
        "hexaleg: 120/1600 designs (7.5 %), 6 s so far, about 7 min 24 s left",
        "hexaleg: 128/1600 designs (8.0 %), 8 s so far, about 7 min 1 s left",
    ]


def test_a_short_run_prints_nothing():
    clock, stream = Clock(), io.StringIO()
    with Progress(10, stream=stream, clock=clock) as shown:
        clock.now += INTERVAL / 10
        shown.update(10)
    assert stream.getvalue() == ""


def test_a_terminal_gets_a_bar_and_hidden_progress_nothing():
    terminal = Terminal()
    with Progress(10, stream=terminal) as shown:
        shown.update(5)
    assert "5/10" in terminal.getvalue() and "\r" in terminal.getvalue()
    quiet = Terminal()
    with Progress(10, show=False, stream=quiet) as shown:
        shown.update(10)
    assert quiet.getvalue() == ""


@pytest.mark.parametrize(
    ("seconds", "text"), [(0.2, "1 s"), (59, "59 s"), (61, "1 min 1 s"), (7300, "2 h 1 min")]
)
def test_durations_read_as_a_person_would_say_them(seconds, text):
    assert progress_module._duration(seconds) == text


def test_a_study_off_a_terminal_prints_progress_lines(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(progress_module, "INTERVAL", 0.0)  # every task finished: a line
    spec = StudySpec((0.1,), (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.75, 0.8, 0.85))
    run_study(spec, tmp_path / "s", executor=ThreadPoolExecutor(1))
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("hexaleg: 8/9 designs (88.9 %), ") and "left" in lines[0]
    assert lines[-1].startswith("hexaleg: 9/9 designs (100.0 %), ") and "left" not in lines[-1]


# The CLI in a child process whose progress lines are due after every finished design
# (INTERVAL 0): a fast machine finishes the grid before the usual 5 s and prints none.
EVERY_DESIGN_A_LINE = (
    "import sys; import hexaleg.study.progress as p; p.INTERVAL = 0.0; "
    "from hexaleg.cli import main; sys.exit(main())"
)


@pytest.mark.slow  # a study run as the CLI, its stderr a file
def test_the_cli_shows_lines_not_a_bar_when_stderr_is_a_file(tmp_path):
    log = tmp_path / "log"
    argv = [sys.executable, "-c", EVERY_DESIGN_A_LINE, "study", "--l1-ratios", "0.1", "0.2"]
    argv += ["--l3-points", "300", "--workers", "2", "-o", str(tmp_path / "s")]
    with log.open("w") as err:
        assert (
            subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=err, timeout=900).returncode == 0
        )
    lines = [line for line in log.read_text().splitlines() if "designs (" in line]
    assert lines and lines[-1].startswith("hexaleg: 600/600 designs (100.0 %)")
    assert "\r" not in log.read_text()


def test_the_report_shows_progress_as_a_study_naming_the_step(capsys, monkeypatch):
    """Off a terminal the report prints the study's lines (not nothing), with its step."""
    from dataclasses import dataclass

    from hexaleg import HexapodDesign
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.output.report.part import Part, compute_parts

    @dataclass(frozen=True)
    class First:
        value: int

    @dataclass(frozen=True)
    class Second:
        value: int

    monkeypatch.setattr(progress_module, "INTERVAL", 0.0)  # every step finished: a line
    parts = [
        Part(First, lambda data: First(1), lambda data: None, step="first step"),
        Part(Second, lambda data: Second(2), lambda data: None, needs=(First,), step="second"),
    ]
    data = compute_parts(HexapodDesign(), ReportOptions(), parts)
    assert data[Second].value == 2
    lines = capsys.readouterr().err.splitlines()
    assert [line.split(",")[0] for line in lines] == [
        "hexaleg: 0/3 steps (0.0 %)",
        "hexaleg: 1/3 steps (33.3 %)",
        "hexaleg: 2/3 steps (66.7 %)",
        "hexaleg: 3/3 steps (100.0 %)",
    ]
    assert [line.rsplit("now: ", 1)[-1] for line in lines[:3]] == [
        "model and URDF",
        "first step",
        "second",
    ]
    assert "now:" not in lines[3]
    compute_parts(HexapodDesign(), ReportOptions(progress=False), parts)
    assert capsys.readouterr().err == ""
