"""The viewer's sockets: the page where the user asks, the command socket on loopback only.

Every server here binds a loopback address (127.0.0.0/8 or ::1), is stopped by the test,
and its listening sockets are read from the system (psutil, as /proc/net/tcp* holds them).
"""

from __future__ import annotations

import asyncio
import os
import queue
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.request
from pathlib import Path

import psutil
import pytest

from hexaleg.output.viewer.legend import GAIT_LEGEND, STATICS_LEGEND
from hexaleg.output.viewer.server import LoopbackServer, browser_url, is_loopback

START_TIMEOUT = 180
"""Bound on a server's start, the viewer's computing included [s]."""


def _listening(pid: int) -> set[tuple[str, int]]:
    return {
        (c.laddr.ip, c.laddr.port)
        for c in psutil.Process(pid).net_connections("inet")
        if c.status == psutil.CONN_LISTEN
    }


def _port(url: str) -> int:
    return int(url.rsplit(":", 1)[1].split("/")[0])


def _free(port: int, host: str = "127.0.0.1") -> bool:
    with socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET) as sock:
        try:
            sock.bind((host, port))
        except OSError:
            return False
    return True


def _ipv6_loopback() -> bool:
    try:
        with socket.socket(socket.AF_INET6) as sock:
            sock.bind(("::1", 0))
    except OSError:
        return False
    return True


def test_the_command_socket_is_on_loopback_whatever_the_page_binds():
    with LoopbackServer("127.0.0.2") as server:  # loopback, but not where ZMQ goes
        ours = {("127.0.0.2", server.web_port), ("127.0.0.1", _port(server.zmq_url))}
        assert server.zmq_url.startswith("tcp://127.0.0.1:")
        assert ours <= _listening(os.getpid())
        assert server.web_url == f"http://127.0.0.2:{server.web_port}/static/"
    deadline = time.monotonic() + 30  # ZMQ closes its socket in a thread of its own
    while ours & _listening(os.getpid()) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not ours & _listening(os.getpid())


def test_the_users_port_is_the_page_s_never_the_command_socket_s():
    """`view --port 6000` serves the page on 6000: the ZMQ socket must not take it
    (meshcat's takes the first free port from 6000: the port asked for here)."""
    port = next(p for p in range(6000, 7000) if _free(p))
    with LoopbackServer(port=port) as server:
        assert server.web_port == port
        assert _port(server.zmq_url) != port
        assert ("127.0.0.1", port) in _listening(os.getpid())


@pytest.mark.skipif(not _ipv6_loopback(), reason="no IPv6 loopback on this machine")
def test_ipv6_loopback_serves_a_page_a_browser_can_open():
    with LoopbackServer("::1") as server:
        assert server.web_url == f"http://[::1]:{server.web_port}/static/"
        assert ("::1", server.web_port) in _listening(os.getpid())
        assert server.zmq_url.startswith("tcp://127.0.0.1:")
        with urllib.request.urlopen(server.web_url, timeout=30) as page:
            assert page.status == 200 and b"<html" in page.read(2000).lower()


def test_what_the_page_sends_never_reaches_the_command_socket():
    from tornado.websocket import websocket_connect

    with LoopbackServer() as server:
        forwarded = []
        server._bridge.send_image = forwarded.append

        async def send() -> None:
            url = f"ws://127.0.0.1:{server.web_port}/"
            connection = await asyncio.wait_for(websocket_connect(url), timeout=30)
            await connection.write_message('{"data": "data:image/png;base64,AAAA"}')
            await asyncio.sleep(0.5)
            connection.close()

        asyncio.run(send())
        assert forwarded == []


def test_the_page_is_meshcat_s_with_the_legend_beside_the_scene():
    """The served page carries the legend the static one does; meshcat's scripts unchanged."""
    from hexaleg.output.viewer.legend import torque_legend_html, with_legend

    def fetch(url: str) -> tuple[str, bytes]:
        with urllib.request.urlopen(url, timeout=30) as answer:
            return answer.headers["Cache-Control"], answer.read()

    import meshcat

    dist = Path(meshcat.__file__).parent / "viewer" / "dist"
    plain = (dist / "index.html").read_text(encoding="utf-8")
    with LoopbackServer(legend=GAIT_LEGEND) as server:
        for page in (server.web_url, server.web_url + "index.html"):
            cache, body = fetch(page)
            assert body.decode() == with_legend(plain, GAIT_LEGEND)
            assert torque_legend_html(GAIT_LEGEND) in body.decode() and "no-store" in cache
        assert fetch(server.web_url + "main.min.js")[1] == (dist / "main.min.js").read_bytes()
    with LoopbackServer() as server:  # no legend: meshcat's page as it is
        assert fetch(server.web_url)[1].decode() == plain


