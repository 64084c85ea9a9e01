"""A study's journal: one JSON line per finished design, appended as each task finishes.

The journal (``rows.jsonl`` in the study folder) starts with the study's fingerprint,
``{"spec": {...}}``; each further line is one design's row. It follows the rules of
every hexaleg journal (:mod:`hexaleg._journal`: torn last lines cut, corrupt lines named,
a full disk told in one line, the rows before kept for ``--resume``). A row is corrupt
when it has no ratios, ratios outside the grid, or no error column.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

from hexaleg._folders import MARKER, read_regular, write_marker
from hexaleg._io import os_reason, shown, write_text
from hexaleg._journal import Journal, JournalKind, append_records, header_key, read_records
from hexaleg.exceptions import HexalegError

JOURNAL = "rows.jsonl"
FOLDER_KIND = "study"
"""What a study folder's marker says it is."""
KIND = JournalKind("spec", "study", "-o")

Key = tuple[float, float]
"""(coxa ratio, tibia ratio) of a design [-]."""
Record = dict[str, Any]


def start_journal(
    folder: Path, fingerprint: dict[str, Any], keys: list[Key], resume: bool
) -> dict[Key, Record]:
    """Open the journal of a study in ``folder``; return the rows it already holds.

    A new journal is written with its fingerprint; an existing one is read (with
    ``resume`` only), checked against ``fingerprint`` and ``keys``, and its torn last
    line cut off. The caller holds the folder (:func:`~hexaleg._folders.lock_folder`).

    Raises:
        HexalegError: the journal exists without ``resume``, is corrupt, or belongs
            to a study with other options.

    """
    with Journal(folder / JOURNAL, KIND, fingerprint, _reader(keys), resume) as journal:
        return dict(journal.records)


def read_journal(
    journal: Path, fingerprint: dict[str, Any], keys: list[Key]
) -> tuple[dict[Key, Record], int]:
    """The rows of ``journal`` by ratio pair, and the length [bytes] of its whole lines."""
    data = read_regular(journal, shown(journal))
    rows, intact = read_records(data, KIND, fingerprint, _reader(keys), shown(journal))
    return dict(rows), intact


def append_rows(journal: Path, rows: list[Record]) -> None:
    """Append ``rows`` to ``journal``, one line each, on disk before returning.

    Raises:
        HexalegError: the write failed (a full disk); the journal is cut back to its
            last whole line.

    """
    try:
        fd = os.open(journal, os.O_WRONLY | os.O_APPEND | os.O_CLOEXEC)
    except OSError as err:
        raise HexalegError(f"cannot write {shown(journal)}: {os_reason(err)}") from None
    try:
        append_records(fd, rows, shown(journal))
    finally:
        os.close(fd)


def write_finished_journal(folder: Path, fingerprint: dict[str, Any], rows: list[Record]) -> Path:
    """Write a finished study's journal in one go, atomically."""
    records = [{KIND.key: fingerprint}, *rows]
    return write_text(folder / JOURNAL, "".join(json.dumps(r) + "\n" for r in records))


def adopt_unmarked_study(path: str | os.PathLike[str]) -> None:
    """Mark a study folder written before folders had markers (its journal says it is one)."""
    if not os.fspath(path):
        return
    folder = Path(path)
    if os.path.lexists(folder / MARKER) or not (folder / JOURNAL).is_file():
        return
    if header_key(folder / JOURNAL) == KIND.key:
        write_marker(folder, FOLDER_KIND)


def _reader(keys: list[Key]) -> Callable[[Record], tuple[Key, Record]]:
    grid = set(keys)

    def read(row: Record) -> tuple[Key, Record]:
        l1_ratio, l3_ratio = row.get("l1_ratio"), row.get("l3_ratio")
        if not isinstance(l1_ratio, float) or not isinstance(l3_ratio, float):
            raise ValueError("no ratios")
        key = (l1_ratio, l3_ratio)
        if not math.isfinite(l1_ratio + l3_ratio) or key not in grid:
            raise ValueError("ratios outside the grid")
        if not isinstance(row.get("error"), str):
            raise ValueError("no error column")
        return key, row

    return read
