"""Folders hexaleg writes, and the files it reads back: never another's, held while in use.

Every folder hexaleg creates holds a marker, :data:`MARKER`: a small JSON file saying
which kind of output it is (``report``, ``figures``, ``study``), in which format, and —
for a folder of files — every file hexaleg put there. hexaleg writes into a folder only
when it is new or empty, or when the marker says hexaleg wrote it and the folder holds
nothing else: a file the user added, or a folder hexaleg never wrote, is refused.

- :func:`replace_folder` builds the files in a *staging* folder beside the target, marked
  from its creation, and brings them in when complete: a report is swapped in whole (the
  old folder *parked* under a name of its own, the new one renamed into place, the parked
  one removed); figures are merged (the marker lists the new files first, then each is
  renamed in), so that the figures of several commands share a folder. The next run for
  the same target tidies up after a killed one: a parked folder goes back (or is removed,
  if the swap had completed), a staging folder is removed — only entries hexaleg marked,
  or empty ones: a folder of the user's that merely has such a name is left alone.
- :func:`claim_folder` marks a folder that grows in place (a study's journal).
- :func:`open_regular` opens what hexaleg reads back (a marker, a journal, a lock) only
  if it is a regular file: a FIFO is refused at once, never waited on.
- :func:`hold` and :func:`lock_folder` keep a second run out while the first works, and
  name the first run's pid.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import shutil
import stat
import struct
import sys
import tempfile
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from hexaleg._io import (
    WriteError,
    check_creatable,
    check_output_folder,
    current_umask,
    fsync_folder,
    make_parents,
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
"""The file a run holds locked while it uses its folder; it holds the pid."""
_SHOWN = 3
"""Foreign names quoted in a refusal."""
_FLOCK = "hhqqi" if sys.platform.startswith("linux") else "qqihh"
"""``struct flock`` (type, whence, start, length, pid) as the system lays it out."""
_HELD: set[tuple[int, int]] = set()
"""(device, inode) of the files this process holds with :func:`hold`."""
_HELD_LOCK = threading.Lock()


def check_replaceable_folder(path: str | os.PathLike[str], kind: str, merge: bool = False) -> Path:
    """Refuse, before computing, a folder :func:`replace_folder` would not write.

    Allowed: a folder that does not exist yet, an empty folder, or a ``kind`` folder
    hexaleg wrote that holds only its own files. Returns ``path`` resolved.

    Raises:
        HexalegError: one line naming what is in the way.

    """
    check_output_folder(path)
    text = os.fspath(path)
    target = Path(os.path.realpath(text))
    if not merge and _holds_cwd(target):
        raise HexalegError(
            f"{shown(text)} is the folder you are in (or holds it): hexaleg replaces its {kind} "
            "folder whole, so name a new folder"
        )
    check_creatable(text, target)  # the staging folder is made beside it
    foreign = _foreign_entries(target, kind) if target.is_dir() else []
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
def replace_folder(path: str | os.PathLike[str], kind: str, merge: bool = False) -> Iterator[Path]:
    """Build the ``kind`` folder ``path`` in a staging folder (yielded), then bring it in.

    On leaving the block normally the target is checked again (a file may have appeared
    in it meanwhile), then the staging folder is swapped in whole, or with ``merge`` its
    files moved in; on an error or interrupt the staging folder is removed and the target
    left as it was. A write the system refuses names the target, not the staging folder.
    """
    target = check_replaceable_folder(path, kind, merge)
    text = os.fspath(path)
    try:
        make_parents(target)
        recover_interrupted_swap(target)
        prefix = stale_prefix(target.name, "staging")
        staging = Path(tempfile.mkdtemp(prefix=prefix, dir=target.parent))
    except (OSError, WriteError) as err:
        raise _cannot_write(kind, text, err) from None
    try:
        try:
            existing = target.stat() if target.is_dir() else None
            mode = 0o777 & ~current_umask() if existing is None else stat.S_IMODE(existing.st_mode)
            staging.chmod(mode)  # as mkdir would make it (not mkdtemp's 0700), or as it was
            write_marker(staging, kind)  # only a marked staging folder is ever removed
            yield staging
            check_replaceable_folder(path, kind, merge)
            (_merge_in if merge and existing else _swap_in)(staging, target, kind)
        except (OSError, WriteError) as err:
            raise _cannot_write(kind, text, err) from None
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


def write_marker(folder: Path, kind: str, manifest: list[str] | None = None) -> Path:
    """Write :data:`MARKER` into ``folder``: hexaleg wrote it, as ``kind``, with ``manifest``."""
    record: dict[str, Any] = {"written_by": "hexaleg", "kind": kind, "format": MARKER_FORMAT}
    record["hexaleg_version"] = __version__
    if manifest is not None:
        record["files"] = manifest
    return write_text(folder / MARKER, json.dumps(record, indent=1) + "\n")


def recover_interrupted_swap(target: Path) -> None:
    """Tidy up after processes killed while writing ``target`` (see the module)."""
    for staging in stale_entries(target.parent, target.name, "staging"):
        if _marked(staging):
            shutil.rmtree(staging, ignore_errors=True)
    for parked in stale_entries(target.parent, target.name, "parked"):
        if _marked(parked) and os.path.lexists(target):
            shutil.rmtree(parked, ignore_errors=True)
        elif _marked(parked):
            parked.rename(target)


@contextmanager
def lock_folder(folder: Path, what: str) -> Iterator[None]:
    """Hold ``folder`` for this run (:func:`hold` on its :data:`LOCK`, which gets our pid)."""
    fd = open_regular(folder / LOCK, os.O_RDWR | os.O_CREAT, shown(folder / LOCK))
    try:
        with hold(fd, shown(folder), what):
            os.ftruncate(fd, 0)
            os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
            yield
    finally:
        os.close(fd)


@contextmanager
def hold(fd: int, shown_as: str, what: str) -> Iterator[None]:
    """Hold the open file ``fd`` for this run; another run that tries is refused, told our pid.

    The lock is a POSIX record lock (``lockf``): the system releases it when the process
    ends, however it ends, and — unlike ``flock`` — worker processes forked meanwhile do
    not inherit it, so it never outlives its holder. Two runs in one process are told
    apart here (record locks are per process). Closing any descriptor of the file
    releases it: keep ``fd`` the only one open.

    Raises:
        HexalegError: another run holds the file.

    """
    key = (os.fstat(fd).st_dev, os.fstat(fd).st_ino)
    with _HELD_LOCK:
        if key in _HELD:
            raise _in_use(shown_as, what, str(os.getpid()))
        try:
            fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as err:
            if err.errno not in (errno.EACCES, errno.EAGAIN):
                raise HexalegError(f"cannot lock {shown_as}: {os_reason(err)}") from None
            raise _in_use(shown_as, what, _holder(fd)) from None
        _HELD.add(key)
    try:
        yield
    finally:
        with _HELD_LOCK:
            _HELD.discard(key)
        fcntl.lockf(fd, fcntl.LOCK_UN)


def open_regular(path: Path, flags: int, shown_as: str) -> int:
    """Open ``path`` with ``flags`` only if it is a regular file (never waiting on a FIFO).

    Raises:
        HexalegError: it is a FIFO, a device or a folder, or the system refuses.

    """
    try:
        fd = os.open(path, flags | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC, 0o666)
    except OSError as err:
        if err.errno not in (errno.EISDIR, errno.ENXIO):  # ENXIO: a FIFO nobody reads
            raise HexalegError(f"cannot open {shown_as}: {os_reason(err)}") from None
        fd = -1
    if fd < 0 or not stat.S_ISREG(os.fstat(fd).st_mode):
        if fd >= 0:
            os.close(fd)
        raise HexalegError(
            f"{shown_as} is not a regular file (a FIFO, a device or a folder): hexaleg "
            "reads back only files it wrote; remove it, or choose another name"
        )
    os.set_blocking(fd, True)
    return fd


def read_regular(path: Path, shown_as: str) -> bytes:
    """The content of the regular file ``path`` (see :func:`open_regular`)."""
    with os.fdopen(open_regular(path, os.O_RDONLY, shown_as), "rb") as handle:
        try:
            return handle.read()
        except OSError as err:
            raise HexalegError(f"cannot read {shown_as}: {os_reason(err)}") from None


def _holder(fd: int) -> str:
    """The pid of the process whose record lock on ``fd`` conflicts with ours."""
    try:
        found = fcntl.fcntl(fd, fcntl.F_GETLK, struct.pack(_FLOCK, fcntl.F_WRLCK, 0, 0, 0, 0))
    except OSError:
        return "unknown"
    pid = struct.unpack(_FLOCK, found)[4 if _FLOCK.startswith("h") else 2]
    return str(pid) if pid > 0 else "unknown"


def _in_use(shown_as: str, what: str, holder: str) -> HexalegError:
    return HexalegError(
        f"{shown_as} is in use by another hexaleg {what} (pid {holder}): wait for it "
        "to end, or stop it"
    )


def _marked(folder: Path) -> bool:
    """Whether ``folder`` is a real folder that is empty or holds hexaleg's marker.

    A folder holding nothing but the marker's own temporary files, left by a process killed
    while writing the marker (the first thing it writes), counts as marked.
    """
    try:
        if folder.is_symlink() or not folder.is_dir():
            return False
        entries = set(folder.iterdir())
        if not entries or _marker(folder) is not None:
            return True
        return entries <= set(stale_entries(folder, MARKER, "tmp"))
    except (OSError, HexalegError):
        return False


def _holds_cwd(target: Path) -> bool:
    try:
        here = Path.cwd().resolve()
    except OSError:  # the current folder was removed
        return False
    return target == here or target in here.parents


def _swap_in(staging: Path, target: Path, kind: str) -> None:
    write_marker(staging, kind, manifest=_files(staging))
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


def _merge_in(staging: Path, target: Path, kind: str) -> None:
    """Move the files of ``staging`` into ``target``, listed in its marker first."""
    new = _files(staging)
    old = (_read_marker(target, kind) or {}).get("files", [])
    write_marker(target, kind, manifest=sorted(set(old) | set(new)))
    for name in new:
        (target / name).parent.mkdir(parents=True, exist_ok=True)
        os.replace(staging / name, target / name)
    shutil.rmtree(staging, ignore_errors=True)
    fsync_folder(target)


def _marker(folder: Path) -> dict[str, Any] | None:
    """The marker hexaleg wrote in ``folder``, or None if it has none (or not hexaleg's)."""
    marker = folder / MARKER
    if not os.path.lexists(marker):
        return None
    try:
        record = json.loads(read_regular(marker, shown(marker)))
    except ValueError:
        return None
    if not isinstance(record, dict) or record.get("written_by") != "hexaleg":
        return None
    files = record.get("files", [])
    if not isinstance(files, list) or not all(isinstance(name, str) for name in files):
        raise HexalegError(
            f'{shown(marker)} is corrupt (its "files" is not a list of names): remove the '
            "folder, or choose another"
        )
    return record


def _read_marker(folder: Path, kind: str) -> dict[str, Any] | None:
    """The marker of a ``kind`` folder hexaleg wrote, or None if it has none (or another)."""
    record = _marker(folder)
    if record is None or record.get("kind") != kind:
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
    ours = set()
    if record is not None:
        ours = {MARKER, LOCK}
        for name in record.get("files", []):
            ours |= {name, *(parent.as_posix() for parent in Path(name).parents)}
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


def _files(folder: Path) -> list[str]:
    """The files hexaleg put in ``folder`` (its marker aside)."""
    return [name for name in _entries(folder, files_only=True) if name != MARKER]


def _cannot_write(kind: str, text: str, err: OSError | WriteError) -> HexalegError:
    reason = err.reason if isinstance(err, WriteError) else os_reason(err)
    return HexalegError(f"cannot write {kind} to {shown(text)}: {reason}")
