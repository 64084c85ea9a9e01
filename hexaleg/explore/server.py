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

Only the explorer's own page may use it. Every request names the explorer in its
``Host`` (127.0.0.1, localhost, [::1] or the ``--host`` given, at its port; beyond
loopback also any IP address): another name is a DNS-rebinding page's, refused with 403
before anything else. Every API request must come from the page itself: an ``Origin``
other than ``http://`` + its ``Host``, or a browser's ``Sec-Fetch-Site`` other than
``same-origin`` or ``none`` (another site's page, another local port's), answers 403,
nothing written, no job started. A request without either (curl, a script on this
machine) is served. A body is read and dropped (the queries are in the URL): its
``Content-Length`` must be a byte count of at most :data:`MAX_BODY` — anything else
answers 400 (413 too large) at once and closes the connection; a request that stalls is
dropped after :data:`REQUEST_TIMEOUT`.
"""

from __future__ import annotations

import ipaddress
import json
import sys
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from typing import Any
from urllib.parse import parse_qsl, urlsplit

from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.explore.session import Session
from hexaleg.output.viewer.server import is_loopback

__all__ = ["ExplorerServer"]

STATIC = {
    "/": ("index.html", "text/html; charset=utf-8"),
    "/explore.js": ("explore.js", "text/javascript; charset=utf-8"),
    "/explore.css": ("explore.css", "text/css; charset=utf-8"),
}
"""The page's files by path, with their content types (shipped in ``explore/static``)."""
MAX_BODY = 64 * 1024
"""Largest request body read and dropped [bytes]."""
REQUEST_TIMEOUT = 30.0
"""A request whose headers or body stall longer than this is dropped [s]."""
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")
"""The names the explorer answers to on any host (with its port)."""
PAGE_FETCHES = ("same-origin", "none")
"""A browser's ``Sec-Fetch-Site`` of a request the explorer's own page (or the user) made."""


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
        given = f"[{host}]" if ":" in host else host
        self.names = frozenset(name.lower() for name in (*LOOPBACK_NAMES, given))
        self.any_address = not is_loopback(host)  # beyond loopback, reached by its addresses

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
    timeout = REQUEST_TIMEOUT

    def do_GET(self) -> None:
        url = urlsplit(self.path)
        if not self._admitted(url.path):
            return
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
        if not self._admitted(url.path):
            return
        session = self.server.session
        routes = {
            "/api/save": lambda params: {"wrote": str(session.save(params))},
            "/api/job": lambda params: session.start_job(_kind(params), params),
            "/api/job/stop": lambda params: _stopped(session, _kind(params)),
        }
        if url.path not in routes:
            self._json(HTTPStatus.NOT_FOUND, {"error": f"no such endpoint: {url.path}"})
            return
        self._answer(lambda: routes[url.path](_params(url.query)))

    def _admitted(self, path: str) -> bool:
        """Whether to serve the request: its Host, its body and (API) its Origin checked.

        A refusal is answered here (403, or 400/413 for the body), the connection closed.
        """
        refused = self._foreign_host() or self._unread_body()
        if refused is None and path.startswith("/api/"):
            refused = self._foreign_page()
        if refused is None:
            return True
        status, field, error, allowed = refused
        self.close_connection = True  # what is left of the request is not read
        self._json(status, {"error": error, "field": field, "allowed": allowed})
        return False

    def _foreign_host(self) -> tuple[HTTPStatus, str, str, str] | None:
        """A Host naming another machine than the explorer (DNS rebinding), as a refusal."""
        host = self.headers.get("Host", "")
        port = self.server.port
        allowed = f"127.0.0.1, localhost or [::1] (or --host) at port {port}"
        found = _host_and_port(host)
        if found is not None and found[1] == port and self._our_name(found[0]):
            return None
        error = f"Host {host!r} does not name this explorer: it answers at {allowed}"
        return HTTPStatus.FORBIDDEN, "Host", error, allowed

    def _our_name(self, name: str) -> bool:
        if name in self.server.names:
            return True
        if not self.server.any_address:
            return False
        try:  # served beyond loopback: reached by any of its addresses, never by a name
            ipaddress.ip_address(name.strip("[]"))
        except ValueError:
            return False
        return True

    def _foreign_page(self) -> tuple[HTTPStatus, str, str, str] | None:
        """A request another site's page made (its Origin, its Sec-Fetch-Site), as a refusal."""
        page = f"http://{self.headers.get('Host', '')}".lower()
        origin = self.headers.get("Origin")
        if origin is not None and origin.lower() not in (page, page.removesuffix(":80")):
            error = f"Origin {origin!r} is not this explorer's page ({page}): no other may use it"
            return HTTPStatus.FORBIDDEN, "Origin", error, page
        fetched = self.headers.get("Sec-Fetch-Site")
        if fetched is not None and fetched.lower() not in PAGE_FETCHES:
            error = f"Sec-Fetch-Site {fetched!r}: a request from another page may not use it"
            return HTTPStatus.FORBIDDEN, "Sec-Fetch-Site", error, " or ".join(PAGE_FETCHES)
        return None

    def _unread_body(self) -> tuple[HTTPStatus, str, str, str] | None:
        """Read and drop the body; a length that is no byte count (or too large) as a refusal."""
        allowed = f"a byte count 0..{MAX_BODY} (digits)"
        chunked = self.headers.get("Transfer-Encoding")
        if chunked is not None:  # no length to bound the body by
            error = f"Transfer-Encoding {chunked!r} is not accepted: send a Content-Length"
            return HTTPStatus.BAD_REQUEST, "Transfer-Encoding", error, "a Content-Length"
        lengths = self.headers.get_all("Content-Length") or []
        if not lengths:
            return None
        text = lengths[0].strip()
        if len(lengths) > 1 or not (text.isascii() and text.isdigit()):
            error = f"Content-Length {', '.join(lengths)!r} is not valid: {allowed}"
            return HTTPStatus.BAD_REQUEST, "Content-Length", error, allowed
        if len(text) > len(str(MAX_BODY)) or int(text) > MAX_BODY:
            error = f"Content-Length {text} is too large: {allowed}"
            return HTTPStatus.REQUEST_ENTITY_TOO_LARGE, "Content-Length", error, allowed
        self.rfile.read(int(text))  # the query is in the URL; the body is read and dropped
        return None

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
        if self.close_connection:
            self.send_header("Connection", "close")
        self.end_headers()
        self.wfile.write(body)

    def log_message(self, format: str, *args: Any) -> None:
        """Say nothing per request (the terminal shows the URL and errors only)."""


def _host_and_port(host: str) -> tuple[str, int] | None:
    """The name and port a Host header gives (port 80 when it gives none); ``None``: neither.

    An IPv6 address stands in brackets (``[::1]:8000``).
    """
    if host.endswith("]") or ":" not in host:  # no port: a name or an address alone
        name, port = host, "80"
    else:
        name, _, port = host.rpartition(":")
    if ":" in name and not (name.startswith("[") and name.endswith("]")):
        return None
    if not (name and port.isascii() and port.isdigit() and len(port) <= 5):
        return None
    return name.lower(), int(port)


def _kind(params: dict[str, str]) -> str:
    """The job a request names (``kind``), taken out of the design's keys."""
    from hexaleg.explore.jobs import require_job_kind

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
