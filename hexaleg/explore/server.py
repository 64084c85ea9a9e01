"""The explorer's web server: the page, its scripts and the JSON endpoints, on one host.

Standard-library :mod:`http.server`, one thread a request, bound to the host and port
given (127.0.0.1 unless the user asks; port 0 lets the system pick). Endpoints:

- ``GET /``: the page; ``GET /explore.js``, ``/explore.css``: its script and style;
- ``GET /api/evaluate?l1=…&…``: one design's numbers (:func:`~.answer.answer`); a bad
  value answers 400 with ``{"error", "field", "allowed"}`` and the server keeps serving;
- ``GET /api/reach?…``: each foot's reach on the ground for that design (on demand);
- ``GET /api/loaded``: what the page starts at and resets to;
- ``GET /api/cloud``: the study's cloud (``ready`` false while it is measured);
- ``POST /api/save?…``: writes the design the query describes to the session's file;
- ``POST /api/job?kind=free|decide&…``: starts a long job on the design the query
  describes (:mod:`~.jobs`); ``GET /api/job?kind=…``: its state and progress;
  ``POST /api/job/stop?kind=…``: stops it.
"""

from __future__ import annotations

import json
import sys
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from typing import Any
from urllib.parse import parse_qsl, urlsplit

from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.explore.jobs import require_job_kind
from hexaleg.explore.session import Session

__all__ = ["ExplorerServer"]

STATIC = {
    "/": ("index.html", "text/html; charset=utf-8"),
    "/explore.js": ("explore.js", "text/javascript; charset=utf-8"),
    "/explore.css": ("explore.css", "text/css; charset=utf-8"),
}
"""The page's files by path, with their content types (shipped in ``explore/static``)."""


class ExplorerServer(ThreadingHTTPServer):
    """The explorer's HTTP server for one :class:`~.session.Session`.

    Attributes:
        session: What it serves.

    """

    daemon_threads = True

    def __init__(self, session: Session, host: str, port: int) -> None:
        self.session = session
        self.address_family = _family(host)
        super().__init__((host, port), _Handler)

    @property
    def port(self) -> int:
        """The port it listens on (the system's choice for port 0)."""
        return int(self.server_address[1])

    def handle_error(self, _request: Any, _client_address: Any) -> None:
        """A page that went away mid-answer is no error; anything else is one line."""
        error = sys.exc_info()[1]
        if isinstance(error, ConnectionError):
            return
        print(f"hexaleg explore: a request failed: {error!r}", file=sys.stderr)


def _family(host: str) -> Any:
    """The socket family of ``host`` (IPv6 for an address with a colon)."""
    import socket

    return socket.AF_INET6 if ":" in host else socket.AF_INET


class _Handler(BaseHTTPRequestHandler):
    """One request: a static file, or a JSON endpoint."""

    server: ExplorerServer
    protocol_version = "HTTP/1.1"

    def do_GET(self) -> None:
        url = urlsplit(self.path)
        if url.path in STATIC:
            name, kind = STATIC[url.path]
            text = resources.files("hexaleg.explore").joinpath("static").joinpath(name).read_bytes()
            self._send(HTTPStatus.OK, text, kind)
            return
        session = self.server.session
        routes = {
            "/api/evaluate": lambda params: session.evaluate(params),
            "/api/reach": lambda params: session.reach(params),
            "/api/loaded": lambda params: session.loaded(),
            "/api/cloud": lambda params: session.cloud.to_dict(),
            "/api/job": lambda params: session.job(_kind(params)),
        }
        if url.path not in routes:
            self._json(HTTPStatus.NOT_FOUND, {"error": f"no such page: {url.path}"})
            return
        self._answer(lambda: routes[url.path](_params(url.query)))

    def do_POST(self) -> None:
        url = urlsplit(self.path)
        session = self.server.session
        routes = {
            "/api/save": lambda params: {"wrote": str(session.save(params))},
            "/api/job": lambda params: session.start_job(_kind(params), params),
            "/api/job/stop": lambda params: _stopped(session, _kind(params)),
        }
        length = int(self.headers.get("Content-Length") or 0)
        self.rfile.read(length)  # the query is in the URL; the body is read and dropped
        if url.path not in routes:
            self._json(HTTPStatus.NOT_FOUND, {"error": f"no such endpoint: {url.path}"})
            return
        self._answer(lambda: routes[url.path](_params(url.query)))

    def _answer(self, compute: Any) -> None:
        """The endpoint's JSON, or a 400 naming what the user got wrong."""
        try:
            data = compute()
        except ParameterError as err:
            self._json(HTTPStatus.BAD_REQUEST,
                       {"error": str(err), "field": err.field, "allowed": err.allowed})  # fmt: skip
            return
        except HexalegError as err:
            self._json(HTTPStatus.BAD_REQUEST, {"error": str(err), "field": None, "allowed": None})
            return
        self._json(HTTPStatus.OK, data)

    def _json(self, status: HTTPStatus, data: dict[str, Any]) -> None:
        body = json.dumps(data, allow_nan=False).encode("utf-8")
        self._send(status, body, "application/json")

    def _send(self, status: HTTPStatus, body: bytes, kind: str) -> None:
        self.send_response(status)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(body)

    def log_message(self, format: str, *args: Any) -> None:
        """Say nothing per request (the terminal shows the URL and errors only)."""


def _kind(params: dict[str, str]) -> str:
    """The job a request names (``kind``), taken out of the design's keys."""
    return require_job_kind(params.pop("kind", ""))


def _stopped(session: Session, kind: str) -> dict[str, Any]:
    """Stop the job of ``kind``; its state after."""
    session.jobs.stop(kind)
    return session.job(kind)


def _params(query: str) -> dict[str, str]:
    """A query string's keys and values.

    Raises:
        ParameterError: A key given twice (which value was meant is not known).

    """
    pairs = parse_qsl(query, keep_blank_values=True)
    params = dict(pairs)
    if len(params) < len(pairs):
        twice = next(key for key in params if sum(k == key for k, _ in pairs) > 1)
        raise ParameterError(twice, params[twice], "given more than once: give it once")
    return params
