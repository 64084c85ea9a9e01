"""meshcat's server, bound to one interface, and the loop that serves a scene until stopped.

meshcat 0.3.2's own server listens on all interfaces; :class:`LoopbackServer` runs
its bridge in a thread of this process with tornado bound to the host given
(127.0.0.1 unless the user asks), so stopping the process stops it all. Its two sockets:

- the web page and its WebSocket, on ``host`` (``--host``, ``--port``): a browser
  watches the scene there, and cannot change it (messages from the page are dropped);
  the page is meshcat's with the scene's colour legend beside it (:mod:`.legend`);
- the ZMQ command socket that changes the scene, always on 127.0.0.1 at a port the
  system picks: never beyond this machine, and never on a port the user asked for.
"""

from __future__ import annotations

import asyncio
import contextlib
import io
import ipaddress
import signal
import socket
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from hexaleg.exceptions import HexalegError
from hexaleg.output.viewer.legend import Legend, with_legend

COMMAND_SOCKET = "tcp://127.0.0.1:*"
"""Where the ZMQ command socket binds: loopback, at a port the system picks."""


class LoopbackServer:
    """meshcat's ZMQ/WebSocket bridge in a background thread, bound to one host.

    Attributes:
        host: Interface the web server binds (127.0.0.1 by default).
        zmq_url: Where a ``meshcat.Visualizer`` sends commands (always on 127.0.0.1).
        web_url: The page to open in a browser (on this machine, for a wildcard host).
        web_port: The web server's port.
        legend: What the scene's colours mean, shown beside it on the page (``None``: no
            legend, meshcat's page as it is).

    """

    def __init__(
        self, host: str = "127.0.0.1", port: int | None = None, legend: Legend | None = None
    ) -> None:
        self.host = host
        self.legend = legend
        self._ready = threading.Event()
        self._error: BaseException | None = None
        self._bridge: Any = None
        self._http_servers: list[Any] = []
        self._thread = threading.Thread(target=self._serve, args=(port,), daemon=True)
        self._thread.start()
        if not self._ready.wait(timeout=30):
            raise HexalegError("the meshcat server did not start within 30 s")
        if self._error is not None:
            raise HexalegError(
                f"cannot start the viewer on {host}:{port}: {self._error}"
            ) from self._error
        bridge: Any = self._bridge  # set by the server thread before _ready
        self.zmq_url: str = bridge.zmq_url
        self.web_port: int = bridge.fileserver_port
        self.web_url: str = browser_url(host, self.web_port)
        bridge.web_url = self.web_url  # what meshcat answers a client asking for the URL

    def _serve(self, port: int | None) -> None:
        import zmq
        from meshcat.servers import zmqserver
        from meshcat.servers.zmqserver import ZMQWebSocketBridge

        # meshcat's server prints "Port: 6000 in use, trying another..." and "opened: <...>"
        # for every browser tab: noise to a hexaleg user. Only that module's print is muted.
        zmqserver.print = _quiet

        host = self.host
        http_servers = self._http_servers
        legend = self.legend

        class Bridge(ZMQWebSocketBridge):
            def make_app(self) -> Any:
                app = _read_only_app(self, legend)
                listen = app.listen

                def listen_on_host(port: int, **kwargs: Any) -> Any:
                    server = listen(port, address=host, **kwargs)
                    http_servers.append(server)
                    return server

                app.listen = listen_on_host
                return app

            def setup_zmq(self, url: str) -> Any:
                zmq_socket, stream, _ = super().setup_zmq(url)
                return zmq_socket, stream, zmq_socket.getsockopt_string(zmq.LAST_ENDPOINT)

        asyncio.set_event_loop(asyncio.new_event_loop())
        try:
            self._bridge = Bridge(zmq_url=COMMAND_SOCKET, host=host, port=port)
        except BaseException as err:  # port taken, bad host: reported by __init__
            self._error = err
            self._ready.set()
            return
        self._ready.set()
        self._bridge.run()

    def stop(self) -> None:
        """Stop the server thread and release its sockets."""
        if self._bridge is None:
            return
        loop = self._bridge.ioloop

        def shut_down() -> None:
            for server in self._http_servers:  # release the listening port
                server.stop()
            loop.stop()

        loop.add_callback(shut_down)
        self._thread.join(timeout=10)
        self._bridge.zmq_stream.close(linger=0)
        self._bridge.zmq_socket.close(linger=0)
        self._bridge = None

    def __enter__(self) -> LoopbackServer:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.stop()


