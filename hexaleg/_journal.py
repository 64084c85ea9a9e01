"""Journals: a header, then one JSON record a line, each on disk as soon as it is known.

A journal (a study's ``rows.jsonl``, ``decide --journal FILE``) starts with its header,
``{KEY: fingerprint}``: KEY names the kind of journal (``spec`` for a study, ``decide`` for
a decision's searches), the fingerprint what determines its records. It is read strictly,
so that a resumed run never mixes in records it cannot trust, and hexaleg never writes to
a file that is not its own journal:

- only a regular file is opened (a FIFO is refused at once, never waited on), and its
  header read before anything is written: a file whose first line is not a header of
  this kind, or one of another fingerprint (other options), is refused untouched;
- a last line without its newline is *torn* (a kill, a full disk): once every other
  line has been read it is cut off, before anything is appended;
- any other line the reader cannot take is corrupt: "line N is corrupt", refused;
- a file holding no whole line, only the start of a header (a run stopped while
  creating it), holds no record: a new run starts it again; ``--resume`` says so;
- an append is on disk (written whole, fsynced) before it returns; one that fails (a
  full disk) is cut back to the last whole line and reported in one line;
- one run at a time holds a journal opened with ``lock`` (:func:`hexaleg._folders.hold`).
"""

from __future__ import annotations

import contextlib
import json
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Generic, NamedTuple, TypeVar

from hexaleg._folders import hold, open_regular, read_regular
from hexaleg._io import (
    check_output_file,
    fsync_folder,
    make_parents,
    os_reason,
    shown,
    standard_stream,
)
from hexaleg.exceptions import HexalegError

T = TypeVar("T")
Record = dict[str, Any]
CORRUPT = (ValueError, KeyError, TypeError, AttributeError, RecursionError)
"""What a reader of records raises for a line it cannot take: the line is corrupt."""


class JournalKind(NamedTuple):
    """Which journal a file is: its header's key, and what it and its option are called."""

    key: str
    what: str
    option: str


