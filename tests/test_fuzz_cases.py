"""Output safety, case by case: nothing of the user's lost or overwritten, nothing hung.

Each row of :data:`CASES` is a folder as a user left it, a command (or the API call under
it), and the one line the command must end with (exit status 2); every file that was
there is then byte for byte as it was, and nothing new is left — unless the row says
what the command must make instead. The runs happen in a thread with a deadline, so a
command that waits on a FIFO fails the test instead of hanging it.
"""

from __future__ import annotations

import contextlib
import errno
import io
import json
import math
import os
import re
import subprocess
import sys
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from conftest import run_cli

import hexaleg
from hexaleg._folders import MARKER, replace_folder
from hexaleg._io import write_text
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.statics.ground import Ground
from hexaleg.study import optimize
from hexaleg.study import progress as progress_module
from hexaleg.study.optimize import SearchSettings
from hexaleg.study.search_journal import Journal
from hexaleg.study.sensitivity import sensitivity_table

FIFO = object()
"""A file's content in :attr:`Case.files` that makes it a FIFO instead."""


@dataclass(frozen=True)
class Sparse:
    """A file's content in :attr:`Case.files`: ``size`` bytes of a hole (no disk used)."""

    size: int


SNAPSHOT_BYTES = 2**20
"""A larger file is compared by its size and time of change, never read whole [bytes]."""
HEADER = {"a": 1}
"""The fingerprint of the decide journals the API rows open."""
DECIDE_HEADER = json.dumps({"decide": HEADER}) + "\n"
STANCE = {"theta2": (-math.pi / 6, math.pi / 6), "theta3": (-3 * math.pi / 4, -math.pi / 12)}
"""The paper's stance limits of the hip and knee [rad] (the ADAMS study)."""
MISSPELLED = "l1 = 0.2\n[requirements]\npaylod = 3\n"
FIGURES = {"up/gait_feet.png": "the user's own figure", "up/notes.txt": "notes"}
DESIGN_FILE_COMMANDS = [
    ["gait", "--csv", "g.csv"], ["urdf", "-o", "r.urdf"], ["workspace", "--plot", "p"],
    ["decide"], ["design", "show"],
]  # fmt: skip
"""Commands that read a design file (each refuses a bad one before writing anything)."""
UNWALKABLE = ["--l1", "0.1", "--l2", "0.15", "--l3", "0.4"]
"""A leg whose max stride (by its root's limit) is short of the default gait's 0.3 m."""
PLOT_COMMANDS = [
    ["gait", "--samples", "12"],
    ["workspace", "--samples", "10"],
    ["manipulability"],
    ["flexibility"],
    ["loads"],
]


@dataclass(frozen=True)
class Case:
    """A fuzz case: the folder before, what runs, the error it must end with.

    Attributes:
        name: The case, as the fuzz run found it.
        files: Path → content (text, or :data:`FIFO`) in the folder before the run.
        run: ``hexaleg`` arguments, or a call of the API (raising on refusal).
        message: What the one-line error says; empty when the command must succeed.
        made: Path → what it must then hold (the command's own output), checked exactly.
        says: What its standard output must say, when it succeeds.
        never: What neither its output nor its error may hold (``inf``, a Python error);
            a ``--json`` answer must be strict JSON (no NaN, no Infinity).

    """

    name: str
    files: dict[str, object]
    run: list[str] | Callable[[], object]
    message: str
    made: dict[str, str] = field(default_factory=dict)
    says: str = ""
    never: tuple[str, ...] = ()


def _decide_journal(path: str, resume: bool) -> Callable[[], object]:
    def run() -> None:
        with Journal(path, HEADER, resume):
            pass

    return run


def _causes(value: object) -> str:
    row = {"search": "s", "x": [0.1], "values": {"fb": 0.1}, "causes": value, "error": ""}
    return DECIDE_HEADER + json.dumps(row) + "\n"


