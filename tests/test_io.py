"""Writing output files: atomic where it can be, never breaking what is already there.

Each case is run as the user would meet it: through the CLI where the CLI is what the
user runs, on the API where the API is the mechanism.
"""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys
import threading
from pathlib import Path

import pytest
from conftest import run_cli
from unprivileged import plain_folder, run_plain

from hexaleg._io import (
    check_output_file,
    check_output_folder,
    current_umask,
    remove_stale,
    write_bytes,
    write_text,
)
from hexaleg.exceptions import HexalegError

HEXALEG = [sys.executable, "-m", "hexaleg"]
TOO_LONG = "a" * 256 + ".urdf"  # one byte over the usual 255


def _dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait(timeout=60)
    return process.pid


def _entries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def test_a_new_file_gets_a_normal_mode_and_nothing_else_is_left(tmp_path):
    path = write_text(tmp_path / "new.urdf", "text")
    assert path.read_text() == "text"
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~current_umask()
    assert _entries(tmp_path) == ["new.urdf"]


def test_an_existing_file_keeps_its_mode_and_is_replaced_atomically(tmp_path):
    path = tmp_path / "private.urdf"
    path.write_text("old content, longer than the new")
    path.chmod(0o600)
    inode = path.stat().st_ino
    write_text(path, "new")
    assert path.read_text() == "new"
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert path.stat().st_ino != inode  # a new file renamed over the old one
    assert _entries(tmp_path) == ["private.urdf"]


def test_a_symbolic_link_is_written_through_to_its_target(tmp_path):
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "robot.urdf"
    target.write_text("old")
    link = tmp_path / "link.urdf"
    link.symlink_to(target)
    assert run_cli(["urdf", "-o", str(link)]) == 0
    assert link.is_symlink() and link.resolve() == target
    assert target.read_text().startswith("<?xml")
    assert _entries(tmp_path) == ["link.urdf", "real"]  # no staging link, nothing stale
    assert _entries(tmp_path / "real") == ["robot.urdf"]


def test_a_dangling_link_creates_its_target(tmp_path):
    link = tmp_path / "link.urdf"
    link.symlink_to("made.urdf")
    write_text(link, "made")
    assert link.is_symlink() and (tmp_path / "made.urdf").read_text() == "made"


def test_hard_links_are_written_in_place_so_every_name_sees_the_new_content(tmp_path):
    first = tmp_path / "a.urdf"
    first.write_text("old content, longer than the new")
    os.link(first, tmp_path / "b.urdf")
    inode = first.stat().st_ino
    write_text(first, "new")
    for name in ("a.urdf", "b.urdf"):
        assert (tmp_path / name).read_text() == "new"  # truncated to the new length
        assert (tmp_path / name).stat().st_ino == inode
    assert _entries(tmp_path) == ["a.urdf", "b.urdf"]


def test_a_fifo_is_written_directly_and_stays_a_fifo(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()), daemon=True)
    reader.start()
    write_bytes(fifo, b"through the pipe")
    reader.join(timeout=30)
    assert received == [b"through the pipe"]
    assert stat.S_ISFIFO(fifo.stat().st_mode)


@pytest.mark.slow  # two runs of the command
def test_dev_stdout_is_this_process_stdout_never_replaced_nor_truncated(tmp_path):
    log = tmp_path / "log"
    log.write_text("kept\n")
    with log.open("a") as out:
        result = subprocess.run(
            [*HEXALEG, "urdf", "-o", "/dev/stdout"], stdout=out, stderr=subprocess.PIPE, text=True
        )
    assert result.returncode == 0, result.stderr
    text = log.read_text()
    assert text.startswith("kept\n<?xml") and text.rstrip().endswith("</robot>")
    piped = subprocess.run([*HEXALEG, "urdf", "-o", "/dev/stdout"], capture_output=True)
    assert piped.returncode == 0 and piped.stdout.startswith(b"<?xml")


