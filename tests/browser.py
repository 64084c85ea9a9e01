"""Headless Chromium for the viewer's tests: a page's screenshot, or its layout as laid out.

Chromium draws WebGL with SwiftShader (no GPU here). :func:`screenshot` returns the
pixels; :func:`evaluate` runs a JavaScript expression in the loaded page through the
DevTools protocol (on a loopback port Chromium picks) and returns its JSON value, for
checks a picture cannot make, such as where an element lies and what covers it.
Every wait is bounded, and the browser is stopped by its own pid.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import shutil
import signal
import subprocess
import tempfile
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
TIMEOUT = 120
"""Bound on one browser run: start, load, draw [s]."""
FLAGS = (
    "--headless",
    "--no-sandbox",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--window-size=800,600",
)


def require_chromium() -> str:
    """The browser's path; skip (fail on CI, which must install it) when there is none."""
    if CHROMIUM is None:
        if os.environ.get("CI"):
            pytest.fail("chromium is not installed: .ci/run must install it")
        pytest.skip("chromium is not installed")
    return CHROMIUM


def screenshot(url: str, path: Path) -> np.ndarray:
    """The page at ``url`` as RGB pixels (800 × 600), after 10 s of its virtual time."""
    from PIL import Image

    with _chromium("--virtual-time-budget=10000", f"--screenshot={path}", url) as (browser, _):
        try:
            status = browser.wait(timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            pytest.fail(f"chromium drew no screenshot within {TIMEOUT} s")
        assert status == 0, f"chromium exited with status {status}"
    return np.asarray(Image.open(path).convert("RGB"), dtype=int)


def evaluate(url: str, expression: str) -> Any:
    """The JSON value of ``expression`` (a promise is awaited) in the page at ``url``."""
    debugging = ("--remote-debugging-address=127.0.0.1", "--remote-debugging-port=0", url)
    with _chromium(*debugging) as (_, profile):
        socket_url = _page_socket(profile / "DevToolsActivePort", url)
        return asyncio.run(asyncio.wait_for(_evaluate(socket_url, expression), TIMEOUT))


@contextlib.contextmanager
def _chromium(*arguments: str) -> Iterator[tuple[subprocess.Popen[bytes], Path]]:
    """Chromium on a fresh profile, in its own process group, stopped (group and all) on exit.

    Chromium's helpers (renderer, GPU, crash handler) outlive the browser's own pid by a
    moment and keep writing into the profile: the whole group is stopped, and waited for,
    before the profile is removed.
    """
    with tempfile.TemporaryDirectory() as folder:
        profile = Path(folder)
        browser = subprocess.Popen(
            [require_chromium(), *FLAGS, f"--user-data-dir={profile}", *arguments],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )
        try:
            yield browser, profile
        finally:
            _stop_group(browser)


def _stop_group(browser: subprocess.Popen[bytes]) -> None:
    """SIGTERM the browser's process group, SIGKILL what is left after 30 s; reap it all."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(browser.pid, sig)
        with contextlib.suppress(subprocess.TimeoutExpired):
            browser.wait(timeout=30)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            try:
                os.killpg(browser.pid, 0)  # anyone left in the group?
            except ProcessLookupError:
                return
            time.sleep(0.1)


def _page_socket(active_port: Path, url: str) -> str:
    """The DevTools WebSocket of the browser's page, once it is at ``url``."""
    deadline = time.monotonic() + TIMEOUT
    while time.monotonic() < deadline:
        lines = active_port.read_text().split() if active_port.exists() else []
        if len(lines) == 2:
            with urllib.request.urlopen(f"http://127.0.0.1:{lines[0]}/json/list", timeout=30) as r:
                pages = [t for t in json.load(r) if t["type"] == "page" and t["url"] == url]
            if pages:
                return str(pages[0]["webSocketDebuggerUrl"])
        time.sleep(0.2)
    pytest.fail(f"chromium opened no DevTools port within {TIMEOUT} s")


async def _evaluate(socket_url: str, expression: str) -> Any:
    """Evaluate ``expression`` in the page; again while the page is still loading."""
    while True:
        answer = await _evaluate_once(socket_url, expression)
        if answer.get("error", {}).get("message") != "Execution context was destroyed.":
            break
        await asyncio.sleep(0.2)  # the page navigated under the expression: ask again
    if "error" in answer:
        pytest.fail(f"chromium refused the expression: {answer['error']}")
    result = answer["result"]
    if "exceptionDetails" in result:
        pytest.fail(f"the page's script failed: {result['exceptionDetails']}")
    return result["result"].get("value")


async def _evaluate_once(socket_url: str, expression: str) -> dict[str, Any]:
    from tornado.websocket import websocket_connect

    connection = await websocket_connect(socket_url, max_message_size=1 << 26)
    try:
        params = {"expression": expression, "awaitPromise": True, "returnByValue": True}
        connection.write_message(
            json.dumps({"id": 1, "method": "Runtime.evaluate", "params": params})
        )
        while True:
            message = await connection.read_message()
            if message is None:
                pytest.fail("chromium closed the DevTools connection")
            answer = json.loads(message)
            if answer.get("id") == 1:
                break
    finally:
        connection.close()
    return dict(answer)


LEGEND_LAYOUT = """
new Promise((resolve, reject) => {
  const start = Date.now();
  const box = (element) => {
    const r = element.getBoundingClientRect();
    return {left: r.left, right: r.right, top: r.top, bottom: r.bottom};
  };
  const sample = () => {
    const canvas = document.querySelector('#meshcat-pane canvas');
    const legend = document.getElementById('hexaleg-legend');
    if (canvas === null) return null;
    const found = legend === null ? null : box(legend);
    const middle = found === null ? null : document.elementFromPoint(
      (found.left + found.right) / 2, (found.top + found.bottom) / 2);
    return {
      canvas: box(canvas),
      legend: found,
      text: legend === null ? null : legend.innerText,
      shown: legend !== null && getComputedStyle(legend).visibility === 'visible'
        && getComputedStyle(legend).display !== 'none' && legend.contains(middle),
      window: {width: innerWidth, height: innerHeight},
    };
  };
  let last = null;
  (function poll() {
    const now = sample();
    if (now !== null && last !== null && JSON.stringify(now) === JSON.stringify(last)) {
      resolve(now);
    } else if (Date.now() - start > 60000) {
      reject(new Error('the page did not settle within 60 s: ' + JSON.stringify(now)));
    } else {
      last = now;
      setTimeout(poll, 500);
    }
  })();
})
"""
"""Where the legend and the scene's canvas lie once the page has settled (the same twice,
0.5 s apart; meshcat sizes its canvas after the page loads), what the legend says, and
whether it is seen (displayed, and what lies at its middle is the legend, not the canvas)."""