MOTORS = {
    "motors.toml": "".join(
        f'[actuators.{joint}]\ncatalog = "hd_cha_25a_100"\n' for joint in ("root", "hip", "knee")
    )
}
"""A design file with catalog motors and no battery."""
BATTERY = {"b.toml": "[battery]\ncapacity = 500\nspecific_energy = 150\n"}
"""A design file with a battery and no motors."""
FAR = {"far.toml": "[gait]\nstride = 1.2\n"}
"""A design file whose gait no foot reaches: its joint speeds would be unbounded."""
KRABY = str(Path(__file__).parent / "data" / "robots" / "kraby" / "hexapod.urdf")
ROBOT_TEXT = Path(KRABY).read_text()
"""A robot file's text, copied into the folder a row runs in."""
NOT_NUMBERS = (r"\binf\b", r"\bnan\b", r"\bInfinity\b", r"\bNaN\b", "Traceback", "Error:")
"""Patterns of what no answer holds: a number that is none, a Python error."""

CASES = [
    # data lost or overwritten
    Case("a text file as --journal, --resume", {"notes.txt": "notes\nlast line"},
         ["decide", "--journal", "notes.txt", "--resume"], "is not a hexaleg decision journal"),
    Case("a one-line file without its newline", {"one.txt": "last line"},
         ["decide", "--journal", "one.txt", "--resume"], "is not a hexaleg decision journal"),
    Case("a one-line file, without --resume", {"one.txt": "last line"},
         ["decide", "--journal", "one.txt"], "is not a hexaleg decision journal"),
    Case("a report's report.md as --journal", {"r/report.md": "# Report\n\ntext"},
         ["decide", "--journal", "r/report.md", "--resume"], "is not a hexaleg decision journal"),
    Case("a user's folder named like hexaleg's staging, its pid dead",
         {".conc.staging-999999.mine/data.txt": "the user's data",
          ".conc.parked-999999.mine/data.txt": "more of it"},
         lambda: _report("conc"), "", {"conc/report.md": "new"}),
    *(Case(f"{command[0]} --plot into the user's folder", FIGURES,
           [*command, "--plot", "up"], "holds files hexaleg did not write (gait_feet.png")
      for command in PLOT_COMMANDS),
    Case("two outputs on one path", {}, ["gait", "--csv", "same.out", "--html", "same.out"],
         "--csv and --html both write to same.out"),
    Case("a file inside the plot folder", {}, ["gait", "--plot", "p", "--csv", "p/x.csv"],
         "--plot and --csv both write to p/x.csv"),
    Case("report -o -", {}, ["report", "-o", "-"], "- is standard output, which cannot hold"),
    Case("study -o -", {}, ["study", "-o", "-"], "- is standard output, which cannot hold"),
    Case("--plot -", {}, ["workspace", "--plot", "-"], "- is standard output, which cannot"),
    Case("--journal -", {}, ["decide", "--journal", "-"], "it must be a file"),
    *(Case(f"{' '.join(argv)}: '-' is standard output, no file named '-'", {}, argv, "")
      for argv in (["gait", "--samples", "12", "--csv", "-"], ["urdf", "-o", "-"])),
    # the input robot or design file is never an output
    *(Case(f"urdf --urdf r.urdf -o {target}", {"r.urdf": ROBOT_TEXT, "sub/keep": "k"},
           ["urdf", "--urdf", "r.urdf", "--l2", "0.08", "-o", target],
           f"-o {target} is the robot file read (--urdf r.urdf): write it elsewhere")
      for target in ("r.urdf", "sub/../r.urdf", "./r.urdf")),
    Case("urdf --design d.toml -o d.toml", {"d.toml": "l1 = 0.2\n"},
         ["urdf", "--design", "d.toml", "-o", "d.toml"],
         "-o d.toml is the design file read (--design d.toml): write it elsewhere"),
    Case("urdf --design with [robot] urdf, -o that robot file",
         {"r.urdf": ROBOT_TEXT, "d.toml": '[robot]\nurdf = "r.urdf"\n'},
         ["urdf", "--design", "d.toml", "-o", "r.urdf"],
         "-o r.urdf is the robot file read"),
    # hangs
    Case("a FIFO as --journal, --resume", {"j.jsonl": FIFO},
         ["decide", "--journal", "j.jsonl", "--resume"], "j.jsonl is not a regular file"),
    Case("a FIFO as --journal", {"j.jsonl": FIFO},
         ["decide", "--journal", "j.jsonl"], "j.jsonl is not a regular file"),
    *(Case(f"a FIFO as the marker of {' '.join(argv)}", {"d/.hexaleg.json": FIFO},
           argv, ".hexaleg.json is not a regular file")
      for argv in (["report", "-o", "d"], ["study", "-o", "d"], ["study", "-o", "d", "--resume"],
                   ["workspace", "--plot", "d"])),
    Case("a FIFO as a study's lock", {"d/.hexaleg.json": json.dumps(
        {"written_by": "hexaleg", "kind": "study", "format": 1}), "d/.hexaleg.lock": FIFO},
         ["study", "-o", "d"], ".hexaleg.lock is not a regular file"),
    # journals and markers
    *(Case(f'a decide journal line with "causes": {value}', {"j.jsonl": _causes(value)},
           _decide_journal("j.jsonl", resume=True), "j.jsonl: line 2 is corrupt")
      for value in ("[]", "null", '{"fb": 5}', '{"fb": {"kind": "nonsense"}}')),
    Case('a report marker with "files": 5', {"r/.hexaleg.json": json.dumps(
        {"written_by": "hexaleg", "kind": "report", "format": 1, "files": 5})},
         ["report", "-o", "r"], '.hexaleg.json is corrupt (its "files" is not a list'),
    Case("a torn header, --resume", {"j.jsonl": DECIDE_HEADER[:9]},
         _decide_journal("j.jsonl", resume=True), "run without --resume to start it again"),
    Case("a torn header, a new run starts it again", {"j.jsonl": DECIDE_HEADER[:9]},
         _decide_journal("j.jsonl", resume=False), "", {"j.jsonl": DECIDE_HEADER}),
    Case("an empty journal, a new run starts it", {"j.jsonl": ""},
         _decide_journal("j.jsonl", resume=False), "", {"j.jsonl": DECIDE_HEADER}),
    Case("--journal d/nothere/", {"d/keep": "k"}, ["decide", "--journal", "d/nothere/"],
         "d/nothere/ ends in '/', which names a folder"),
    Case("missing parent folders of a journal are made", {},
         _decide_journal("new/deeper/j.jsonl", resume=False), "",
         {"new/deeper/j.jsonl": DECIDE_HEADER}),
    Case('--journal ""', {}, ["decide", "--journal", ""], "--journal is empty: name a file"),
    # decide: bounds, budgets and the options the user typed
    *(Case(f"decide --free {free}", {}, ["decide", "--free", free],
           f"--free {free.split('=')[0]} = '{free.split('=')[1]}' is not valid: bounds within "
           f"[{STANCE[free[:6]][0]:.4g}, {STANCE[free[:6]][1]:.4g}] [rad] (the design's stance")
      for free in ("theta3=-0.2:-0.1", "theta3=0.5:1", "theta2=0.6:1", "theta2=-10:10")),
    Case("decide --free l1 beyond --leg-length", {},
         ["decide", "--free", "l1=0.5:0.9", "--leg-length", "0.3"],
         "--free l1 = '0.5:0.9' is not valid: bounds within [0.001, 0.3] [m] (l1 + l2 + l3 at"),
    Case("decide --free l1 beyond the design's leg length", {}, ["decide", "--free", "l1=50:100"],
         "--free l1 = '50:100' is not valid: bounds within [0.001, 1] [m]"),
    Case("decide --free l1 given twice", {},
         ["decide", "--free", "l1=0.1:0.2", "--free", "l1=0.1:0.3"],
         "--free = 'l1=0.1:0.3' is not valid: l1 is given twice"),
    Case("decide --free body_height=50:100: no design can stand", {},
         ["decide", "--fixed-posture", "--free", "body_height=50:100", "--evaluations", "80",
          "--workers", "1"],
         "no design within the search bounds (l1 0.02:1, l2 0.02:1, l3 0.02:1, body_height "
         "50:100) can be measured: nominal_angles"),
    Case("decide --evaluations 48 with four free variables", {},
         ["decide", "--fixed-posture", "--free", "body_width=0.4:0.8", "--evaluations", "48"],
         "--evaluations = 48 is not valid: whole generations of 40 designs"),
    Case("decide --evaluations 48 with three free lengths", {},
         ["decide", "--fixed-posture", "--evaluations", "48"],
         "--evaluations = 48 is not valid: whole generations of 30 designs (10 a free variable, "
         "at least 24) for 3 free variables, at least two, at most 100000: e.g. 60 or 90"),
    Case("decide --evaluations 70 with the posture free", {},
         ["decide", "--free-posture", "--evaluations", "70"],
         "whole generations of 50 designs (10 a free variable, at least 24) for 5 free"),
    Case("decide --evaluations 1000000", {}, ["decide", "--evaluations", "1000000"],
         "argument --evaluations: 1000000 is not valid: must be in 48..100000"),
    Case("decide --leg-length 200", {}, ["decide", "--leg-length", "200"],
         "--leg-length = 200 is not valid: must lie in [0.003, 100] [m]"),
    # decide: what a design cannot measure is refused before any search
    *(Case(f"decide {' '.join(argv).replace(KRABY, 'kraby')} without [battery]", files,
           ["decide", *argv], "--range-km = 5 is not valid: range needs a [battery] table" + more)
      for argv, files, more in (
          (["--range-km", "5"], {}, " and an [actuators] table in the design file (or --choose"),
          (["--urdf", KRABY, "--range-km", "5"], {}, " and an [actuators] table"),
          (["--range-km", "5", "--choose-actuators"], {}, " in the design file: the distance"),
          (["--design", "motors.toml", "--range-km", "5"], MOTORS, " in the design file"))),
    Case("report --range-km 5 without [battery]", {}, ["report", "-o", "r", "--range-km", "5"],
         "--range-km = 5 is not valid: range needs a [battery] table"),
    Case("decide --range-km 5 without [actuators]", BATTERY, ["decide", "--design", "b.toml",
         "--range-km", "5"], "--range-km = 5 is not valid: range needs an [actuators] table"),
    Case("[requirements] range_km without [battery]", {"r.toml": "[requirements]\nrange_km = 5\n"},
         ["decide", "--design", "r.toml"], "range_km = 5 is not valid: range needs a [battery]"),
    Case("decide --continuous-margin 0.8 without [actuators]", {},
         ["decide", "--continuous-margin", "0.8"],
         "--continuous-margin = 0.8 is not valid: continuous load needs an [actuators] table"),
    Case("decide --maximize battery_range without [battery]", {},
         ["decide", "--maximize", "battery_range"],
         "--maximize = 'battery_range' is not valid: range needs a [battery] table"),
    # friction, declared once
    *(Case(f"{command} --friction {value}", {}, [command, "--friction", value, *more],
           f"--friction = {shown} is not valid: {allowed}")
      for command, more in (("gait", ["--csv", "g.csv"]), ("loads", ["--plot", "p"]))
      for value, shown, allowed in (
          ("nan", "nan", "must be finite"), ("inf", "inf", "must be finite"),
          ("-1", "-1", "must lie in [0.001, 10] [-]"), ("0", "0", "must lie in [0.001, 10]"),
          ("1e308", "1e+308", "must lie in [0.001, 10] [-]"))),
    # a design file read the same way by every command
    *(Case(f"{argv[0]} --design with a misspelled requirement", {"d.toml": MISSPELLED},
           [*argv, "--design", "d.toml"],
           "d.toml, line 3: requirements.paylod = 3 is not valid: unknown requirement; did you "
           "mean 'payload'?")
      for argv in DESIGN_FILE_COMMANDS),
    *(Case(f"{argv[0]} --design with a requirement as text",
           {"d.toml": "[requirements]\npayload = 'x'\n"}, [*argv, "--design", "d.toml"],
           "d.toml, line 2: requirements.payload = 'x' is not valid: must be a real number")
      for argv in DESIGN_FILE_COMMANDS),
    # wrong answers: a gait that tips over is not feasible; what gait refuses, view refuses
    Case("gait --payload 30 --payload-at 100 100 100: the ZMP leaves the feet", {},
         ["gait", "--samples", "24", "--payload", "30", "--payload-at", "100", "100", "100"], "",
         says="no: t = 0.000 s: ZMP leaves the support polygon (min ZMP margin -"),
    *(Case(f"{' '.join(argv)} of a design that cannot walk the default gait", {},
           [*argv, *UNWALKABLE], "stride = 0.3 is not valid: must be at most ")
      for argv in (["gait", "--html", "g.html"], ["view", "--gait", "--html", "v.html"],
                   ["view", "--gait", "--port", "1"])),
    # the API: hexaleg's own error, naming the argument
    *(Case(f"{name}(None)", {}, lambda name=name: getattr(hexaleg, name)(None),
           f"design = None is not valid: must be a {kind}")
      for name, kind in (("analyze_loads", "HexapodDesign"), ("analyze_gait", "HexapodDesign"),
                         ("decide", "Robot or a HexapodDesign"))),
    *(Case(f"analyze_gait({name}={value})", {},
           lambda name=name, value=value: hexaleg.analyze_gait(HexapodDesign(), **{name: value}),
           f"{name} = {value:g} is not valid: {allowed}")
      for name, value, allowed in (
          ("gravity", 0.0, "must lie in [0.01, 1000] [m/s²]"),
          ("gravity", math.nan, "must be finite"), ("gravity", -9.81, "must lie in [0.01, 1000]"),
          ("safety_factor", 0.5, "must lie in [1, 100] [-]"),
          ("safety_factor", math.nan, "must be finite"))),
    *(Case(f"Ground({name}={value})", {},
           lambda name=name, value=value: hexaleg.analyze_gait(
               HexapodDesign(), ground=Ground(**{name: value})),
           f"{name} = {value:g} is not valid: {allowed}")
      for name, value, allowed in (
          ("friction", math.nan, "must be finite"),
          ("friction", 0.0, "must lie in [0.001, 10] [-]"),
          ("slope", 1.1, "must lie in [-1.0472, 1.0472] [rad]"),
          ("slope", math.nan, "must be finite"))),
    Case("analyze_loads(friction=nan)", {},
         lambda: hexaleg.analyze_loads(HexapodDesign(), friction=math.nan),
         "friction = nan is not valid: must be finite"),
    Case("Requirements.from_table({1: 2})", {}, lambda: Requirements.from_table({1: 2}),
         "requirements.1 = 2 is not valid: keys must be requirement names (text)"),
    Case("decide(resume=True) without a journal", {},
         lambda: hexaleg.decide(HexapodDesign(), resume=True),
         "resume = True is not valid: continues a journal: give journal=FILE"),
]  # fmt: skip

