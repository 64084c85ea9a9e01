"""meshcat's server, bound to one interface, and the loop that serves a scene until stopped.

meshcat 0.3.2's own server listens on all interfaces; :class:`LoopbackServer` runs
its bridge in a thread of this process with tornado bound to the host given
(127.0.0.1 unless the user asks), so stopping the process stops it all.
"""

from __future__ import annotations

import asyncio
import contextlib
import io
import signal
import threading
import time
from typing import Any

from hexaleg.exceptions import HexalegError


class LoopbackServer:
    """meshcat's ZMQ/WebSocket bridge in a background thread, bound to one host.

    Attributes:
        host: Interface the web and ZMQ servers bind (127.0.0.1 by default).
        zmq_url: Where a ``meshcat.Visualizer`` sends commands.
        web_url: The page to open in a browser.

    """

    def __init__(self, host: str = "127.0.0.1", port: int | None = None) -> None:
        self.host = host
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
        self.web_url: str = bridge.web_url

    def _serve(self, port: int | None) -> None:
        from meshcat.servers import zmqserver
        from meshcat.servers.zmqserver import ZMQWebSocketBridge

        # meshcat's server prints "Port: 6000 in use, trying another..." and "opened: <...>"
        # for every browser tab: noise to a hexaleg user. Only that module's print is muted.
        zmqserver.print = _quiet

        host = self.host
        http_servers = self._http_servers

        class Bridge(ZMQWebSocketBridge):
            def make_app(self) -> Any:
                app = super().make_app()
                listen = app.listen

                def listen_on_host(port: int, **kwargs: Any) -> Any:
                    server = listen(port, address=host, **kwargs)
                    http_servers.append(server)
                    return server

                app.listen = listen_on_host
                return app

        asyncio.set_event_loop(asyncio.new_event_loop())
        try:
            self._bridge = Bridge(host=host, port=port)
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

    def __exit__(self, *exc: object) -> None:
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
