"""A study's journal: torn tails cut, corrupt lines refused, full disks and second runs told."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pandas as pd
import pytest
from conftest import run_cli

from hexaleg._folders import MARKER, claim_folder
from hexaleg.design import l3_ratio_grid
from hexaleg.exceptions import HexalegError
from hexaleg.study import StudySpec, run_study
from hexaleg.study.journal import JOURNAL, append_rows, read_journal, start_journal

SPEC = StudySpec((0.1,), tuple(l3_ratio_grid(3)))
"""The smallest study worth resuming: three designs, as `study --l1-ratios 0.1 --l3-points 3`."""
CLI = ["study", "--l1-ratios", "0.1", "--l3-points", "3", "--workers", "1"]
ROW = {"l1_ratio": 0.1, "l3_ratio": 0.1, "fb": 0.2, "error": ""}
LAST = {**ROW, "l3_ratio": 0.75}


def _journal(folder: Path, *rows: dict | str) -> Path:
    """A journal of ``SPEC`` holding ``rows`` (a str is written as the line itself)."""
    claim_folder(folder, "study")
    lines = [json.dumps({"spec": SPEC.fingerprint()})]
    lines += [row if isinstance(row, str) else json.dumps(row) for row in rows]
    path = folder / JOURNAL
    path.write_text("".join(line + "\n" for line in lines))
    return path


def test_a_torn_last_line_is_cut_before_appending_so_a_second_resume_works(tmp_path):
    """The first resume must not append after half a line."""
    straight = run_study(SPEC, tmp_path / "straight", executor=ThreadPoolExecutor(1))
    whole = (tmp_path / "straight" / JOURNAL).read_text().splitlines()
    torn = _journal(tmp_path / "torn", *whole[1:2])
    torn.write_text(torn.read_text() + whole[2][:25])  # killed mid-write
    first = run_study(SPEC, tmp_path / "torn", executor=ThreadPoolExecutor(1), resume=True)
    lines = torn.read_text().splitlines()
    assert torn.read_text().endswith("\n") and len(lines) == 4
    assert all(isinstance(json.loads(line), dict) for line in lines)
    second = run_study(SPEC, tmp_path / "torn", executor=ThreadPoolExecutor(1), resume=True)
    pd.testing.assert_frame_equal(first, straight)
    pd.testing.assert_frame_equal(second, straight)


@pytest.mark.parametrize(
    "line",
    [
        "{}",
        "[1, 2]",
        "5",
        "null",
        '"text"',
        "{not json",
        json.dumps({"l1_ratio": 0.1, "error": ""}),  # no tibia ratio
        json.dumps({**ROW, "l1_ratio": "0.1"}),  # a string
        json.dumps({**ROW, "l3_ratio": 0.35}),  # not in the grid
        json.dumps({"l1_ratio": 0.1, "l3_ratio": 0.1}),  # no error column
        json.dumps({"spec": SPEC.fingerprint()}),  # a second header
    ],
)
def test_a_corrupt_line_is_named_and_refused(tmp_path, capsys, line):
    """No KeyError or TypeError, "line N is corrupt" and exit 2."""
    journal = _journal(tmp_path / "s", ROW, line, LAST)
    before = journal.read_bytes()
    with pytest.raises(HexalegError, match="line 3 is corrupt"):
        read_journal(journal, SPEC.fingerprint(), SPEC.keys())
    assert run_cli([*CLI, "-o", str(tmp_path / "s"), "--resume"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "line 3 is corrupt" in err
    assert journal.read_bytes() == before


@pytest.mark.parametrize("content", ["", '{"spec": {"l1_ratios": [0.1]'])
def test_a_journal_without_its_fingerprint_refuses_any_grid(tmp_path, content):
    claim_folder(tmp_path, "study")
    (tmp_path / JOURNAL).write_text(content)
    with pytest.raises(HexalegError, match="holds no study fingerprint"):
        start_journal(tmp_path, SPEC.fingerprint(), SPEC.keys(), resume=True)
    assert (tmp_path / JOURNAL).read_text() == content


def test_a_journal_of_other_options_is_refused(tmp_path):
    _journal(tmp_path, ROW)
    other = StudySpec((0.1,), (0.1, 0.4))
    with pytest.raises(HexalegError, match="other options"):
        start_journal(tmp_path, other.fingerprint(), other.keys(), resume=True)


def test_a_journal_that_is_not_a_file_is_refused_without_waiting(tmp_path):
    claim_folder(tmp_path, "study")
    os.mkfifo(tmp_path / JOURNAL)
    with pytest.raises(HexalegError, match="not a regular file"):
        start_journal(tmp_path, SPEC.fingerprint(), SPEC.keys(), resume=True)


def test_a_full_disk_while_journaling_is_one_error_and_no_half_line(tmp_path):
    journal = _journal(tmp_path, ROW)
    full = tmp_path / "full.jsonl"
    full.symlink_to("/dev/full")  # every write: "No space left on device"
    with pytest.raises(HexalegError) as caught:
        append_rows(full, [ROW])
    assert str(caught.value).count("\n") == 0
    assert "No space left on device" in str(caught.value) and "--resume" in str(caught.value)
    append_rows(journal, [LAST])
    assert read_journal(journal, SPEC.fingerprint(), SPEC.keys())[0].keys() == {
        (0.1, 0.1),
        (0.1, 0.75),
    }


@pytest.mark.slow  # a study run in a private mount namespace
def test_a_study_on_a_full_disk_ends_in_one_line_leaving_whole_lines(tmp_path):
    """A real full file system: a 16 KiB tmpfs in a mount namespace of this test's own."""
    if os.geteuid() != 0 or shutil.which("unshare") is None:
        pytest.skip("mounting a small tmpfs needs root and unshare")
    if subprocess.run(["unshare", "-m", "true"], capture_output=True).returncode != 0:
        pytest.skip("unshare -m is not permitted here")
    disk = tmp_path / "disk"
    disk.mkdir()
    study = [sys.executable, "-m", "hexaleg", "study", "--l1-ratios", "0.1", "--l3-points", "8"]
    script = (
        f"mount --make-rprivate / && mount -t tmpfs -o size=16k tmpfs {disk} && "
        f"{' '.join(study)} --workers 1 -o {disk}/s; echo status=$?; "
        f"tail -c 1 {disk}/s/{JOURNAL} | od -An -c"
    )
    result = subprocess.run(
        ["unshare", "-m", "sh", "-c", script], capture_output=True, text=True, timeout=600
    )
    assert "status=2" in result.stdout, (result.stdout, result.stderr)
    assert result.stdout.split()[-1] == "\\n"  # the journal ends with a whole line
    errors = [line for line in result.stderr.splitlines() if line.startswith("hexaleg")]
    assert len(errors) == 1 and "No space left on device" in errors[0]
    assert "Traceback" not in result.stderr