SLOW_CASES = [  # each a whole decision (seconds); a robot walks its own default gait, sized
    # to it, so Kraby too is given the gait it cannot walk (the reproducer walked ours)
    *(Case(f"decide {name} --walking-payload 0.05{json}: never inf", FAR,
           [*argv, "--walking-payload", "0.05", "--evaluations", "150", "--workers", "1",
            *json.split()], "", says=says, never=NOT_NUMBERS)
      for name, argv in (("far.toml", ["decide", "--design", "far.toml"]),
                         ("kraby", ["decide", "--urdf", KRABY, "--design", "far.toml"]))
      for json, says in (("", "cannot walk it"), (" --json", '"walking_violation": "t = '))),
]  # fmt: skip

SIMULATE_CASES = [
    Case("simulate --l1 100 --l2 100 --l3 100", {},
         ["simulate", "--l1", "100", "--l2", "100", "--l3", "100", "--html", "s.html"],
         "l1, l2, l3 = (100, 100, 100) is not valid: too large to simulate"),
    Case("simulate --cycles 200 --period 1000", {},
         ["simulate", "--cycles", "200", "--period", "1000", "--html", "s.html"],
         "--cycles = 200 is not valid: cycles × period (1000 s, set by period or speed) must be "
         "at most 3600 s simulated: at most 3 at this period"),
    Case("simulate --friction 0", {}, ["simulate", "--friction", "0", "--html", "s.html"],
         "--friction = 0 is not valid: must lie in [0.001, 10] [-]"),
    Case("simulate_gait(None)", {}, lambda: hexaleg.simulate_gait(None),
         "design = None is not valid: must be a HexapodDesign"),
    # a payload far beyond the robot: the simulation diverges, says so, writes no log
    *(Case(f"simulate --urdf kraby --payload 10000{json}: diverged, said in one line", {},
           ["simulate", "--urdf", KRABY, "--stride", "0.05", "--step-height", "0.02",
            "--period", "1", "--cycles", "2", "--payload", "10000", *json.split()], "",
           says=says, never=(*never, *NOT_NUMBERS))
      for json, says, never in (("", "DIVERGED while walking, at t = ", (r"\bfell\b",)),
                                (" --json", '"diverged": "while walking, at t = ', ()))),
]  # fmt: skip


