"""The journal of a decision's searches: every evaluated design, one JSON line each.

A resumed search replays the same seeded algorithm and reads the designs it has already
evaluated from here instead of evaluating them again (:mod:`hexaleg.study.optimize`).
The first line holds what determines the results, checked on resume; a last line cut
short when the process was stopped is dropped before new lines are appended.
"""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from hexaleg._io import atomic_write_text
from hexaleg.cause import Cause
from hexaleg.exceptions import HexalegError
from hexaleg.study.evaluation import Evaluation


class Journal:
    """Every evaluated design of a decision, one JSON line each, for resuming.

    Args:
        path: The journal file; ``None`` keeps nothing.
        header: What determines the results (checked on resume).
        resume: Continue an existing journal instead of refusing to overwrite it.

    """

    def __init__(self, path: str | os.PathLike[str] | None, header: dict[str, Any], resume: bool):
        self.path = None if path is None else Path(path)
        self._rows: dict[tuple[str, tuple[float, ...]], Evaluation] = {}
        if self.path is None:
            return
        header = json.loads(json.dumps(header))
        if self.path.exists() and not resume:
            raise HexalegError(
                f"--journal {self.path} exists: pass --resume to continue it, or choose another"
            )
        if resume and self.path.exists():
            self._read(header)
        else:
            self._append([{"decide": header}])

    def lookup(self, key: str, x: tuple[float, ...]) -> Evaluation | None:
        """The evaluation of point ``x`` in search ``key``, if journalled."""
        return self._rows.get((key, x))

    def record(
        self, key: str, points: Sequence[tuple[float, ...]], found: Sequence[Evaluation]
    ) -> None:
        """Keep these evaluations (on disk before returning)."""
        for x, evaluation in zip(points, found, strict=True):
            self._rows[(key, x)] = evaluation
        self._append(
            [
                {"search": key, "x": list(x), **_to_json(e)}
                for x, e in zip(points, found, strict=True)
            ]
        )

    def _append(self, records: list[dict[str, Any]]) -> None:
        if self.path is None:
            return
        try:
            with self.path.open("a", encoding="utf-8") as handle:
                handle.write("".join(json.dumps(r) + "\n" for r in records))
                handle.flush()
                os.fsync(handle.fileno())
        except OSError as err:
            raise HexalegError(f"--journal {self.path}: cannot write it ({err.strerror})") from None

    def _read(self, header: dict[str, Any]) -> None:
        assert self.path is not None
        try:
            text = self.path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as err:
            raise HexalegError(f"--journal {self.path}: cannot read it ({err})") from None
        if text and not text.endswith("\n"):  # the line being written when it was stopped
            text = text[: text.rfind("\n") + 1]
            atomic_write_text(self.path, text)
        lines = text.splitlines()
        if not lines or _header(lines[0]) != header:
            raise HexalegError(
                f"--journal {self.path} holds no decision with these options; resume it with "
                "the same ones"
            )
        for number, line in enumerate(lines[1:], start=2):
            try:
                record = json.loads(line)
                x = tuple(float(v) for v in record["x"])
                self._rows[(record["search"], x)] = _from_json(record)
            except (json.JSONDecodeError, KeyError, TypeError, ValueError):
                raise HexalegError(f"{self.path}: line {number} is corrupt") from None


def _header(line: str) -> Any:
    """What a journal's first line says determines its results (None: not a journal)."""
    try:
        record = json.loads(line)
    except json.JSONDecodeError:
        return None
    return record.get("decide") if isinstance(record, dict) else None


def _to_json(evaluation: Evaluation) -> dict[str, Any]:
    causes = {
        metric: {"kind": c.kind, "leg": c.leg, "joint": c.joint, "bound": c.bound}
        for metric, c in evaluation.causes.items()
    }
    return {"values": dict(evaluation.values), "causes": causes, "error": evaluation.error}


def _from_json(record: dict[str, Any]) -> Evaluation:
    causes = {metric: Cause(**cause) for metric, cause in record["causes"].items()}
    return Evaluation(record["values"], causes, record["error"])
