"""The journal of a decision's searches: every evaluated design, one JSON line each.

A resumed search replays the same seeded algorithm and reads the designs it has already
evaluated from here instead of evaluating them again (:mod:`hexaleg.study.optimize`).
The first line, ``{"decide": {...}}``, holds what determines the results, checked on
resume; the file follows the rules of every hexaleg journal (:mod:`hexaleg._journal`),
and one decision at a time holds it.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Sequence
from typing import Any

from hexaleg._io import shown
from hexaleg._journal import Journal as JournalFile
from hexaleg._journal import JournalKind, Record
from hexaleg.evaluation.evaluate import Evaluation
from hexaleg.evaluation.metrics import Causes, Metrics

KIND = JournalKind("decide", "decision", "--journal")
Point = tuple[str, tuple[float, ...]]
"""A search's key and a point of it."""


class Journal:
    """Every evaluated design of a decision, one JSON line each, for resuming.

    Args:
        path: The journal file; ``None`` keeps nothing.
        header: What determines the results (checked on resume).
        resume: Continue an existing journal instead of refusing to overwrite it.

    """

    def __init__(self, path: str | os.PathLike[str] | None, header: dict[str, Any], resume: bool):
        self._file: JournalFile[tuple[Point, Evaluation]] | None = None
        self._rows: dict[Point, Evaluation] = {}
        if path is not None:
            name = f"--journal {shown(path)}"
            self._file = JournalFile(path, KIND, header, _read, resume, "decide", name)
            self._rows = dict(self._file.records)

    def lookup(self, key: str, x: tuple[float, ...]) -> Evaluation | None:
        """The evaluation of point ``x`` in search ``key``, if journalled."""
        return self._rows.get((key, x))

    def record(
        self, key: str, points: Sequence[tuple[float, ...]], found: Sequence[Evaluation]
    ) -> None:
        """Keep these evaluations (on disk before returning)."""
        for x, evaluation in zip(points, found, strict=True):
            self._rows[(key, x)] = evaluation
        if self._file is not None:
            self._file.append([_record(key, x, e) for x, e in zip(points, found, strict=True)])

    def close(self) -> None:
        """Release the journal file (another decision may then resume it)."""
        if self._file is not None:
            self._file.close()

    def __enter__(self) -> Journal:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()


def _record(key: str, x: tuple[float, ...], evaluation: Evaluation) -> Record:
    causes = {s.name: c.to_dict() for s, c in evaluation.causes.items() if c is not None}
    return {
        "search": key,
        "x": list(x),
        "values": evaluation.metrics.to_dict(),
        "causes": causes,
        "error": evaluation.error,
    }


def _read(record: Record) -> tuple[Point, Evaluation]:
    """A journal line back as its point and evaluation; ValueError if it is not one."""
    key, x, values, causes, error = (
        record[name] for name in ("search", "x", "values", "causes", "error")
    )
    typed = isinstance(key, str) and isinstance(error, str) and isinstance(causes, dict)
    if not (typed and isinstance(x, list) and _numbers(x) and isinstance(values, dict)):
        raise ValueError("not an evaluated point of a search")
    if not _numbers(values.values()) or not all(math.isfinite(v) for v in x):
        raise ValueError("not an evaluated point of a search")
    found = Evaluation(Metrics.from_dict(values), Causes.from_dict(causes), error)
    return (key, tuple(float(v) for v in x)), found


def _numbers(values: Iterable[Any]) -> bool:
    return all(isinstance(v, int | float) and not isinstance(v, bool) for v in values)
