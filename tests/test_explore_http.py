"""The explorer under hostile HTTP: forged Origin and Host, malformed Content-Length.

Raw requests (:mod:`http.client`, as curl sends them) to an explorer started as its own
process on 127.0.0.1 (:mod:`explorer`). A request from another site (its Origin not the
explorer's page) or through another name (a DNS-rebinding Host) answers 403 on every API
endpoint, nothing written and no job started; the page's own requests keep working. A
Content-Length that is not a byte count answers 400 (too large: 413) at once.
"""

from __future__ import annotations

import http.client
import json
import socket
import time
from urllib.parse import urlsplit

import pytest
from explorer import Explorer, running

from hexaleg.cli import main

ANSWER_WITHIN = 10.0
"""Bound on any answer here [s]: a refusal is immediate, never a wait for a body."""


@pytest.fixture(scope="module")
def design_file(tmp_path_factory) -> str:
    path = tmp_path_factory.mktemp("explore_http") / "robot.toml"
    assert main(["design", "init", str(path), "--l1", "0.18"]) == 0
    path.write_text("# the user's comments\n" + path.read_text())
    return str(path)


@pytest.fixture(scope="module")
def explorer(design_file) -> Explorer:
    with running("--design", design_file) as server:
        yield server


def _port(server: Explorer) -> int:
    return int(urlsplit(server.url).port or 0)


def _send(
    server: Explorer, method: str, path: str, headers: dict[str, str], body: bytes = b""
) -> tuple[int, dict]:
    """``method path`` with exactly ``headers`` (Host included) and ``body``: status, JSON."""
    connection = http.client.HTTPConnection("127.0.0.1", _port(server), timeout=ANSWER_WITHIN)
    try:
        connection.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
        for name, value in headers.items():
            connection.putheader(name, value)
        connection.endheaders(body or None)
        answer = connection.getresponse()
        return answer.status, json.loads(answer.read() or b"{}")
    finally:
        connection.close()


def _own(server: Explorer, host: str = "127.0.0.1") -> dict[str, str]:
    """The headers of the explorer's own page, opened at ``host``."""
    where = f"{host}:{_port(server)}"
    return {"Host": where, "Origin": f"http://{where}", "Content-Length": "0"}


FORGED = {
    "another site's page": {"Origin": "http://evil.example"},
    "a DNS-rebinding name": {"Host": "evil.example:{port}", "Origin": "http://evil.example:{port}"},
    "another port": {"Host": "127.0.0.1:1", "Origin": "http://127.0.0.1:1"},
    "a sandboxed page": {"Origin": "null"},
    "the right host on https": {"Origin": "https://127.0.0.1:{port}"},
    "a cross-site fetch without Origin": {"Origin": None, "Sec-Fetch-Site": "cross-site"},
}
"""How a request from elsewhere differs from the page's own (None: the header left out)."""

ENDPOINTS = [
    ("POST", "/api/save?l2=0.41"),
    ("POST", "/api/job?kind=free"),
    ("POST", "/api/job/stop?kind=free"),
    ("GET", "/api/evaluate?l2=0.41"),
    ("GET", "/api/reach"),
    ("GET", "/api/loaded"),
    ("GET", "/api/cloud"),
    ("GET", "/api/job?kind=free"),
]


def _forged(server: Explorer, how: str) -> dict[str, str]:
    headers = _own(server)
    for name, value in FORGED[how].items():
        if value is None:
            headers.pop(name)
        else:
            headers[name] = value.format(port=_port(server))
    return headers


@pytest.mark.parametrize("how", list(FORGED))
@pytest.mark.parametrize(("method", "path"), ENDPOINTS, ids=[" ".join(e) for e in ENDPOINTS])
def test_a_request_from_elsewhere_is_refused_and_changes_nothing(
    explorer, design_file, how, method, path
):
    before = open(design_file, "rb").read()
    status, got = _send(explorer, method, path, _forged(explorer, how))
    assert status == 403, got
    assert got["field"] in ("Origin", "Host", "Sec-Fetch-Site") and "403" not in got["error"]
    assert open(design_file, "rb").read() == before  # the user's file, comments and all
    assert explorer.get("api/job?kind=free") == (200, {"kind": "free", "state": "none"})


def test_the_page_s_own_requests_are_answered(explorer, design_file):
    before = open(design_file, "rb").read()
    for host in ("127.0.0.1", "localhost"):
        status, got = _send(explorer, "GET", "/api/evaluate?l2=0.41", _own(explorer, host))
        assert status == 200 and got["error"] == "", got
    page = http.client.HTTPConnection("127.0.0.1", _port(explorer), timeout=ANSWER_WITHIN)
    page.request("GET", "/", headers={"Host": f"localhost:{_port(explorer)}"})
    assert page.getresponse().status == 200
    page.close()
    assert open(design_file, "rb").read() == before


def test_the_page_itself_is_refused_through_another_name(explorer):
    page = http.client.HTTPConnection("127.0.0.1", _port(explorer), timeout=ANSWER_WITHIN)
    page.request("GET", "/", headers={"Host": f"evil.example:{_port(explorer)}"})
    answer = page.getresponse()
    assert answer.status == 403 and b"Host" in answer.read()
    page.close()