def _report(target: str) -> None:
    with replace_folder(target, "report") as staging:
        write_text(staging / "report.md", "new")


def _lay_out(folder: Path, files: dict[str, object]) -> None:
    for name, content in files.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if content is FIFO:
            os.mkfifo(path)
        elif isinstance(content, Sparse):
            with path.open("wb") as file:
                file.truncate(content.size)
        else:
            path.write_text(str(content))


def _snapshot(folder: Path) -> dict[str, object]:
    """Every entry below ``folder``: a file's bytes (a large one's size), FIFO or folder."""
    found: dict[str, object] = {}
    for path in sorted(folder.rglob("*")):
        name = path.relative_to(folder).as_posix()
        if path.is_file() and path.stat().st_size > SNAPSHOT_BYTES:
            found[name] = (path.stat().st_size, path.stat().st_mtime_ns)
        else:
            found[name] = path.read_bytes() if path.is_file() else "fifo" if path.is_fifo() else "/"
    return found


def _within_deadline(run: Callable[[], object], seconds: float = 120) -> object:
    """``run()``'s result or exception, failing if it has not returned in ``seconds``."""
    outcome: list[object] = []

    def target() -> None:
        try:
            outcome.append(run())
        except BaseException as err:  # handed to the test
            outcome.append(err)

    worker = threading.Thread(target=target, daemon=True)
    worker.start()
    worker.join(seconds)
    assert outcome, f"still running after {seconds} s (waiting on a FIFO?)"
    return outcome[0]