class Journal(Generic[T]):
    """An open journal: :attr:`records` read and checked; :meth:`append` adds more.

    Args:
        path: The journal file; missing folders on its path are created.
        kind: Which journal it is.
        fingerprint: What determines its records (JSON-ready), checked on resume.
        read: Turns one record (a JSON object) into what the caller keeps; raising one
            of :data:`CORRUPT` says the line is corrupt.
        resume: Continue an existing journal; without it, one is refused.
        lock: Hold the journal for this run, as this command (``decide``); ``None`` when
            the caller holds it otherwise (a study locks its folder).
        name: The journal in messages (default: its path).

    Raises:
        HexalegError: see the module: one line, and the file untouched.

    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        kind: JournalKind,
        fingerprint: Any,
        read: Callable[[Record], T],
        resume: bool,
        lock: str | None = None,
        name: str | None = None,
    ) -> None:
        if not os.fspath(path):
            raise HexalegError(f"{kind.option} is empty: name a file")
        self.name = name or shown(path)
        if standard_stream(os.fspath(path)) is not None:
            raise HexalegError(f"{self.name}: a journal is read back, so it must be a file")
        self.path, self._kind = check_output_file(path), kind
        self._header = {kind.key: json.loads(json.dumps(fingerprint))}
        existed = os.path.lexists(self.path)
        make_parents(self.path)
        self._fd = open_regular(self.path, os.O_RDWR | os.O_APPEND | os.O_CREAT, self.name)
        self._held = contextlib.ExitStack()
        try:
            if lock is not None:
                self._held.enter_context(hold(self._fd, self.name, lock))
            self.records = self._open(_read_all(self._fd), read, resume, existed)
        except BaseException:
            self.close()
            if not existed:
                self.path.unlink(missing_ok=True)
            raise

    def append(self, records: Sequence[Record]) -> None:
        """Add ``records``, one line each, on disk before returning (see the module)."""
        append_records(self._fd, records, self.name)

    def close(self) -> None:
        """Release the journal (and its lock)."""
        if self._fd >= 0:
            self._held.close()
            os.close(self._fd)
            self._fd = -1

    def __enter__(self) -> Journal[T]:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()

    def _open(
        self, data: bytes, read: Callable[[Record], T], resume: bool, existed: bool
    ) -> list[T]:
        kind, state = self._kind, _state(data, self._kind.key)
        if state == "foreign":
            raise HexalegError(
                f"{self.name} is not a hexaleg {kind.what} journal (its first line is not one): "
                f"hexaleg writes only to its own; choose another {kind.option}"
            )
        if state == "start" and resume and existed:
            raise HexalegError(
                f"{self.name} holds no {kind.what} fingerprint: its first line is incomplete "
                "(a run stopped while starting it), so there is nothing to resume; run "
                "without --resume to start it again"
            )
        if state == "start":
            os.ftruncate(self._fd, 0)
            append_records(self._fd, [self._header], self.name)
            fsync_folder(self.path.parent)
            return []
        if not resume:
            raise HexalegError(
                f"{self.name} exists: pass --resume to continue it, or choose another {kind.option}"
            )
        records, intact = read_records(data, kind, self._header[kind.key], read, self.name)
        try:
            os.ftruncate(self._fd, intact)
        except OSError as err:
            message = f"cannot cut the torn line of {self.name}: {os_reason(err)}"
            raise HexalegError(message) from None
        return records


def read_records(
    data: bytes, kind: JournalKind, fingerprint: Any, read: Callable[[Record], T], name: str
) -> tuple[list[T], int]:
    """The records of the journal ``data``, and the length [bytes] of its whole lines."""
    intact = data.rfind(b"\n") + 1  # what follows the last newline is a torn write
    lines = data[:intact].split(b"\n")[:-1]
    header = _object(lines[0]) if lines else None
    if header is None or list(header) != [kind.key]:
        raise HexalegError(f"{name} holds no {kind.what} fingerprint: choose another {kind.option}")
    if header[kind.key] != json.loads(json.dumps(fingerprint)):
        raise HexalegError(
            f"{name} holds no {kind.what} with these options (it was started with other "
            f"options): resume it with the same ones, or choose another {kind.option}"
        )
    records = []
    for number, line in enumerate(lines[1:], start=2):
        record = _object(line)
        try:
            if record is None:
                raise ValueError("not a JSON object")
            records.append(read(record))
        except CORRUPT:
            raise HexalegError(
                f"{name}: line {number} is corrupt (not a record of this {kind.what}): repair "
                f"or remove that line, or choose another {kind.option}"
            ) from None
    return records, intact


def append_records(fd: int, records: Sequence[Record], name: str) -> None:
    """Append ``records`` to the journal open as ``fd`` (``O_APPEND``), on disk when done.

    Raises:
        HexalegError: the write failed (a full disk); the journal is cut back to its
            last whole line.

    """
    data = "".join(json.dumps(record, allow_nan=True) + "\n" for record in records).encode()
    try:
        size = os.fstat(fd).st_size
        try:
            view = memoryview(data)
            while view:
                view = view[os.write(fd, view) :]
            os.fsync(fd)
        except OSError:
            with contextlib.suppress(OSError):  # no half line left, if the system lets us
                os.ftruncate(fd, size)
            raise
    except OSError as err:
        raise HexalegError(
            f"cannot write {name}: {os_reason(err)}; the records before are kept, "
            "continue with --resume"
        ) from None


def header_key(path: Path) -> str | None:
    """The key of the journal header ``path`` starts with, or None (not a journal)."""
    try:
        header = _object(read_regular(path, shown(path)).partition(b"\n")[0])
    except HexalegError:
        return None
    return next(iter(header)) if header is not None and len(header) == 1 else None


def _state(data: bytes, key: str) -> str:
    """``start`` (nothing, or the first bytes of a header), ``journal`` or ``foreign``."""
    start = json.dumps({key: None})[: len(key) + 5].encode()  # b'{"key": '
    first, newline, _ = data.partition(b"\n")
    if not newline and (start.startswith(data) or data.startswith(start)):
        return "start"
    header = _object(first) if newline else None
    return "journal" if header is not None and list(header) == [key] else "foreign"


def _object(line: bytes) -> Record | None:
    try:
        record = json.loads(line)
    except (ValueError, RecursionError):
        return None
    return record if isinstance(record, dict) else None


def _read_all(fd: int) -> bytes:
    chunks, offset = [], 0
    while chunk := os.pread(fd, 1 << 20, offset):
        chunks.append(chunk)
        offset += len(chunk)
    return b"".join(chunks)
