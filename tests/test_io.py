"""Atomic output: staging folders have a normal mode and never outlive a killed writer."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from hexaleg._io import atomic_write_text, remove_stale_staging, staging_folder


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait(timeout=60)
    return process.pid


def test_staging_folder_has_a_normal_folders_mode(tmp_path):
    staging = staging_folder(tmp_path / "out")
    assert staging.parent == tmp_path and staging.name.startswith(f".out.staging-{os.getpid()}.")
    assert staging.stat().st_mode & 0o777 == 0o777 & ~_umask()


def test_only_staging_of_ended_processes_is_removed(tmp_path):
    dead = tmp_path / f".out.staging-{_dead_pid()}.abc"
    mine = tmp_path / f".out.staging-{os.getpid()}.def"
    other_target = tmp_path / f".other.staging-{_dead_pid()}.ghi"
    user_folder = tmp_path / ".out.mine"
    for folder in (dead, mine, other_target, user_folder):
        folder.mkdir()
        (folder / "file").write_text("x")
    assert remove_stale_staging(tmp_path / "out") == [dead]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        p.name for p in (mine, other_target, user_folder)
    )


@pytest.mark.parametrize("where", ["", "folder", "missing-parent-is-a-file/x.txt"])
def test_unwritable_targets_are_one_line_errors_and_leave_nothing(tmp_path, where):
    from hexaleg.exceptions import HexalegError

    (tmp_path / "folder").mkdir()
    (tmp_path / "missing-parent-is-a-file").write_text("a file, not a folder")
    before = sorted(p.name for p in tmp_path.rglob("*"))
    path = str(tmp_path / where) if where else ""
    with pytest.raises(HexalegError) as caught:
        atomic_write_text(path, "text")
    assert "\n" not in str(caught.value)
    assert sorted(p.name for p in tmp_path.rglob("*")) == before
