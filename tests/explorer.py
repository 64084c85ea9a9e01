"""An explorer started as its own process for the tests: its URL, its pid, a bounded stop.

``hexaleg explore`` runs as a subprocess on the host given, port 0 (the system picks),
its URL read from its first line within a bounded wait; the test stops it by its pid
(SIGTERM, then SIGKILL after a bound) and reads how it ended.
"""

from __future__ import annotations

import contextlib
import json
import os
import queue
import signal
import subprocess
import sys
import threading
import urllib.error
import urllib.request
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import pytest

START_TIMEOUT = 120
"""Bound on the explorer's start [s]."""
REQUEST_TIMEOUT = 60
"""Bound on one request [s]."""


@dataclass
class Explorer:
    """A running explorer: its process and the URL it printed."""

    process: subprocess.Popen[str]
    url: str

    def get(self, path: str) -> tuple[int, Any]:
        """The status and JSON of ``GET path``."""
        return _request(urllib.request.Request(self.url + path.lstrip("/")))

    def post(self, path: str) -> tuple[int, Any]:
        """The status and JSON of ``POST path`` (an empty body)."""
        return _request(urllib.request.Request(self.url + path.lstrip("/"), b"", method="POST"))

    def stop(self, signum: int = signal.SIGTERM) -> tuple[int, str]:
        """Send ``signum`` to its pid; its exit status and what it wrote on stderr."""
        with contextlib.suppress(ProcessLookupError):
            os.kill(self.process.pid, signum)
        try:
            _, err = self.process.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            self.process.kill()
            _, err = self.process.communicate(timeout=30)
            pytest.fail(f"the explorer did not stop within 30 s of signal {signum}")
        return self.process.returncode, err


def _request(request: urllib.request.Request) -> tuple[int, Any]:
    try:
        with urllib.request.urlopen(request, timeout=REQUEST_TIMEOUT) as answer:
            return answer.status, json.load(answer)
    except urllib.error.HTTPError as err:
        return err.code, json.load(err)


@contextlib.contextmanager
def running(*arguments: str, cwd: str | os.PathLike[str] | None = None) -> Iterator[Explorer]:
    """``hexaleg explore ARGUMENTS --port 0`` (in folder ``cwd``), stopped by its pid after."""
    process = subprocess.Popen(
        [sys.executable, "-m", "hexaleg", "explore", *arguments, "--port", "0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
    )
    lines: queue.Queue[str] = queue.Queue()
    assert process.stdout is not None
    stdout = process.stdout
    threading.Thread(target=lambda: lines.put(stdout.readline()), daemon=True).start()
    explorer = Explorer(process, "")
    try:
        try:
            first = lines.get(timeout=START_TIMEOUT)
        except queue.Empty:
            pytest.fail(f"the explorer printed no URL within {START_TIMEOUT} s")
        if not first.startswith("hexaleg explore: open http"):
            process.kill()
            pytest.fail(f"the explorer did not start: {first!r} {process.communicate()[1]!r}")
        explorer.url = first.split("open ", 1)[1].strip()
        yield explorer
    finally:
        if process.poll() is None:
            explorer.stop()
