"""Output folders: replaced only when hexaleg wrote them, swapped in whole, locked while in use."""

from __future__ import annotations

import json
import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import run_cli

from hexaleg._folders import (
    LOCK,
    MARKER,
    MARKER_FORMAT,
    check_replaceable_folder,
    claim_folder,
    lock_folder,
    recover_interrupted_swap,
    replace_folder,
    write_marker,
)
from hexaleg._io import current_umask
from hexaleg.exceptions import HexalegError


def _dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait(timeout=60)
    return process.pid


def _entries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def _write_report(target: Path, files: dict[str, str]) -> None:
    with replace_folder(target, "report") as staging:
        for name, text in files.items():
            (staging / name).parent.mkdir(parents=True, exist_ok=True)
            (staging / name).write_text(text)


def test_report_never_deletes_a_folder_hexaleg_did_not_write(tmp_path, capsys, monkeypatch):
    """The user's notes.txt and src/ beside a report.md of their own."""
    from hexaleg.output import report

    docs = tmp_path / "docs"
    (docs / "src").mkdir(parents=True)
    (docs / "report.md").write_text("x")
    (docs / "notes.txt").write_text("n")
    monkeypatch.setattr(report, "compute_report", lambda *a: pytest.fail("computed first"))
    assert run_cli(["report", "-o", str(docs)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "notes.txt, report.md, src" in err
    assert _entries(docs) == ["notes.txt", "report.md", "src"]
    assert (docs / "notes.txt").read_text() == "n"


def test_a_new_folder_is_marked_with_its_files_and_a_normal_mode(tmp_path):
    _write_report(tmp_path / "r", {"report.md": "a", "study/rows.jsonl": "b"})
    marker = json.loads((tmp_path / "r" / MARKER).read_text())
    assert marker["written_by"] == "hexaleg" and marker["kind"] == "report"
    assert marker["format"] == MARKER_FORMAT
    assert marker["files"] == ["report.md", "study/rows.jsonl"]
    assert stat.S_IMODE((tmp_path / "r").stat().st_mode) == 0o777 & ~current_umask()
    assert _entries(tmp_path) == ["r"]


def test_a_folder_hexaleg_wrote_is_replaced_whole_keeping_its_mode(tmp_path):
    target = tmp_path / "r"
    _write_report(target, {"report.md": "old", "old-only.csv": "gone"})
    target.chmod(0o750)
    _write_report(target, {"report.md": "new"})
    assert _entries(target) == [MARKER, "report.md"]
    assert (target / "report.md").read_text() == "new"
    assert stat.S_IMODE(target.stat().st_mode) == 0o750
    assert _entries(tmp_path) == ["r"]  # no staging, no parked folder


def test_an_empty_folder_is_replaced(tmp_path):
    (tmp_path / "r").mkdir()
    _write_report(tmp_path / "r", {"report.md": "new"})
    assert _entries(tmp_path / "r") == [MARKER, "report.md"]


STUDY_MARKER = {"written_by": "hexaleg", "kind": "study", "format": 1}


@pytest.mark.parametrize(
    ("change", "named"),
    [
        (lambda r: (r / "notes.txt").write_text("mine"), "notes.txt"),
        (lambda r: (r / "drafts").mkdir(), "drafts"),
        (lambda r: (r / MARKER).write_text(json.dumps(STUDY_MARKER)), "report.md"),
        (lambda r: (r / MARKER).write_text("not json"), MARKER),
    ],
)  # fmt: skip
def test_a_report_folder_with_anything_hexaleg_did_not_write_is_refused(tmp_path, change, named):
    target = tmp_path / "r"
    _write_report(target, {"report.md": "old"})
    change(target)
    before = {p: p.stat().st_mtime_ns for p in target.rglob("*")}
    with pytest.raises(HexalegError, match="hexaleg replaces only what it wrote") as caught:
        _write_report(target, {"report.md": "new"})
    assert named in str(caught.value)
    assert {p: p.stat().st_mtime_ns for p in target.rglob("*")} == before
    assert _entries(tmp_path) == ["r"]


def test_a_file_added_while_computing_is_seen_before_the_swap(tmp_path):
    target = tmp_path / "r"
    _write_report(target, {"report.md": "old"})
    with pytest.raises(HexalegError, match=r"notes\.txt"):
        with replace_folder(target, "report") as staging:
            (staging / "report.md").write_text("new")
            (target / "notes.txt").write_text("written meanwhile")
    assert (target / "notes.txt").exists() and (target / "report.md").read_text() == "old"
    assert _entries(tmp_path) == ["r"]


def test_a_folder_from_a_newer_hexaleg_is_refused(tmp_path):
    (tmp_path / "r").mkdir()
    record = {"written_by": "hexaleg", "kind": "report", "format": MARKER_FORMAT + 1}
    (tmp_path / "r" / MARKER).write_text(json.dumps(record))
    with pytest.raises(HexalegError, match="newer hexaleg"):
        check_replaceable_folder(tmp_path / "r", "report")


def test_an_error_while_writing_leaves_the_old_folder(tmp_path):
    target = tmp_path / "r"
    _write_report(target, {"report.md": "old"})
    with pytest.raises(ZeroDivisionError):
        with replace_folder(target, "report") as staging:
            (staging / "report.md").write_text("half")
            raise ZeroDivisionError
    assert (target / "report.md").read_text() == "old" and _entries(tmp_path) == ["r"]


@pytest.mark.parametrize("output", [".", "..", ""])
def test_the_current_folder_its_parents_and_nothing_are_refused(tmp_path, monkeypatch, output):
    (tmp_path / "here").mkdir()
    monkeypatch.chdir(tmp_path / "here")
    with pytest.raises(HexalegError, match=r"the folder you are in|an empty path"):
        check_replaceable_folder(output, "report")


def test_an_interrupted_swap_puts_the_old_folder_back(tmp_path):
    """Killed between parking the old folder and renaming the new."""
    dead = _dead_pid()
    target = tmp_path / "r"
    parked = tmp_path / f".r.parked-{dead}.abc"
    parked.mkdir()
    (parked / "report.md").write_text("the previous report")
    write_marker(parked, "report", ["report.md"])  # a parked folder is a report hexaleg wrote
    staging = tmp_path / f".r.staging-{dead}.def"
    staging.mkdir()
    live = tmp_path / f".r.staging-{os.getpid()}.ghi"
    live.mkdir()
    recover_interrupted_swap(target)
    assert (target / "report.md").read_text() == "the previous report"
    assert _entries(tmp_path) == sorted(["r", live.name])


def test_a_staging_folder_killed_while_writing_its_marker_is_removed(tmp_path):
    """The marker is the first file a staging folder gets: a kill during its write leaves only
    the marker's temporary file, which is hexaleg's; beside a user's file it is not."""
    dead = _dead_pid()
    torn = f".{MARKER}.tmp-{dead}.xyz"  # as hexaleg names a temporary file of the marker
    staging = tmp_path / f".r.staging-{dead}.abc"
    staging.mkdir()
    (staging / torn).write_text('{"written_by"')
    mine = tmp_path / f".r.staging-{dead}.mine"
    mine.mkdir()
    (mine / torn).write_text("")
    (mine / "data.txt").write_text("the user's")
    recover_interrupted_swap(tmp_path / "r")
    assert _entries(tmp_path) == [mine.name]
    assert (mine / "data.txt").read_text() == "the user's"


def test_a_parked_folder_is_removed_once_its_swap_has_completed(tmp_path):
    parked = tmp_path / f".r.parked-{_dead_pid()}.abc"
    parked.mkdir()
    (tmp_path / "r").mkdir()
    (tmp_path / "r" / "report.md").write_text("the new report")
    recover_interrupted_swap(tmp_path / "r")
    assert _entries(tmp_path) == ["r"]
    assert (tmp_path / "r" / "report.md").read_text() == "the new report"


def test_a_study_folder_is_claimed_only_when_new_empty_or_marked(tmp_path):
    assert claim_folder(tmp_path / "s", "study") == (tmp_path / "s").resolve()
    assert json.loads((tmp_path / "s" / MARKER).read_text())["kind"] == "study"
    (tmp_path / "s" / "rows.jsonl").write_text("")
    claim_folder(tmp_path / "s", "study")  # marked: accepted again
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("n")
    with pytest.raises(HexalegError, match="not a hexaleg study folder"):
        claim_folder(tmp_path / "mine", "study")
    assert _entries(tmp_path / "mine") == ["notes.txt"]
    with pytest.raises(HexalegError, match="is a file"):
        claim_folder(tmp_path / "mine" / "notes.txt", "study")


HOLDER = """
import os, sys, time
from pathlib import Path
from hexaleg._folders import lock_folder
with lock_folder(Path(sys.argv[1]), "study"):
    if os.fork() == 0:  # a worker forked while the lock is held outlives its parent
        time.sleep(600)
        os._exit(0)
    print("locked", flush=True)
    time.sleep(600)
"""


def test_a_held_folder_is_refused_naming_the_holder_and_freed_when_it_dies(tmp_path):
    holder = subprocess.Popen(
        [sys.executable, "-c", HOLDER, str(tmp_path)],
        stdout=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        assert holder.stdout.readline() == "locked\n"
        with pytest.raises(HexalegError) as caught:
            with lock_folder(tmp_path, "study"):
                pass
        assert f"in use by another hexaleg study (pid {holder.pid})" in str(caught.value)
    finally:
        os.kill(holder.pid, signal.SIGKILL)  # the holder alone: its forked child lives on
        holder.wait(timeout=30)
    try:
        deadline = time.monotonic() + 30
        while True:  # the lock goes with its holder, not with the forked child
            try:
                with lock_folder(tmp_path, "study"):
                    break
            except HexalegError:
                assert time.monotonic() < deadline, "the lock outlived its holder"
                time.sleep(0.05)
        assert (tmp_path / LOCK).read_text() == f"{os.getpid()}\n"
    finally:
        os.killpg(holder.pid, signal.SIGKILL)


def test_two_runs_in_one_process_are_told_apart(tmp_path):
    with lock_folder(tmp_path, "study"):
        with pytest.raises(HexalegError, match=f"pid {os.getpid()}"):
            with lock_folder(tmp_path, "study"):
                pass
    with lock_folder(tmp_path, "study"):  # released
        pass


def test_missing_parent_folders_are_made(tmp_path):
    _write_report(tmp_path / "a" / "b" / "r", {"report.md": "new"})
    assert _entries(tmp_path / "a" / "b") == ["r"]
