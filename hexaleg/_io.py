"""Writing hexaleg's output files: one mechanism for every command.

- :func:`check_output_file` and :func:`check_output_folder` refuse, before any computing,
  a path that cannot be written: empty, a folder where a file is meant (``nothere/``),
  ``-`` where a folder is meant, a name longer than the file system allows, a folder
  nothing can be created in, a read-only file. They find out by trying (a probe file, an
  open for writing that changes nothing), so the reason is the system's own.
- :func:`write_bytes` / :func:`write_text` write one file, creating missing folders on its
  path as ``mkdir -p`` would: ``-``, ``/dev/stdout``, ``/dev/stderr`` and ``/dev/fd/N``
  through the process's own stream (never replaced, never truncated); a regular file
  atomically (a temporary file beside it, then a rename: a failed or interrupted write
  leaves the old file or nothing), keeping its mode (and, where allowed, its owner);
  through a symbolic link to its target; a file with other hard links, or in a folder the
  user cannot write, in place (the same inode; the data is complete in memory before the
  first byte is written, but that write is not atomic); device nodes and FIFOs directly.

Folders are in :mod:`hexaleg._folders`, journals in :mod:`hexaleg._journal`. Every OS
error becomes a one-line :class:`~hexaleg.exceptions.HexalegError`.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import stat
import sys
import tempfile
from pathlib import Path

from hexaleg.exceptions import HexalegError

STDOUT = "/dev/stdout"
"""The path that means "standard output" to :func:`write_text` (as on Linux), like ``-``."""

_STREAM = re.compile(r"^/(?:dev/fd|proc/self/fd)/(\d+)$")
_STREAMS = {"-": 1, "/dev/stdout": 1, "/dev/stderr": 2}
_SHOWN_PATH = 120
"""Longest path quoted whole in a message [characters]."""
_SHORT_NAME = 100
"""Bytes of a target's name kept in its temporary and staging names (the system's limit
on a name, usually 255 bytes, must leave room for the suffixes)."""


class WriteError(HexalegError):
    """The system refused a write; ``reason`` is its own word for why (``No space left …``)."""

    def __init__(self, message: str, reason: str) -> None:
        super().__init__(message)
        self.reason = reason


def write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` as described in the module; return ``path``."""
    return write_bytes(path, text.encode("utf-8"))