def test_dev_null_stays_a_device_in_a_private_mount_namespace(tmp_path):
    """As root, in a mount namespace of its own with a fresh /dev: never the real one."""
    if os.geteuid() != 0:
        pytest.skip("mknod and mount need root")
    if shutil.which("unshare") is None:
        pytest.skip("unshare (util-linux) is not installed")
    probe = subprocess.run(["unshare", "-m", "true"], capture_output=True)
    if probe.returncode != 0:
        pytest.skip(f"unshare -m is not permitted here: {probe.stderr.decode().strip()}")
    script = (
        "mount --make-rprivate / && mount -t tmpfs tmpfs /dev && "
        "mknod -m 666 /dev/null c 1 3 && "
        f"{' '.join(HEXALEG)} urdf -o /dev/null && stat -c %F /dev/null"
    )
    result = subprocess.run(["unshare", "-m", "sh", "-c", script], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "character special file"
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


@pytest.mark.parametrize(
    ("output", "message"),
    [
        ("", "an empty path"),
        ("nothere/", "ends in '/'"),
        ("folder", "is a folder"),
        ("a-file/x.urdf", "is not a folder"),
        (TOO_LONG, "longer than the 255 bytes"),
        ("line\nbreak/", "line\\nbreak/ ends in '/'"),
    ],
)
def test_unwritable_paths_are_refused_before_computing(
    tmp_path, capsys, monkeypatch, output, message
):
    from hexaleg.robot.robot import Robot

    monkeypatch.chdir(tmp_path)
    (tmp_path / "folder").mkdir()
    (tmp_path / "a-file").write_text("a file, not a folder")
    before = _entries(tmp_path)
    monkeypatch.setattr(Robot, "urdf", lambda *args: pytest.fail("rendered the URDF"))
    assert run_cli(["urdf", "-o", output]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err and len(err) < 300, err
    assert _entries(tmp_path) == before


@pytest.mark.skipif(not Path("/proc/self").exists(), reason="needs Linux's /proc")
@pytest.mark.parametrize("command", [["report", "-o"], ["flexibility", "--plot"]])
def test_a_folder_nothing_can_be_created_in_is_refused_before_computing(capsys, command):
    # /proc refuses new files whatever the permissions say (root may "write" anywhere)
    assert run_cli([*command, "/proc/hexaleg-report"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "cannot write in /proc" in err and "staging" not in err, err


def test_the_api_refuses_the_same_paths_without_leaving_anything(tmp_path):
    (tmp_path / "folder").mkdir()
    for bad in ("", str(tmp_path / "folder"), str(tmp_path / TOO_LONG)):
        with pytest.raises(HexalegError) as caught:
            write_text(bad, "text")
        assert "\n" not in str(caught.value)
    assert _entries(tmp_path) == ["folder"]
    with pytest.raises(HexalegError, match="is a file, not a folder"):
        check_output_folder(write_text(tmp_path / "file", "x"))
    assert check_output_file(tmp_path / "new" / "deeper" / "x.urdf").name == "x.urdf"
    assert _entries(tmp_path) == ["file", "folder"]  # checking creates nothing


def test_a_name_near_the_limit_is_written_its_temporary_name_shortened(tmp_path):
    name = "b" * 250
    write_text(tmp_path / name, "fits")
    assert _entries(tmp_path) == [name]


def test_temporary_files_of_ended_writers_are_removed_others_kept(tmp_path):
    dead = tmp_path / f".x.urdf.tmp-{_dead_pid()}.abc"
    alive = tmp_path / f".x.urdf.tmp-{os.getpid()}.def"
    other = tmp_path / f".y.urdf.tmp-{_dead_pid()}.ghi"
    for path in (dead, alive, other):
        path.write_text("half")
    assert remove_stale(tmp_path, "x.urdf", "tmp") == [dead]
    write_text(tmp_path / "y.urdf", "whole")
    assert _entries(tmp_path) == sorted([alive.name, "y.urdf"])


def test_a_full_disk_on_stdout_is_one_line(tmp_path):
    with open("/dev/full", "w") as full:
        result = subprocess.run(
            [*HEXALEG, "urdf"], stdout=full, stderr=subprocess.PIPE, text=True, timeout=120
        )
    assert result.returncode == 2
    assert (
        result.stderr == "hexaleg urdf: error: cannot write /dev/stdout: No space left on device\n"
    )


def test_a_closed_stdout_is_one_line_in_process(monkeypatch, capsys):
    monkeypatch.setattr(sys, "stdout", None)
    for argv in (["urdf"], ["design", "show"]):
        assert run_cli(argv) == 2
    err = capsys.readouterr().err.splitlines()
    assert err == [
        "hexaleg urdf: error: standard output is closed: pass -o FILE, or open it",
        "hexaleg design: error: standard output is closed: nowhere to print the result",
    ]


@pytest.mark.slow  # a run of the command each
@pytest.mark.parametrize("argv", [["urdf"], ["design", "show"], ["workspace", "--samples", "10"]])
def test_a_closed_stdout_is_one_line(argv):
    result = subprocess.run(
        [*HEXALEG, *argv], stderr=subprocess.PIPE, text=True, preexec_fn=lambda: os.close(1),
        timeout=120,
    )  # fmt: skip
    assert result.returncode == 2, result.stderr
    assert result.stderr.count("\n") == 1 and "standard output is closed" in result.stderr


@pytest.mark.slow  # two runs of the command as another user
def test_a_read_only_folder_is_refused_for_a_plain_user():
    folder = plain_folder()
    try:
        (folder / "locked").mkdir()
        (folder / "locked" / "old.urdf").write_text("old")
        for path in (folder / "locked", folder / "locked" / "old.urdf"):
            shutil.chown(path, folder.stat().st_uid, folder.stat().st_gid)
        (folder / "locked").chmod(0o555)
        result = run_plain(["urdf", "-o", "locked/new.urdf"], cwd=folder)
        assert result.returncode == 2, result.stderr
        assert result.stderr.count("\n") == 1
        assert result.stderr.endswith("/locked: Permission denied\n"), result.stderr
        (folder / "locked" / "old.urdf").chmod(0o444)
        (folder / "locked").chmod(0o755)
        result = run_plain(["urdf", "-o", "locked/old.urdf"], cwd=folder)
        assert (
            result.returncode == 2 and "locked/old.urdf is read-only (mode 0444)" in result.stderr
        )
        assert _entries(folder / "locked") == ["old.urdf"]
        assert (folder / "locked" / "old.urdf").read_text() == "old"
    finally:
        shutil.rmtree(folder, ignore_errors=True)