def client(server: LoopbackServer) -> Any:
    """A ``meshcat.Visualizer`` connected to ``server`` (without meshcat's stdout banner)."""
    import meshcat

    with contextlib.redirect_stdout(io.StringIO()):
        return meshcat.Visualizer(zmq_url=server.zmq_url)


def serve_until_stopped(server: LoopbackServer, poll: float = 0.5) -> None:
    """Block until Ctrl-C or SIGTERM, then stop ``server`` cleanly."""
    for signum in (signal.SIGINT, signal.SIGTERM):  # Ctrl-C or kill: stop cleanly
        signal.signal(signum, signal.default_int_handler)
    try:
        while True:
            time.sleep(poll)
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()


def _quiet(*args: Any, **kwargs: Any) -> None:
    """Drop what meshcat's server module prints."""


def _read_only_app(bridge: Any, legend: Legend | None) -> Any:
    """The meshcat web application, watch-only, its page showing ``legend``.

    Its page (with the legend beside the scene, when one is given), its scripts, and a
    WebSocket that only sends the scene to the page.
    """
    import tornado.web
    from meshcat.servers.zmqserver import (
        VIEWER_HTML,
        VIEWER_ROOT,
        StaticFileHandlerNoCache,
        WebSocketHandler,
    )

    class WatchOnly(WebSocketHandler):
        def on_message(self, message: Any) -> None:
            """Drop what a page sends (meshcat would forward it to the command socket)."""

    static = {"path": VIEWER_ROOT, "default_filename": VIEWER_HTML}
    handlers: list[Any] = [
        (r"/static/(.*)", StaticFileHandlerNoCache, static),
        (r"/", WatchOnly, {"bridge": bridge}),
    ]
    if legend is not None:  # meshcat's page with the legend, matched before the plain files
        page = (Path(VIEWER_ROOT) / VIEWER_HTML).read_text(encoding="utf-8")
        handlers.insert(
            0,
            (rf"/static/(?:{VIEWER_HTML})?", _page_handler(), {"html": with_legend(page, legend)}),
        )
    return tornado.web.Application(handlers)


def _page_handler() -> Any:
    """A tornado handler serving one fixed HTML page, never cached (the scene changes)."""
    import tornado.web

    class Page(tornado.web.RequestHandler):
        def initialize(self, html: str) -> None:
            self.html = html

        def get(self) -> None:
            self.set_header("Content-Type", "text/html; charset=utf-8")
            self.set_header("Cache-Control", "no-store, no-cache, must-revalidate, max-age=0")
            self.finish(self.html)

    return Page


def is_loopback(host: str) -> bool:
    """Whether every address ``host`` names is on this machine only (127.0.0.0/8, ::1).

    ``127.1`` and ``localhost`` are; ``0.0.0.0`` (every interface) is not.
    """
    try:
        infos = socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)
    except (OSError, UnicodeError, ValueError):  # not an address, not a known name
        return False
    return bool(infos) and all(
        ipaddress.ip_address(str(info[4][0]).split("%")[0]).is_loopback for info in infos
    )


def browser_url(host: str, port: int, path: str = "/static/") -> str:
    """The page at ``path`` as a browser opens it (meshcat's page by default).

    A wildcard host (``0.0.0.0``, ``::``) becomes this machine's loopback, an IPv6
    address gets its brackets, a numeric shorthand (``127.1``) its full form; a name
    stays as given.
    """
    wildcard = {"": "127.0.0.1", "0.0.0.0": "127.0.0.1", "::": "::1"}
    shown = wildcard.get(host, host)
    try:
        info = socket.getaddrinfo(shown, None, flags=socket.AI_NUMERICHOST)[0]
    except (OSError, UnicodeError, ValueError):  # a name: shown as given
        return f"http://{shown}:{port}{path}"
    address = ipaddress.ip_address(str(info[4][0]))
    text = f"[{address}]" if address.version == 6 else str(address)
    return f"http://{text}:{port}{path}"


def static_page(build: Callable[[Any], None], legend: Legend | None) -> str:
    """A self-contained HTML page (no server needed to view it) of one scene.

    Args:
        build: Draws the scene into the ``meshcat.Visualizer`` it is given.
        legend: What the scene's colours mean, beside it on the page (``None``: none).

    """
    with LoopbackServer() as server:
        viewer = client(server)
        build(viewer)
        html: str = viewer.static_html()
        viewer.window.zmq_socket.close(linger=0)
    return html if legend is None else with_legend(html, legend)