def write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` as described in the module; return ``path``.

    Raises:
        HexalegError: ``path`` is empty or a folder, the file is read-only, or the system
            refuses the write (a :class:`WriteError`: permission, name too long, disk
            full); one line, and no temporary file is left behind.

    """
    text = STDOUT if os.fspath(path) == "-" else _text(path)
    stream = standard_stream(text)
    try:
        if stream is not None:
            _write_stream(stream, data)
            return Path(text)
        target = Path(os.path.realpath(text))  # through symbolic links, to their target
        existing = _stat(target)
        if existing is not None and stat.S_ISDIR(existing.st_mode):
            raise HexalegError(f"{shown(text)} is a folder, not a file to write")
        if existing is None or stat.S_ISREG(existing.st_mode):
            _refuse_unwritable_file(text, target, existing)
        if existing is not None and not stat.S_ISREG(existing.st_mode):
            _write_direct(target, data)  # a device node, a FIFO
        elif existing is not None and _in_place(target, existing):
            _write_direct(target, data, truncate=True)
        else:
            _write_atomically(target, data, existing)
    except OSError as err:
        raise WriteError(f"cannot write {shown(text)}: {os_reason(err)}", os_reason(err)) from None
    return Path(text)


def check_output_file(path: str | os.PathLike[str]) -> Path:
    """Refuse, before computing, a file :func:`write_bytes` could not write; return ``path``."""
    text = _text(path)
    if standard_stream(text) is not None:
        return Path(text)
    if text.endswith(("/", os.sep)):
        raise HexalegError(
            f"{shown(text)} ends in '/', which names a folder: name the file to write"
        )
    target = Path(os.path.realpath(text))
    existing = _stat(target)
    if existing is not None and stat.S_ISDIR(existing.st_mode):
        raise HexalegError(f"{shown(text)} is a folder, not a file to write")
    if existing is None or stat.S_ISREG(existing.st_mode):
        _refuse_unwritable_file(text, target, existing)
    return Path(text)


def check_output_folder(path: str | os.PathLike[str]) -> Path:
    """Refuse, before computing, a folder files cannot be written into (or created as)."""
    text = _text(path)
    if standard_stream(text) is not None:
        raise HexalegError(
            f"{shown(text)} is standard output, which cannot hold a folder: name a folder"
        )
    target = Path(os.path.realpath(text))
    existing = _stat(target)
    if existing is not None and not stat.S_ISDIR(existing.st_mode):
        raise HexalegError(f"{shown(text)} is a file, not a folder")
    if existing is None:
        check_creatable(text, target)
    else:
        probe_folder(target)
    return Path(text)


def check_creatable(text: str, target: Path) -> None:
    """Refuse a ``target`` that cannot be created.

    Its nearest existing ancestor must be a folder this process can write, and each name
    to create must be within the file system's limit.
    """
    ancestor, missing = target.parent, [target.name]
    while _stat(ancestor) is None and ancestor != ancestor.parent:
        missing.append(ancestor.name)
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise HexalegError(f"cannot write {shown(text)}: {shown(ancestor)} is not a folder")
    limit = _name_max(ancestor)
    if any(len(os.fsencode(name)) > limit for name in missing):
        raise HexalegError(
            f"cannot write {shown(text)}: a name in it is longer than the "
            f"{limit} bytes the file system allows"
        )
    probe_folder(ancestor)


def probe_folder(folder: Path) -> None:
    """Refuse a folder no file can be created in, by creating (and removing) one.

    Permissions do not tell: root may write anywhere by mode, yet not in ``/proc`` or on a
    read-only mount; the write that would fail after the computing fails here instead,
    with the system's reason.
    """
    try:
        fd, name = tempfile.mkstemp(prefix=".hexaleg-probe-", dir=folder)
    except OSError as err:
        raise HexalegError(f"cannot write in {shown(folder)}: {os_reason(err)}") from None
    os.close(fd)
    os.unlink(name)


def make_parents(target: Path) -> None:
    """Create the missing folders above ``target``, as ``mkdir -p`` would."""
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        message = f"cannot create {shown(target.parent)}: {os_reason(err)}"
        raise WriteError(message, os_reason(err)) from None


def shown(path: str | os.PathLike[str]) -> str:
    """``path`` for a one-line message: control characters escaped, a long one cut."""
    text = os.fspath(path)
    if not text.isprintable():
        text = text.encode("unicode_escape").decode("ascii")
    return text if len(text) <= _SHOWN_PATH else f"{text[:40]}…{text[-40:]}"


def os_reason(err: OSError) -> str:
    """An OS error in words, without its errno number: ``Permission denied``."""
    return err.strerror or str(err)


def current_umask() -> int:
    """The process's umask (read without changing it for longer than a call)."""
    mask = os.umask(0)
    os.umask(mask)
    return mask


def fsync_folder(folder: Path) -> None:
    """Put a rename in ``folder`` on disk (best effort: not every file system allows it)."""
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY | os.O_CLOEXEC)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def stale_prefix(name: str, role: str) -> str:
    """The name prefix of this process's ``role`` entry for the target ``name``.

    ``role`` is ``tmp``, ``staging`` or ``parked``; the prefix ``.<name>.<role>-<pid>.``
    names the owning process, so that the entries of ended processes can be found.
    """
    return f".{_short_name(name)}.{role}-{os.getpid()}."


def stale_entries(folder: Path, name: str, role: str) -> list[Path]:
    """``role`` entries for ``name`` in ``folder`` whose owning process has ended."""
    pattern = re.compile(rf"^\.{re.escape(_short_name(name))}\.{role}-(\d+)\.")
    try:
        entries = sorted(folder.iterdir())
    except OSError:
        return []
    return [e for e in entries if (m := pattern.match(e.name)) and not _running(int(m[1]))]


def remove_stale(folder: Path, name: str, role: str) -> list[Path]:
    """Remove the temporary files of ``name`` left by ended processes (a kill mid-write)."""
    removed = []
    for entry in stale_entries(folder, name, role):
        if entry.is_file() and not entry.is_symlink():
            entry.unlink(missing_ok=True)
            removed.append(entry)
    return removed


def _text(path: str | os.PathLike[str]) -> str:
    text = os.fspath(path)
    if not text:
        raise HexalegError("an empty path names no file or folder: give a name")
    return text


def _short_name(name: str) -> str:
    return os.fsencode(name)[:_SHORT_NAME].decode("utf-8", errors="ignore")


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # alive, owned by someone else
        pass
    return True


def _stat(path: Path) -> os.stat_result | None:
    try:
        return path.stat()
    except OSError as err:  # a name too long, a loop of links, a file in the path
        if err.errno in (errno.ENOENT, errno.ENOTDIR, errno.ENAMETOOLONG):
            return None  # nothing there (a name too long is refused by check_creatable)
        raise HexalegError(f"cannot write {shown(path)}: {os_reason(err)}") from None


def _name_max(folder: Path) -> int:
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):
        return 255


def _refuse_unwritable_file(text: str, target: Path, existing: os.stat_result | None) -> None:
    if existing is None:
        check_creatable(text, target)
        return
    try:  # opening for writing, without truncating, changes nothing
        os.close(os.open(target, os.O_WRONLY | os.O_NONBLOCK | os.O_CLOEXEC))
    except OSError as err:
        if err.errno != errno.EACCES:
            raise HexalegError(f"cannot write {shown(text)}: {os_reason(err)}") from None
        raise HexalegError(
            f"{shown(text)} is read-only (mode {stat.S_IMODE(existing.st_mode):04o}): "
            "make it writable, or choose another name"
        ) from None
    if not _in_place(target, existing):
        check_creatable(text, target)  # the rename needs to write its folder


def _in_place(target: Path, existing: os.stat_result) -> bool:
    """Other hard links share the file, or its folder is not ours to write: keep the inode."""
    return existing.st_nlink > 1 or not os.access(target.parent, os.W_OK | os.X_OK)


def standard_stream(text: str) -> int | None:
    """The descriptor ``text`` names (``-``, ``/dev/stdout``, ``/dev/fd/N``), or None."""
    match = _STREAM.match(text)
    return int(match.group(1)) if match else _STREAMS.get(text)


def _write_stream(fd: int, data: bytes) -> None:
    """Write to this process's own stdout, stderr or descriptor ``fd``."""
    stream = {1: sys.stdout, 2: sys.stderr}.get(fd)
    if fd in (1, 2) and stream is None:
        name = "output" if fd == 1 else "error"
        raise HexalegError(f"standard {name} is closed: pass -o FILE, or open it")
    if stream is None:
        _write_all(fd, data)
        return
    buffer = getattr(stream, "buffer", None)
    if buffer is None:  # a text-only stream (a test's StringIO)
        stream.write(data.decode("utf-8", errors="replace"))
    else:
        stream.flush()
        buffer.write(data)
    stream.flush()


def _write_direct(target: Path, data: bytes, truncate: bool = False) -> None:
    """Write into the existing file ``target`` itself: no temporary file, no rename."""
    fd = os.open(target, os.O_WRONLY | os.O_CLOEXEC)  # never O_CREAT: it must exist
    try:
        _write_all(fd, data)
        if truncate:
            os.ftruncate(fd, len(data))
            os.fsync(fd)
    finally:
        os.close(fd)


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


def _write_atomically(target: Path, data: bytes, existing: os.stat_result | None) -> None:
    """A temporary file beside ``target``, renamed over it once complete and on disk."""
    make_parents(target)
    remove_stale(target.parent, target.name, "tmp")
    fd, tmp = tempfile.mkstemp(prefix=stale_prefix(target.name, "tmp"), dir=target.parent)
    try:
        with os.fdopen(fd, "wb") as handle:
            if existing is None:
                os.fchmod(fd, 0o666 & ~current_umask())  # as open() would create it
            else:
                with contextlib.suppress(PermissionError):  # not root: ours, as an editor's
                    os.fchown(fd, existing.st_uid, existing.st_gid)
                os.fchmod(fd, stat.S_IMODE(existing.st_mode))
            handle.write(data)
            handle.flush()
            os.fsync(fd)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    fsync_folder(target.parent)
