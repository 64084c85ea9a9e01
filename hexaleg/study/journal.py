"""A study's journal: one JSON line per finished design, appended as each task finishes.

The journal (``rows.jsonl`` in the study folder) starts with the study's fingerprint,
``{"spec": {...}}``, written with the file; each further line is one design's row. It is
read strictly, so that a resumed study never mixes in rows it cannot trust:

- a last line without its newline is a *torn* write (a kill, a full disk): it is cut
  off before anything is appended, and its design computed again;
- any other line that is not a row of this study (not JSON, not an object, no ratios,
  ratios outside the grid, a second header) is corrupt: "line N is corrupt", refused;
- a journal without its fingerprint, or with another study's, is refused.

An append that fails (a full disk) is undone to the last whole line and reported in
one line; the rows before it stay, and ``--resume`` continues from them.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import stat
from pathlib import Path
from typing import Any

from hexaleg._folders import MARKER, write_marker
from hexaleg._io import os_reason, write_text
from hexaleg.exceptions import HexalegError

JOURNAL = "rows.jsonl"
FOLDER_KIND = "study"
"""What a study folder's marker says it is."""

Key = tuple[float, float]
"""(coxa ratio, tibia ratio) of a design [-]."""
Record = dict[str, Any]


def start_journal(
    folder: Path, fingerprint: dict[str, Any], keys: list[Key], resume: bool
) -> dict[Key, Record]:
    """Open the journal of a study in ``folder``; return the rows it already holds.

    A new journal is written with its fingerprint; an existing one is read (with
    ``resume`` only), checked against ``fingerprint`` and ``keys``, and its torn last
    line cut off.

    Raises:
        HexalegError: the journal exists without ``resume``, is corrupt, or belongs
            to a study with other options.

    """
    journal = folder / JOURNAL
    if not os.path.lexists(journal):
        write_text(journal, _lines([{"spec": fingerprint}]))
        return {}
    if not resume:
        raise HexalegError(
            f"{folder} already holds a study: pass --resume to continue it, or choose another -o"
        )
    rows, intact = read_journal(journal, fingerprint, keys)
    if intact < journal.stat().st_size:
        try:
            os.truncate(journal, intact)
        except OSError as err:
            raise HexalegError(f"cannot cut the torn line of {journal}: {os_reason(err)}") from None
    return rows


def read_journal(
    journal: Path, fingerprint: dict[str, Any], keys: list[Key]
) -> tuple[dict[Key, Record], int]:
    """The rows of ``journal`` by ratio pair, and the length [bytes] of its whole lines."""
    data = _read_regular(journal)
    intact = data.rfind(b"\n") + 1  # what follows the last newline is a torn write
    lines = data[:intact].split(b"\n")[:-1]
    if not lines:
        raise HexalegError(
            f"{journal} holds no study fingerprint (the study stopped before it began): "
            "remove the folder, or choose another -o"
        )
    if _parse(journal, 1, lines[0]) != {"spec": json.loads(json.dumps(fingerprint))}:
        raise HexalegError(
            f"{journal.parent} holds a study with other options; resume it with the same ones"
        )
    grid = set(keys)
    rows: dict[Key, Record] = {}
    for number, line in enumerate(lines[1:], start=2):
        row = _parse(journal, number, line)
        key = _row_key(row)
        if key is None or key not in grid or not isinstance(row.get("error"), str):
            raise _corrupt(journal, number)
        rows[key] = row
    return rows, intact


def append_rows(journal: Path, rows: list[Record]) -> None:
    """Append ``rows`` to ``journal``, one line each, on disk before returning.

    Raises:
        HexalegError: the write failed (a full disk); the journal is cut back to its
            last whole line.

    """
    data = _lines(rows).encode("utf-8")
    try:
        fd = os.open(journal, os.O_WRONLY | os.O_APPEND | os.O_CLOEXEC)
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
        finally:
            os.close(fd)
    except OSError as err:
        raise HexalegError(
            f"cannot write {journal}: {os_reason(err)}; the rows before are kept, "
            "continue with --resume"
        ) from None


def write_finished_journal(folder: Path, fingerprint: dict[str, Any], rows: list[Record]) -> Path:
    """Write a finished study's journal in one go, atomically."""
    return write_text(folder / JOURNAL, _lines([{"spec": fingerprint}, *rows]))


def adopt_unmarked_study(path: str | os.PathLike[str]) -> None:
    """Mark a study folder written before folders had markers (its journal says it is one)."""
    if not os.fspath(path):
        return
    folder = Path(path)
    journal = folder / JOURNAL
    if os.path.lexists(folder / MARKER) or not journal.is_file():
        return
    with journal.open("rb") as handle:
        first = handle.readline(1 << 20)
    try:
        header = json.loads(first)
    except ValueError:
        return
    if isinstance(header, dict) and set(header) == {"spec"}:
        write_marker(folder, FOLDER_KIND)


def _lines(records: list[Record]) -> str:
    return "".join(json.dumps(record, allow_nan=True) + "\n" for record in records)


def _read_regular(journal: Path) -> bytes:
    try:
        fd = os.open(journal, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)  # a FIFO: no wait
    except OSError as err:
        raise HexalegError(f"cannot read {journal}: {os_reason(err)}") from None
    with os.fdopen(fd, "rb") as handle:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise HexalegError(f"{journal} is not a regular file")
        try:
            return handle.read()
        except OSError as err:
            raise HexalegError(f"cannot read {journal}: {os_reason(err)}") from None


def _parse(journal: Path, number: int, line: bytes) -> Record:
    try:
        record = json.loads(line)
    except (ValueError, RecursionError):
        raise _corrupt(journal, number) from None
    if not isinstance(record, dict):
        raise _corrupt(journal, number)
    return record


def _row_key(row: Record) -> Key | None:
    l1_ratio, l3_ratio = row.get("l1_ratio"), row.get("l3_ratio")
    if isinstance(l1_ratio, float) and isinstance(l3_ratio, float):
        return (l1_ratio, l3_ratio) if math.isfinite(l1_ratio + l3_ratio) else None
    return None


def _corrupt(journal: Path, number: int) -> HexalegError:
    return HexalegError(
        f"{journal}: line {number} is corrupt (not a row of this study): repair or remove "
        "that line, or choose another -o"
    )