def _run(case: Case) -> tuple[int, str, str]:
    """The exit status, standard error and standard output of ``case``."""
    if callable(case.run):
        call = case.run
        outcome = _within_deadline(call)
        if isinstance(outcome, HexalegError):
            return 2, str(outcome) + "\n", ""
        if isinstance(outcome, BaseException):
            raise outcome
        return 0, "", ""
    argv = case.run
    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        status = _within_deadline(lambda: run_cli(argv))
    assert isinstance(status, int), status
    return status, err.getvalue(), out.getvalue()


@pytest.mark.parametrize(
    "case",
    [*CASES, *(pytest.param(case, marks=pytest.mark.slow) for case in SLOW_CASES)],
    ids=[case.name for case in (*CASES, *SLOW_CASES)],
)
def test_a_fuzz_case_loses_nothing_and_ends_in_one_line(tmp_path, monkeypatch, case):
    _check(case, tmp_path, monkeypatch)


@pytest.mark.parametrize("case", SIMULATE_CASES, ids=[case.name for case in SIMULATE_CASES])
def test_a_simulate_fuzz_case_ends_in_one_line(tmp_path, monkeypatch, case):
    pytest.importorskip("mujoco")
    _check(case, tmp_path, monkeypatch)


def _check(case: Case, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Run ``case`` in ``tmp_path``: its one-line error and nothing changed, or what it made."""
    monkeypatch.chdir(tmp_path)
    _lay_out(tmp_path, case.files)
    before = _snapshot(tmp_path)
    status, err, out = _run(case)
    after = _snapshot(tmp_path)
    if case.message:
        assert status == 2 and err.count("\n") == 1 and case.message in err, err
        assert "Traceback" not in err and "staging" not in err
        assert after == before
        return
    assert status == 0, err
    assert case.says in out, out
    assert not any(re.search(word, out + err) for word in case.never), out + err
    if not callable(case.run) and "--json" in case.run:
        json.loads(out, parse_constant=lambda word: pytest.fail(f"{word} in the JSON"))
    for name, content in case.made.items():
        assert after.pop(name) == content.encode()
    kept = {name: value for name, value in before.items() if name not in case.made}
    assert {k: v for k, v in after.items() if k in kept} == kept  # every file of the user's
    new = set(after) - set(kept)
    assert all(name in case.made or value == "/" or name.endswith(MARKER) for name, value in
               ((n, after[n]) for n in new)), new  # fmt: skip


LOCKED_JOURNAL = """
import sys, time
from hexaleg.study.search_journal import Journal
with Journal(sys.argv[1], {"a": 1}, resume=False):
    print("locked", flush=True)
    time.sleep(600)
"""


def test_a_second_decision_on_a_journal_in_use_is_refused_naming_the_first(tmp_path, capsys):
    journal = tmp_path / "j.jsonl"
    holder = subprocess.Popen(
        [sys.executable, "-c", LOCKED_JOURNAL, str(journal)], stdout=subprocess.PIPE, text=True
    )
    try:
        assert holder.stdout.readline() == "locked\n"
        before = journal.read_bytes()
        assert run_cli(["decide", "--journal", str(journal), "--resume"]) == 2
        with pytest.raises(
            HexalegError, match=f"in use by another hexaleg decide .pid {holder.pid}"
        ):
            Journal(journal, HEADER, resume=True)
    finally:
        holder.kill()
        holder.wait(timeout=30)
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"in use by another hexaleg decide (pid {holder.pid})" in err
    assert journal.read_bytes() == before
    with Journal(journal, HEADER, resume=True):  # free once its holder is gone
        pass


@pytest.mark.parametrize(
    ("code", "reason"), [(errno.ENOSPC, "No space left on device"), (errno.EROFS, "Read-only")]
)
def test_a_refused_write_names_the_users_target_and_the_systems_reason(
    tmp_path, monkeypatch, code, reason
):
    def refuse(fd: int) -> None:
        raise OSError(code, os.strerror(code))

    monkeypatch.setattr(os, "fsync", refuse)  # the data reaches no disk
    (tmp_path / "kept").mkdir()
    before = _snapshot(tmp_path)
    with pytest.raises(HexalegError) as file_error:
        write_text(tmp_path / "kept" / "out.txt", "text")
    with pytest.raises(HexalegError) as folder_error:
        _report(str(tmp_path / "conc"))
    monkeypatch.undo()
    assert str(file_error.value) == f"cannot write {tmp_path}/kept/out.txt: {os.strerror(code)}"
    assert str(folder_error.value) == f"cannot write report to {tmp_path}/conc: {os.strerror(code)}"
    assert reason in os.strerror(code)
    assert _snapshot(tmp_path) == before  # no temporary file, no staging folder left


def test_a_search_shows_its_progress_on_a_pipe_and_evaluates_what_is_asked(monkeypatch, capsys):
    monkeypatch.setattr(progress_module, "INTERVAL", 0.0)  # a line at every update
    asked: list[int] = []
    evaluate = optimize._Evaluator.__call__

    def counted(self, points):
        asked.append(len(points))
        return evaluate(self, points)

    monkeypatch.setattr(optimize._Evaluator, "__call__", counted)
    for free_posture, budget in ((False, 90), (True, 100)):
        asked.clear()
        with ThreadPoolExecutor(1) as here:
            result = hexaleg.decide(HexapodDesign(), free_posture=free_posture, executor=here,
                                    settings=SearchSettings(evaluations=budget))  # fmt: skip
        assert result.feasible and result.evaluations == budget
        assert sum(asked) == budget  # the designs the algorithm asked for, cached or not
        lines = capsys.readouterr().err.splitlines()
        assert len(lines) >= 2 and all(line.startswith("hexaleg: ") for line in lines)
        assert lines[-1].startswith(f"hexaleg: {budget}/{budget} designs (100.0 %), ")


def test_the_sensitivity_after_a_study_shows_its_own_progress_on_a_pipe(monkeypatch, capsys):
    monkeypatch.setattr(progress_module, "INTERVAL", 0.0)
    variants = [("narrow", {"body_width": 0.5}), ("wide", {"body_width": 0.7})]
    table = sensitivity_table((0.1,), (0.3, 0.4, 0.5), variants=variants)
    assert list(table["variant"]) == ["narrow", "wide"]
    lines = capsys.readouterr().err.splitlines()
    assert "hexaleg: 0/6 designs (0.0 %)" in lines[0] and "now: sensitivity, narrow" in lines[0]
    assert any("3/6 designs" in line and "now: sensitivity, wide" in line for line in lines)
    assert lines[-1].startswith("hexaleg: 6/6 designs (100.0 %)")


@pytest.mark.parametrize("command", ["loads", "gait", "simulate"])
def test_every_command_states_the_one_friction_range(command, capsys):
    assert run_cli([command, "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert text.count("friction coefficient between feet and ground, in [0.001, 10] [-]") == 1
    assert "(0, 10]" not in text and "[0, 10]" not in text


def test_view_gait_refuses_what_gait_refuses_in_the_same_words(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    lines = {}
    for argv in (["gait", "--html", "g.html"], ["view", "--gait", "--html", "v.html"]):
        assert run_cli([*argv, *UNWALKABLE]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1
        lines[argv[0]] = err.removeprefix(f"hexaleg {argv[0]}: error: ")
    assert lines["gait"] == lines["view"] and "max stride" in lines["gait"]
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("link", [os.link, os.symlink], ids=["hard link", "symbolic link"])
def test_the_input_robot_file_is_not_written_through_another_name(tmp_path, monkeypatch, link):
    monkeypatch.chdir(tmp_path)
    Path("r.urdf").write_text(ROBOT_TEXT)
    link("r.urdf", "other.urdf")
    before = _snapshot(tmp_path)
    status, err, _ = _run(Case("", {}, ["urdf", "--urdf", "r.urdf", "-o", "other.urdf"], "x"))
    assert status == 2 and err.count("\n") == 1
    assert "-o other.urdf is the robot file read (--urdf r.urdf)" in err
    assert _snapshot(tmp_path) == before
