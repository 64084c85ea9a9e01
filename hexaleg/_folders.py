"""Folders hexaleg writes: replaced whole only when hexaleg wrote them, locked while in use.

Every folder hexaleg creates holds a marker, :data:`MARKER`: a small JSON file saying
which kind of output it is (``report``, ``study``), in which format, and — for a folder
that is replaced whole — every file hexaleg put there. hexaleg replaces a folder only
when the marker says it wrote it and the folder holds nothing else: a file the user
added, or a folder hexaleg never wrote, is refused (never deleted).

- :func:`replace_folder` builds the new folder beside its target (a *staging* folder
  named after the process) and swaps it in when complete: the old folder is *parked*
  under a name of its own, the new one renamed into place, the parked one removed. A
  process killed between the two renames leaves the old folder parked; the next run
  for the same target puts it back (or removes it, if the swap had completed).
- :func:`claim_folder` marks a folder that grows in place (a study's journal);
  :func:`lock_folder` keeps a second run out of it while the first works, and names
  the first run's pid.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import shutil
import stat
import tempfile
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from hexaleg._io import (
    check_creatable,
    check_output_folder,
    current_umask,
    fsync_folder,
    os_reason,
    shown,
    stale_entries,
    stale_prefix,
    write_text,
)
from hexaleg._version import __version__
from hexaleg.exceptions import HexalegError

MARKER = ".hexaleg.json"
"""The file that says hexaleg wrote the folder it is in."""
MARKER_FORMAT = 1
"""Format of :data:`MARKER` (and of the folders it marks) this hexaleg writes and reads."""
LOCK = ".hexaleg.lock"
"""The file a run holds locked (``flock``) while it uses its folder; it holds the pid."""
_SHOWN = 3
"""Foreign names quoted in a refusal."""
_HELD: set[tuple[int, int]] = set()
"""(device, inode) of the lock files this process holds."""
_HELD_LOCK = threading.Lock()


def check_replaceable_folder(path: str | os.PathLike[str], kind: str) -> Path:
    """Refuse, before computing, a folder :func:`replace_folder` would not replace.

    Allowed: a folder that does not exist yet, an empty folder, or a ``kind`` folder
    hexaleg wrote that holds only its own files. Returns ``path`` resolved.

    Raises:
        HexalegError: one line naming what is in the way.

    """
    check_output_folder(path)
    text = os.fspath(path)
    target = Path(os.path.realpath(text))
    if _holds_cwd(target):
        raise HexalegError(
            f"{shown(text)} is the folder you are in (or holds it): hexaleg replaces its {kind} "
            "folder whole, so name a new folder"
        )
    check_creatable(text, target)  # the staging folder is made beside it
    if target.is_dir():
        foreign = _foreign_entries(target, kind)
        if foreign:
            names = ", ".join(shown(name) for name in foreign[:_SHOWN])
            names += ", …" if len(foreign) > _SHOWN else ""
            raise HexalegError(
                f"{shown(text)} is not a hexaleg {kind} folder, or holds files hexaleg did not "
                f"write ({names}): hexaleg replaces only what it wrote; choose a new or "
                "empty folder"
            )
    return target


@contextmanager
def replace_folder(path: str | os.PathLike[str], kind: str) -> Iterator[Path]:
    """Build the ``kind`` folder ``path`` in a staging folder (yielded), then swap it in.

    On leaving the block normally the marker is written, the target checked again (a
    file may have appeared in it meanwhile) and the staging folder swapped in; on an
    error or interrupt the staging folder is removed and the target left as it was.
    """
    target = check_replaceable_folder(path, kind)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise HexalegError(f"cannot create {shown(target.parent)}: {os_reason(err)}") from None
    recover_interrupted_swap(target)
    staging = Path(tempfile.mkdtemp(prefix=stale_prefix(target.name, "staging"), dir=target.parent))
    try:
        existing = target.stat() if target.is_dir() else None
        mode = 0o777 & ~current_umask() if existing is None else stat.S_IMODE(existing.st_mode)
        staging.chmod(mode)  # as mkdir would make it (not mkdtemp's 0700), or as it was
        yield staging
        write_marker(staging, kind, manifest=_entries(staging, files_only=True))
        check_replaceable_folder(path, kind)
        _swap_in(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise


def claim_folder(path: str | os.PathLike[str], kind: str) -> Path:
    """Create (or accept) the ``kind`` folder ``path``, which hexaleg then grows in place.

    Allowed: a new or empty folder (marked now), or one hexaleg marked as ``kind``.
    Returns ``path`` resolved.
    """
    check_output_folder(path)
    text = os.fspath(path)
    target = Path(os.path.realpath(text))
    if target.is_dir() and _read_marker(target, kind) is None and any(target.iterdir()):
        raise HexalegError(
            f"{shown(text)} is not a hexaleg {kind} folder: choose a new or empty folder"
        )
    try:
        target.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise HexalegError(f"cannot create {shown(text)}: {os_reason(err)}") from None
    if _read_marker(target, kind) is None:
        write_marker(target, kind)
    return target


@contextmanager
def lock_folder(folder: Path, what: str) -> Iterator[None]:
    """Hold ``folder`` for this run; another run that tries is refused, told our pid.

    The lock is a POSIX record lock (``fcntl``/``lockf``) on :data:`LOCK`: the system
    releases it when the process ends, however it ends, and — unlike ``flock`` — worker
    processes forked meanwhile do not inherit it, so it never outlives its holder. Two
    runs in one process are told apart here (record locks are per process).

    Raises:
        HexalegError: another run holds the folder.

    """
    try:
        fd = os.open(folder / LOCK, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
    except OSError as err:
        raise HexalegError(f"cannot lock {shown(folder)}: {os_reason(err)}") from None
    key = (os.fstat(fd).st_dev, os.fstat(fd).st_ino)
    try:
        with _HELD_LOCK:
            if key in _HELD:
                raise _in_use(folder, what, str(os.getpid()))
            try:
                fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as err:
                if err.errno not in (errno.EACCES, errno.EAGAIN):
                    raise HexalegError(f"cannot lock {shown(folder)}: {os_reason(err)}") from None
                holder = os.pread(fd, 32, 0).decode("ascii", errors="replace").strip()
                raise _in_use(folder, what, holder or "unknown") from None
            _HELD.add(key)
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        yield
    finally:
        with _HELD_LOCK:
            _HELD.discard(key)
        os.close(fd)  # releases the record lock


def _in_use(folder: Path, what: str, holder: str) -> HexalegError:
    return HexalegError(
        f"{shown(folder)} is in use by another hexaleg {what} (pid {holder}): wait for it "
        "to end, or stop it"
    )


def write_marker(folder: Path, kind: str, manifest: list[str] | None = None) -> Path:
    """Write :data:`MARKER` into ``folder``: hexaleg wrote it, as ``kind``, with ``manifest``."""
    record: dict[str, Any] = {"written_by": "hexaleg", "kind": kind, "format": MARKER_FORMAT}
    record["hexaleg_version"] = __version__
    if manifest is not None:
        record["files"] = manifest
    return write_text(folder / MARKER, json.dumps(record, indent=1) + "\n")


def recover_interrupted_swap(target: Path) -> None:
    """Clean up after processes killed while writing ``target`` with :func:`replace_folder`.

    Their staging folders are removed; a parked old folder goes back to ``target`` if the
    swap never completed (``target`` missing), and is removed if it did.
    """
    for staging in stale_entries(target.parent, target.name, "staging"):
        shutil.rmtree(staging, ignore_errors=True)
    for parked in stale_entries(target.parent, target.name, "parked"):
        if os.path.lexists(target):
            shutil.rmtree(parked, ignore_errors=True)
        else:
            parked.rename(target)


def _holds_cwd(target: Path) -> bool:
    try:
        here = Path.cwd().resolve()
    except OSError:  # the current folder was removed
        return False
    return target == here or target in here.parents


def _swap_in(staging: Path, target: Path) -> None:
    if not os.path.lexists(target):
        staging.rename(target)
    else:
        parked = Path(
            tempfile.mkdtemp(prefix=stale_prefix(target.name, "parked"), dir=target.parent)
        )
        target.rename(parked)  # replaces the empty folder mkdtemp made: the name is ours
        try:
            staging.rename(target)
        except BaseException:
            parked.rename(target)
            raise
        shutil.rmtree(parked, ignore_errors=True)
    fsync_folder(target.parent)


def _read_marker(folder: Path, kind: str) -> dict[str, Any] | None:
    """The marker of a ``kind`` folder hexaleg wrote, or None if it has none (or another)."""
    try:
        record = json.loads((folder / MARKER).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(record, dict) or record.get("written_by") != "hexaleg":
        return None
    if record.get("kind") != kind:
        return None
    if not isinstance(record.get("format"), int) or record["format"] > MARKER_FORMAT:
        raise HexalegError(
            f"{shown(folder)} was written by a newer hexaleg (format {record.get('format')!r}): "
            "upgrade hexaleg, or choose another folder"
        )
    return record


def _foreign_entries(folder: Path, kind: str) -> list[str]:
    """What in ``folder`` hexaleg did not write as a ``kind`` folder (all of it, unmarked)."""
    record = _read_marker(folder, kind)
    ours = {MARKER, LOCK}
    for name in (record or {}).get("files") or ():
        ours |= {name, *(parent.as_posix() for parent in Path(name).parents)}
    if record is None:
        ours = set()
    return [name for name in _entries(folder) if name not in ours]


def _entries(folder: Path, files_only: bool = False) -> list[str]:
    """Every entry below ``folder`` (only the files: not folders), as relative POSIX paths.

    A link to a folder is an entry, never followed.
    """
    found = []
    for root, dirs, files in os.walk(folder):
        dirs.sort()
        base = Path(root).relative_to(folder)
        found += [(base / name).as_posix() for name in sorted(files)]
        found += [
            (base / name).as_posix()
            for name in dirs
            if not files_only or Path(root, name).is_symlink()
        ]
    return found