LOCKED_STUDY = """
import sys, time
from pathlib import Path
from hexaleg._folders import claim_folder, lock_folder
with lock_folder(claim_folder(Path(sys.argv[1]), "study"), "study"):
    print("locked", flush=True)
    time.sleep(600)
"""


def test_a_second_resume_of_a_study_in_use_is_refused_naming_the_first(tmp_path, capsys):
    """Two `study --resume` at once must not each compute every design."""
    holder = subprocess.Popen(
        [sys.executable, "-c", LOCKED_STUDY, str(tmp_path / "s")], stdout=subprocess.PIPE, text=True
    )
    try:
        assert holder.stdout.readline() == "locked\n"
        assert run_cli([*CLI, "-o", str(tmp_path / "s"), "--resume"]) == 2
    finally:
        os.kill(holder.pid, signal.SIGKILL)
        holder.wait(timeout=30)
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"in use by another hexaleg study (pid {holder.pid})" in err
    assert sorted(p.name for p in (tmp_path / "s").iterdir()) == sorted([".hexaleg.lock", MARKER])


@pytest.mark.slow  # two real studies at once
def test_two_real_studies_at_once_compute_each_design_once(tmp_path):
    out = tmp_path / "s"
    argv = [sys.executable, "-m", "hexaleg", "study", "--l1-ratios", "0.1"]
    argv += ["--l3-points", "16", "--workers", "1", "-o", str(out), "--resume"]
    first = subprocess.Popen(
        argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True
    )
    try:
        while not (out / JOURNAL).exists():  # it holds the folder once its journal exists
            assert first.poll() is None, first.stderr.read()
            time.sleep(0.01)
        os.killpg(first.pid, signal.SIGSTOP)  # paused mid-study, still holding the folder
        second = subprocess.run(argv, capture_output=True, text=True, timeout=300)
        os.killpg(first.pid, signal.SIGCONT)
        assert first.wait(timeout=600) == 0
    finally:
        if first.poll() is None:
            os.killpg(first.pid, signal.SIGKILL)
            first.wait(timeout=30)
    assert second.returncode == 2
    assert f"(pid {first.pid})" in second.stderr and second.stderr.count("\n") == 1
    rows = (out / JOURNAL).read_text().splitlines()[1:]
    assert len(rows) == 16 == len(set(rows))


def test_a_study_written_before_folders_had_markers_can_be_resumed(tmp_path):
    journal = _journal(tmp_path / "old", ROW)
    (tmp_path / "old" / MARKER).unlink()
    table = run_study(SPEC, tmp_path / "old", executor=ThreadPoolExecutor(1), resume=True)
    assert len(table) == 3 and (tmp_path / "old" / MARKER).exists()
    assert journal.read_text().count("\n") == 4
