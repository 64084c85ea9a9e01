"""Atomic file output: a failed or interrupted write leaves no file behind.

Folders are built in a staging folder beside the target (named after the process
that owns it) and renamed into place when complete. A process killed mid-write
cannot remove its staging folder; the next run for the same target does, once the
owner is gone.
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
from pathlib import Path

from hexaleg.exceptions import HexalegError


def atomic_write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` to ``path`` via a temporary file in the same folder and a rename."""
    return atomic_write_bytes(path, text.encode("utf-8"))


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` via a temporary file in the same folder and a rename.

    Raises:
        HexalegError: ``path`` names a folder (or nothing), or the folder cannot be
            written; one line, nothing left behind.

    """
    target = Path(path)
    if not str(path):
        raise HexalegError("an empty path is not a file to write")
    if target.is_dir():
        raise HexalegError(f"{target} is a folder, not a file to write")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    except OSError as err:
        raise HexalegError(f"cannot write {target}: {err.strerror or err}") from None
    try:
        os.fchmod(fd, 0o666 & ~_current_umask())  # as open() would create it
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, target)
    except BaseException as err:
        Path(tmp).unlink(missing_ok=True)
        if isinstance(err, OSError):
            raise HexalegError(f"cannot write {target}: {err.strerror or err}") from None
        raise
    return target


def _current_umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def staging_folder(target: Path) -> Path:
    """A new, empty folder beside ``target`` to build it in, with a normal folder's mode.

    Staging folders left by processes that no longer run (killed mid-write) are
    removed first.
    """
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_staging(target)
    staging = Path(
        tempfile.mkdtemp(prefix=f".{target.name}.staging-{os.getpid()}.", dir=target.parent)
    )
    staging.chmod(0o777 & ~_current_umask())  # as mkdir would create it, not mkdtemp's 0700
    return staging


def retired_folder(target: Path) -> Path:
    """Where ``target`` goes while its replacement is swapped in (removed right after)."""
    return target.with_name(f".{target.name}.staging-{os.getpid()}.old")


def remove_stale_staging(target: Path) -> list[Path]:
    """Remove the staging folders of ``target`` whose owning process has ended."""
    pattern = re.compile(rf"^\.{re.escape(target.name)}\.staging-(\d+)\.")
    removed = []
    for entry in target.parent.iterdir() if target.parent.is_dir() else ():
        match = pattern.match(entry.name)
        if match and entry.is_dir() and not _running(int(match.group(1))):
            shutil.rmtree(entry, ignore_errors=True)
            removed.append(entry)
    return removed


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # alive, owned by someone else
        return True
    return True