@pytest.mark.parametrize(
    ("host", "loopback"),
    [
        ("127.0.0.1", True),
        ("127.1", True),
        ("127.0.0.2", True),
        ("::1", True),
        ("localhost", True),
        ("0.0.0.0", False),
        ("::", False),
        ("192.168.1.5", False),
        ("", False),
        ("not a host", False),
        ("example.org", False),
    ],
)
def test_is_loopback(host, loopback):
    assert is_loopback(host) is loopback


@pytest.mark.parametrize(
    ("host", "url"),
    [
        ("0.0.0.0", "http://127.0.0.1:7000/static/"),
        ("::", "http://[::1]:7000/static/"),
        ("127.1", "http://127.0.0.1:7000/static/"),
        ("::1", "http://[::1]:7000/static/"),
        ("192.168.1.5", "http://192.168.1.5:7000/static/"),
        ("localhost", "http://localhost:7000/static/"),
    ],
)
def test_the_url_is_one_a_browser_opens(host, url):
    assert browser_url(host, 7000) == url


def test_binding_beyond_loopback_says_what_is_exposed(monkeypatch, capsys):
    """The warning, printed before serving, for the extremes and for a gait; never on
    loopback. The server itself is a stand-in (no test binds beyond loopback)."""
    from conftest import run_cli

    from hexaleg.cli import view

    bound = []

    class Server:
        web_url = "http://127.0.0.1:7000/static/"

        def __init__(self, host, port, legend):
            bound.append((host, port, legend))

    monkeypatch.setattr(view, "LoopbackServer", Server)
    monkeypatch.setattr(view, "build_scene", lambda *args, **kwargs: None)
    monkeypatch.setattr(view, "build_gait_scene", lambda *args, **kwargs: None)
    monkeypatch.setattr(view, "client", lambda server: None)
    monkeypatch.setattr(view, "serve_until_stopped", lambda server: None)
    assert run_cli(["view", "--host", "0.0.0.0", "--port", "7010"]) == 0
    assert run_cli(["view", "--host", "127.1"]) == 0
    assert run_cli(["view"]) == 0
    assert run_cli(["view", "--gait", "--host", "::"]) == 0
    assert [(host, port) for host, port, _ in bound] == [
        ("0.0.0.0", 7010),
        ("127.1", None),
        ("127.0.0.1", None),
        ("::", None),
    ]
    assert [legend for *_, legend in bound] == [STATICS_LEGEND] * 3 + [GAIT_LEGEND]
    captured = capsys.readouterr()
    notes = [line for line in captured.err.splitlines() if "note" in line]
    assert len(notes) == 2 and "--host ::" in notes[1]
    for said in ("--host 0.0.0.0", "port 7010", "without authentication", "not change them"):
        assert said in notes[0]
    assert "command socket stays on 127.0.0.1" in notes[0]


@pytest.mark.slow  # the viewer computes the extremes before it serves
@pytest.mark.skipif(not _ipv6_loopback(), reason="no IPv6 loopback on this machine")
def test_view_on_ipv6_loopback_and_a_port_of_the_users(tmp_path):
    """As a user runs it: `view --host ::1 --port P`."""
    port = next(p for p in range(6000, 6100) if _free(p, "::1") and _free(p))
    process = subprocess.Popen(
        [sys.executable, "-m", "hexaleg", "view", "--host", "::1", "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lines: queue.Queue[str] = queue.Queue()
    threading.Thread(target=lambda: [lines.put(x) for x in process.stdout], daemon=True).start()
    try:
        try:
            line = lines.get(timeout=START_TIMEOUT)
        except queue.Empty:
            pytest.fail(f"hexaleg view printed no URL within {START_TIMEOUT} s")
        url = f"http://[::1]:{port}/static/"
        assert line == f"hexaleg viewer: open {url}\n"
        sockets = _listening(process.pid)
        assert ("::1", port) in sockets and len(sockets) == 2
        assert all(ip in ("::1", "127.0.0.1") for ip, _ in sockets), sockets
        with urllib.request.urlopen(url, timeout=30) as page:
            assert page.status == 200
        process.send_signal(signal.SIGINT)
        assert process.wait(timeout=60) == 0
        assert "note" not in process.stderr.read()
    finally:
        if process.poll() is None:
            os.kill(process.pid, signal.SIGKILL)
            process.wait(timeout=30)