@pytest.mark.parametrize(
    ("length", "status"),
    [("abc", 400), ("-1", 400), ("+5", 400), ("1e3", 400), (str(10**12), 413), ("1,1", 400)],
)
@pytest.mark.parametrize("method", ["GET", "POST"])
def test_a_content_length_that_is_no_byte_count_is_answered_at_once(
    explorer, design_file, method, length, status
):
    before = open(design_file, "rb").read()
    port = _port(explorer)
    raw = (
        f"{method} /api/save?l2=0.41 HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
        f"Origin: http://127.0.0.1:{port}\r\nContent-Length: {length}\r\n\r\n"
    )
    start = time.monotonic()
    with socket.create_connection(("127.0.0.1", port), timeout=ANSWER_WITHIN) as connection:
        connection.sendall(raw.encode("latin-1"))
        answer = b""
        while chunk := connection.recv(65536):  # the explorer closes the connection after
            answer += chunk
    assert time.monotonic() - start < ANSWER_WITHIN
    head, _, body = answer.partition(b"\r\n\r\n")
    assert head.startswith(f"HTTP/1.1 {status} ".encode()), answer
    assert json.loads(body)["field"] == "Content-Length"
    assert open(design_file, "rb").read() == before
    assert explorer.get("api/loaded")[0] == 200  # and it keeps serving


UNRELATED = "# the user's own notes, not a design\nanswer = 42\n"


def test_a_save_target_not_named_replaces_only_the_file_it_wrote(tmp_path):
    from hexaleg.exceptions import ParameterError
    from hexaleg.explore.session import SaveTarget

    path = tmp_path / "design.toml"
    path.write_text(UNRELATED)
    target = SaveTarget(path, replace=False)
    with pytest.raises(ParameterError, match="exists and this explorer did not write it"):
        target.write("l1 = 0.2\n")
    path.unlink()
    target.write("l1 = 0.2\n")
    target.write("l1 = 0.3\n")  # its own, replaced
    assert path.read_text() == "l1 = 0.3\n"
    path.write_text(UNRELATED)  # another's again
    with pytest.raises(ParameterError):
        target.write("l1 = 0.4\n")
    assert path.read_text() == UNRELATED
    SaveTarget(path, replace=True).write("l1 = 0.5\n")
    assert path.read_text() == "l1 = 0.5\n"


@pytest.mark.parametrize(
    ("argv", "expected"),
    [([], ("design.toml", False)), (["--force"], ("design.toml", False)),
     (["--save", "a.toml"], ("a.toml", True)), (["--design", "d.toml"], ("d.toml", True)),
     (["--design", "d.json"], ("design.toml", False))],
)  # fmt: skip
def test_save_names_the_file_the_user_gave(argv, expected):
    from hexaleg.cli import build_parser
    from hexaleg.cli.explore import _save_target

    args = build_parser("explore").parse_args(["explore", *argv])
    path, named = _save_target(args)
    assert (str(path), named) == expected


@pytest.mark.slow  # explorers started as processes, seconds each
def test_save_without_a_path_given_never_replaces_a_file_it_did_not_write(tmp_path):
    (tmp_path / "design.toml").write_text(UNRELATED)
    with running("--l1", "0.18", cwd=tmp_path) as server:
        status, got = server.post("api/save?l2=0.41")
        assert status == 400 and got["field"] == "save"
        assert "design.toml" in got["error"] and "exists" in got["error"]
        assert "--save" in got["error"]
        assert "--force" in got["error"]
        (tmp_path / "design.toml").unlink()  # gone: the explorer's own from its first save
        assert server.post("api/save?l2=0.41") == (200, {"wrote": "design.toml"})
        assert server.post("api/save?l2=0.42")[0] == 200  # its own file, replaced
        (tmp_path / "design.toml").write_text(UNRELATED)  # someone else's again
        assert server.post("api/save?l2=0.43")[0] == 400
    assert (tmp_path / "design.toml").read_text() == UNRELATED
    assert sorted(p.name for p in tmp_path.iterdir()) == ["design.toml"]


@pytest.mark.slow  # explorers started as processes, seconds each
@pytest.mark.parametrize("given", [["--save", "design.toml"], ["--force"]])
def test_save_replaces_the_file_the_user_named_or_forced(tmp_path, given):
    (tmp_path / "design.toml").write_text(UNRELATED)
    with running("--l1", "0.18", *given, cwd=tmp_path) as server:
        assert server.post("api/save?l2=0.41") == (200, {"wrote": "design.toml"})
    assert "l2 = 0.41" in (tmp_path / "design.toml").read_text()


def test_a_chunked_body_is_refused_at_once_and_the_server_keeps_serving(explorer, design_file):
    before = open(design_file, "rb").read()
    port = _port(explorer)
    raw = (
        f"POST /api/save?l2=0.41 HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
        "Transfer-Encoding: chunked\r\n\r\n"  # and never a chunk
    )
    with socket.create_connection(("127.0.0.1", port), timeout=ANSWER_WITHIN) as connection:
        connection.sendall(raw.encode("latin-1"))
        answer = b""
        while chunk := connection.recv(65536):
            answer += chunk
    head, _, body = answer.partition(b"\r\n\r\n")
    assert head.startswith(b"HTTP/1.1 400 ") and json.loads(body)["field"] == "Transfer-Encoding"
    assert open(design_file, "rb").read() == before
    assert explorer.get("api/loaded")[0] == 200
