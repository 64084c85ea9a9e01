"""The Xacro expansion's own process: limits first, then xacro, the URDF on standard output.

Run by :func:`~hexaleg.robot.source.expand_xacro` as ``python -m
hexaleg.robot._xacro_process`` with a JSON request on standard input (the file, its
arguments and package folders, the limits). Before xacro runs, the process limits its own
memory (``RLIMIT_AS``), CPU time (``RLIMIT_CPU``, a backstop should its parent die) and file
writes (``RLIMIT_FSIZE`` 0: an expansion writes nothing). What xacro prints is kept out of
the pipes (at most :data:`~hexaleg.robot.source.MAX_XACRO_CHATTER` of it is kept to find
its warnings in); the URDF goes to standard output and xacro's warnings, marked, to
standard error (:func:`~hexaleg.robot.source.warning_lines`), a refusal as one line to
standard error with exit status :data:`REFUSED`.
"""

from __future__ import annotations

import io
import json
import os
import resource
import sys
from typing import Any

from hexaleg.exceptions import RobotImportError
from hexaleg.robot.source import (
    MAX_XACRO_CHATTER,
    package_folders,
    past_memory,
    warning_lines,
    xacro_cpu_seconds,
    xacro_text,
    xacro_warnings,
)

REFUSED = 3
"""Exit status of a refusal (its line on standard error)."""


def main() -> int:
    """Expand the requested file within its limits; the exit status."""
    request: dict[str, Any] = json.load(sys.stdin)
    _limit(request["memory"], request["seconds"])
    out = os.fdopen(os.dup(1), "wb")
    printed = _Kept(MAX_XACRO_CHATTER)
    sys.stdout = sys.stderr = printed  # xacro's chatter, whatever its size
    packages = package_folders(request["packages"])
    try:
        text = xacro_text(request["path"], request["args"], packages, request["output"])
    except RobotImportError as err:
        return _refuse(str(err))
    except MemoryError:
        return _refuse(past_memory(request["path"], request["memory"]))
    out.write(text.encode("utf-8"))
    out.close()
    os.write(2, warning_lines(xacro_warnings(printed.text)).encode("utf-8", errors="replace"))
    return 0


class _Kept(io.TextIOBase):
    """A text stream that keeps the first ``limit`` characters written to it."""

    def __init__(self, limit: int) -> None:
        self._limit = limit
        self._parts: list[str] = []
        self._kept = 0

    def write(self, text: str) -> int:
        room = self._limit - self._kept
        if room > 0:
            self._parts.append(text[:room])
            self._kept += min(room, len(text))
        return len(text)

    @property
    def text(self) -> str:
        """What was kept."""
        return "".join(self._parts)


def _limit(memory: int, seconds: float) -> None:
    """Lower this process's limits (never above what it was already held to)."""
    for kind, value in (
        (resource.RLIMIT_AS, memory),
        (resource.RLIMIT_CPU, xacro_cpu_seconds(seconds)),
        (resource.RLIMIT_FSIZE, 0),
    ):
        hard = resource.getrlimit(kind)[1]
        value = value if hard == resource.RLIM_INFINITY else min(value, hard)
        resource.setrlimit(kind, (value, hard))


def _refuse(message: str) -> int:
    os.write(2, (" ".join(message.split()) + "\n").encode("utf-8", errors="replace"))
    return REFUSED


if __name__ == "__main__":
    sys.exit(main())
