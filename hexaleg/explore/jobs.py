"""The explorer's long jobs: a free-coupled search, the best posture or a decision.

A job is the command line itself (``hexaleg flexibility --mode free --json``, ``hexaleg
posture --json`` or ``hexaleg decide --json``) on the design the sliders show, written to a
temporary design file with the session's ``[requirements]``: its numbers are the command's,
and, being
another process, it never slows the sliders' evaluations down. Its progress is read
from the command's own progress lines on its stderr (:mod:`hexaleg.study.progress`,
printed at every step here: :mod:`hexaleg.cli.job_runner`), its answer
from its stdout. One job of each kind at a time; starting one again stops the first; a
job is stopped by its process id; all are stopped when the explorer stops.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

from hexaleg.evaluation.metrics import Better, objectives
from hexaleg.exceptions import ParameterError

__all__ = ["JOB_KINDS", "JOB_OPTIONS", "Job", "Jobs", "job_options", "require_job_kind"]

JOB_KINDS: dict[str, tuple[str, ...]] = {
    "free": ("flexibility", "--mode", "free", "--json"),
    "posture": ("posture", "--json"),
    "decide": ("decide", "--json"),
}
"""Each kind of job: the hexaleg command and options it runs on the shown design."""

JOB_OPTIONS: dict[str, tuple[str, ...]] = {"posture": ("maximize", "minimize")}
"""The keys a request may add for a kind of job: each its command's option of that name."""

PROGRESS_LINE = re.compile(r"^hexaleg: (\d+)/(\d+) ")
"""A progress line of :class:`~hexaleg.study.progress.Progress`: ``done/total``."""


@dataclass
class Job:
    """One running or finished job.

    Attributes:
        kind: ``"free"`` or ``"decide"``.
        process: The command's process.
        folder: The temporary folder holding its design file (removed when it ends).
        started: When it started (monotonic clock) [s].
        done: Steps finished, from its last progress line.
        total: Steps in all (0 until its first progress line).
        answer: Its JSON answer, once it has ended well.
        error: Its last stderr line, if it ended badly.

    """

    kind: str
    process: subprocess.Popen[str]
    folder: tempfile.TemporaryDirectory[str]
    started: float = field(default_factory=time.monotonic)
    done: int = 0
    total: int = 0
    answer: dict[str, Any] | None = None
    error: str = ""
    ended: threading.Event = field(default_factory=threading.Event)

    def state(self) -> str:
        """``running``, ``done``, ``failed`` or ``stopped``."""
        if not self.ended.is_set():
            return "running"
        if self.answer is not None:
            return "done"
        killed = (self.process.returncode or 0) < 0  # ended by a signal: stopped
        return "stopped" if killed else "failed"

    def to_dict(self) -> dict[str, Any]:
        """What the page shows: state, progress, elapsed time [s], the answer or the error."""
        return {
            "kind": self.kind,
            "pid": self.process.pid,
            "state": self.state(),
            "done": self.done,
            "total": self.total,
            "elapsed": time.monotonic() - self.started,
            "answer": self.answer,
            "error": self.error,
        }

    def follow(self) -> None:
        """Read its progress lines to the end, then its answer (run in a thread)."""
        assert self.process.stderr is not None and self.process.stdout is not None
        last, crashed = "", False
        for line in self.process.stderr:
            found = PROGRESS_LINE.match(line)
            if found:
                self.done, self.total = int(found[1]), int(found[2])
            elif line.strip():
                last = line.strip()
                crashed = crashed or line.startswith("Traceback ")
        out = self.process.stdout.read()
        status = self.process.wait()
        if status == 0:
            try:
                self.answer = json.loads(out)
            except json.JSONDecodeError:
                self.error = "the command's answer is not JSON"
        elif crashed:  # a bug, not the user's mistake: one line, and where to see more
            command = JOB_KINDS[self.kind][0]
            self.error = f"hexaleg {command} crashed ({last}): run it in a terminal to see why"
        else:
            self.error = last or f"the command ended with status {status}"
        self.folder.cleanup()
        self.ended.set()

    def stop(self) -> None:
        """Stop its process (by its pid) and wait for it to end."""
        if not self.ended.is_set():
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
        self.ended.wait(timeout=10)


def require_job_kind(kind: str) -> str:
    """``kind`` if it names a job (:data:`JOB_KINDS`), else a ParameterError naming ``kind``."""
    if kind not in JOB_KINDS:
        raise ParameterError("kind", kind, f"must be one of {', '.join(JOB_KINDS)}")
    return kind


def job_options(kind: str, params: dict[str, str]) -> tuple[str, ...]:
    """The command-line options a request gives its job of ``kind``, taken out of ``params``.

    ``maximize=NAME`` or ``minimize=NAME`` (the posture's objective): a metric its command
    offers in that direction (:func:`~hexaleg.evaluation.metrics.objectives`).

    Raises:
        ParameterError: A value that is not one of them, or both keys given.

    """
    given = [key for key in JOB_OPTIONS.get(kind, ()) if key in params]
    if len(given) > 1:
        raise ParameterError(given[1], params[given[1]], f"give {given[0]} or {given[1]}, not both")
    options: list[str] = []
    for key in given:
        name, offered = params.pop(key), objectives(cast(Better, key))
        if name not in offered:
            raise ParameterError(key, name, f"must be one of {', '.join(offered)}")
        options += [f"--{key}", name]
    return tuple(options)


class Jobs:
    """The explorer's jobs, at most one of each kind running."""

    def __init__(self) -> None:
        self._jobs: dict[str, Job] = {}
        self._lock = threading.Lock()

    def start(self, kind: str, design_text: str, options: tuple[str, ...] = ()) -> Job:
        """Run the job ``kind`` on the design file text ``design_text`` (TOML).

        ``options``: more of its command's options (:func:`job_options`).
        """
        kind = require_job_kind(kind)
        with self._lock:
            if kind in self._jobs:
                self._jobs[kind].stop()
            folder = tempfile.TemporaryDirectory(prefix="hexaleg-explore-")
            design = Path(folder.name) / "design.toml"
            design.write_text(design_text, encoding="utf-8")
            command = [sys.executable, "-m", "hexaleg.cli.job_runner",
                       *JOB_KINDS[kind], *options, "--design", str(design)]  # fmt: skip
            process = subprocess.Popen(
                command,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
                cwd=folder.name,
            )
            job = Job(kind, process, folder)
            threading.Thread(target=job.follow, daemon=True).start()
            self._jobs[kind] = job
            return job

    def get(self, kind: str) -> Job | None:
        """The latest job of ``kind``, if one was started."""
        return self._jobs.get(kind)

    def stop(self, kind: str | None = None) -> None:
        """Stop the job of ``kind``, or every job."""
        with self._lock:
            for name, job in self._jobs.items():
                if kind is None or name == kind:
                    job.stop()
