"""Output safety, case by case: nothing of the user's lost or overwritten, nothing hung.

Each row of :data:`CASES` is a folder as a user left it, a command (or the API call under
it), and the one line the command must end with (exit status 2); every file that was
there is then byte for byte as it was, and nothing new is left — unless the row says
what the command must make instead. The runs happen in a thread with a deadline, so a
command that waits on a FIFO fails the test instead of hanging it.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from conftest import run_cli

from hexaleg._folders import MARKER, replace_folder
from hexaleg._io import write_text
from hexaleg.exceptions import HexalegError
from hexaleg.study.search_journal import Journal

FIFO = object()
"""A file's content in :attr:`Case.files` that makes it a FIFO instead."""
HEADER = {"a": 1}
"""The fingerprint of the decide journals the API rows open."""
DECIDE_HEADER = json.dumps({"decide": HEADER}) + "\n"
FIGURES = {"up/gait_feet.png": "the user's own figure", "up/notes.txt": "notes"}
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

    """

    name: str
    files: dict[str, object]
    run: list[str] | Callable[[], object]
    message: str
    made: dict[str, str] = field(default_factory=dict)


def _decide_journal(path: str, resume: bool) -> Callable[[], object]:
    def run() -> None:
        with Journal(path, HEADER, resume):
            pass

    return run


def _causes(value: object) -> str:
    row = {"search": "s", "x": [0.1], "values": {"fb": 0.1}, "causes": value, "error": ""}
    return DECIDE_HEADER + json.dumps(row) + "\n"


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
        else:
            path.write_text(str(content))


def _snapshot(folder: Path) -> dict[str, object]:
    """Every entry below ``folder``: a file's bytes, FIFO or folder."""
    found: dict[str, object] = {}
    for path in sorted(folder.rglob("*")):
        name = path.relative_to(folder).as_posix()
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


def _run(case: Case) -> tuple[int, str]:
    if callable(case.run):
        call = case.run
        outcome = _within_deadline(call)
        if isinstance(outcome, HexalegError):
            return 2, str(outcome) + "\n"
        if isinstance(outcome, BaseException):
            raise outcome
        return 0, ""
    argv = case.run
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = _within_deadline(lambda: run_cli(argv))
    assert isinstance(status, int), status
    return status, err.getvalue()


@pytest.mark.parametrize("case", CASES, ids=[case.name for case in CASES])
def test_a_fuzz_case_loses_nothing_and_ends_in_one_line(tmp_path, monkeypatch, case):
    monkeypatch.chdir(tmp_path)
    _lay_out(tmp_path, case.files)
    before = _snapshot(tmp_path)
    status, err = _run(case)
    after = _snapshot(tmp_path)
    if case.message:
        assert status == 2 and err.count("\n") == 1 and case.message in err, err
        assert "Traceback" not in err and "staging" not in err
        assert after == before
        return
    assert status == 0, err
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
