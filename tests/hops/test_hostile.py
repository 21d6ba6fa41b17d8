"""The Hops server under hostile requests (loopback only, bounded in count
and time): it reads no file a request names, answers no foreign Host or
Origin, answers every malformed request with a 4xx and one line, bounds
bodies and connections, and stays up."""

from __future__ import annotations

import json
import shutil
import socket
import threading
import time
from collections.abc import Iterator

import pytest

from onefold_cad.hops import http as hops_http
from onefold_cad.hops.inputs import SOLVE_INPUTS, hops_request
from onefold_cad.hops.server import make_server
from onefold_cad.templates import find_template
from tests.hops.client import post
from tests.served import Served

SECRET = "the-secret-words-4711"


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory):
    d = tmp_path_factory.mktemp("mine")
    shutil.copy(find_template("paper-square"), d / "my-fold.toml")
    return d


@pytest.fixture(scope="module")
def server(folder) -> Iterator[tuple[str, int]]:
    """A server with a folder of templates, on a free port: (host, port)."""
    srv = make_server("127.0.0.1", 0, template_dir=folder)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    try:
        yield "127.0.0.1", int(srv.server_address[1])
    finally:
        srv.shutdown()
        srv.server_close()
        thread.join(5)


def raw(address: tuple[str, int], data: bytes, timeout: float = 30.0) -> tuple[int, bytes]:
    """Send ``data`` as it is on a new connection; (status, body) of the answer."""
    with socket.create_connection(address, timeout=timeout) as s:
        s.sendall(data)
        s.shutdown(socket.SHUT_WR)
        chunks = []
        while chunk := s.recv(65536):
            chunks.append(chunk)
    reply = b"".join(chunks)
    head, _, body = reply.partition(b"\r\n\r\n")
    return int(head.split(b" ", 2)[1]), body


def request(address, method="POST", path="/solve", body=b"", headers=None) -> bytes:
    host, port = address
    lines = [f"{method} {path} HTTP/1.1", f"Host: {host}:{port}"]
    if headers is None:
        headers = {"Content-Length": str(len(body))}
    lines += [f"{k}: {v}" for k, v in headers.items()]
    return ("\r\n".join(lines) + "\r\n\r\n").encode() + body


def one_line_error(body: bytes) -> str:
    answer = json.loads(body)
    assert answer["values"] == []
    (error,) = answer["errors"]
    assert "\n" not in error and "Traceback" not in error
    return error


def alive(address) -> None:
    host, port = address
    body = hops_request("onefold/solve", SOLVE_INPUTS, {"template": "my-fold", "alpha": 40.0})
    status, answer = post(f"http://{host}:{port}/solve", body)
    assert status == 200, answer


# -- templates: names only ------------------------------------------------------------
def test_a_template_path_is_not_read_and_does_not_tell_whether_it_exists(server, tmp_path):
    secret = tmp_path / "secret.toml"
    secret.write_text(f'[frame]\nalpha = "{SECRET}"\n')
    host, port = server
    errors = {}
    for ref in (str(secret), "/etc/shadow", "/etc/passwd", str(tmp_path / "none.toml"),
                "../" * 12 + str(secret)):  # fmt: skip
        body = hops_request("onefold/solve", SOLVE_INPUTS, {"template": ref})
        status, answer = post(f"http://{host}:{port}/solve", body)
        assert status == 500
        error = one_line_error(json.dumps(answer).encode())
        assert SECRET not in error and "TOML" not in error and "no such file" not in error
        assert error.startswith("template: no template named ")
        shown = ref if len(ref) <= 80 else ref[:77] + "..."
        errors[ref] = error.replace(repr(shown), "X")
    assert len(set(errors.values())) == 1  # the same words for every path


def test_fit_takes_template_names_only_too(server, tmp_path):
    from onefold_cad.hops.inputs import FIT_INPUTS

    secret = tmp_path / "secret.toml"
    secret.write_text(f'[frame]\nalpha = "{SECRET}"\n')
    host, port = server
    body = hops_request("onefold/fit", FIT_INPUTS,
                        {"template": str(secret), "height": 100.0, "span": 100.0})  # fmt: skip
    status, answer = post(f"http://{host}:{port}/solve", body)
    assert status == 500
    assert SECRET not in json.dumps(answer)
    assert one_line_error(json.dumps(answer).encode()).startswith("template: no template named")


def test_the_server_s_folder_and_the_shipped_templates_solve_by_name(server):
    alive(server)
    host, port = server
    body = hops_request("onefold/solve", SOLVE_INPUTS, {"template": "table1-row4"})
    assert post(f"http://{host}:{port}/solve", body)[0] == 200


# -- Host and Origin -----------------------------------------------------------------------
@pytest.mark.parametrize(
    "headers",
    [
        {"Host": "rebound.example:{port}"},
        {"Host": "127.0.0.1:{port}", "Origin": "https://evil.example"},
        {"Host": "127.0.0.1:{port}", "Sec-Fetch-Site": "cross-site"},
        {},
    ],
)
@pytest.mark.parametrize(("method", "path"), [("GET", "/"), ("GET", "/onefold/solve"),
                                              ("POST", "/solve")])  # fmt: skip
def test_a_foreign_host_or_origin_is_refused(server, headers, method, path):
    host, port = server
    body = json.dumps(hops_request("onefold/solve", SOLVE_INPUTS, {"alpha": 40.0})).encode()
    lines = [f"{method} {path} HTTP/1.1"]
    lines += [f"{k}: {v.format(port=port)}" for k, v in headers.items()]
    lines.append(f"Content-Length: {len(body) if method == 'POST' else 0}")
    data = ("\r\n".join(lines) + "\r\n\r\n").encode() + (body if method == "POST" else b"")
    status, answer = raw(server, data)
    assert status == 403
    assert one_line_error(answer).startswith("forbidden: ")
    assert b"OneFold" not in answer  # no component listed


def test_localhost_and_its_own_origin_are_answered(server):
    host, port = server
    data = request(server, "GET", "/", headers={"Origin": f"http://localhost:{port}"})
    data = data.replace(f"Host: {host}:{port}".encode(), f"Host: localhost:{port}".encode())
    status, answer = raw(server, data)
    assert status == 200 and "/onefold/solve" in answer.decode()


# -- malformed requests ---------------------------------------------------------------------
NESTED = b"[" * 200_000 + b"]" * 200_000


@pytest.mark.parametrize(
    ("headers", "body", "status", "words"),
    [
        ({}, b"{}", 411, "Content-Length"),
        ({"Content-Length": "abc"}, b"{}", 400, "Content-Length"),
        ({"Content-Length": "-5"}, b"{}", 400, "Content-Length"),
        ({"Content-Length": "3000000000"}, b"{}", 413, "over"),
        ({"Transfer-Encoding": "chunked"}, b"2\r\n{}\r\n0\r\n\r\n", 411, "chunked"),
        (None, b'{"pointer": 5}', 400, "pointer"),
        (None, b'{"pointer": null}', 400, "pointer"),
        (None, b"null", 400, "not a JSON object"),
        (None, b"[1, 2]", 400, "not a JSON object"),
        (None, b"\xff\xfe{}", 400, "UTF-8"),
        (None, NESTED, 400, "nested"),
        (None, b'{"pointer": "onefold/solve", "values": 5}', 500, "values"),
        (None, b'{"pointer": "onefold/solve", "values": [{"InnerTree": {"{0}": 7}}]}', 500,
         "values"),
        (None, b'{"pointer": "onefold/solve", "values": [{"InnerTree": {"{0}": [3]}}]}', 500,
         "values"),
        (None, b'{"pointer": "../../etc/passwd"}', 404, "no Hops component"),
    ],
)  # fmt: skip
def test_a_malformed_request_is_a_4xx_or_an_error_in_one_line(server, headers, body, status, words):
    got, answer = raw(server, request(server, body=body, headers=headers))
    assert got == status
    assert words in one_line_error(answer)
    alive(server)


def test_an_unknown_component_path_is_404(server):
    status, answer = raw(server, request(server, path="/onefold/nothing", body=b"{}"))
    assert status == 404 and "no Hops component" in one_line_error(answer)
    status, answer = raw(server, request(server, "GET", "/nothing"))
    assert status == 404


def test_a_body_over_the_cap_is_refused_before_it_is_sent(server):
    """The answer comes on the headers alone: the server does not wait for
    (nor read) the 20 MB it was told of."""
    length = 20 * 1024 * 1024
    assert length > hops_http.MAX_BODY
    with socket.create_connection(server, timeout=30) as s:
        s.sendall(request(server, headers={"Content-Length": str(length)}))
        s.sendall(b" " * 65536)  # a first part of the body
        head = s.recv(65536)
    assert head.startswith(b"HTTP/1.1 413 ")
    alive(server)


def test_other_methods_are_refused(server):
    for method in ("PUT", "DELETE", "OPTIONS", "HEAD"):
        status, _ = raw(server, request(server, method, "/", headers={}))
        assert status == 405


def test_half_sent_requests_are_bounded_and_time_out(monkeypatch, folder):
    """More slow clients than the server has slots: no more than its slots
    are served at once, the extra ones get a 503 at once, the slow ones are
    dropped after the timeout, and then it answers."""
    served = Served(monkeypatch, hops_http.HopsHandler, 4.0)
    srv = make_server("127.0.0.1", 0, template_dir=folder)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    address = ("127.0.0.1", int(srv.server_address[1]))
    slow = []
    try:
        for _ in range(hops_http.MAX_CONNECTIONS + 10):
            s = socket.create_connection(address, timeout=10)
            s.sendall(b"POST /solve HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Le")
            slow.append(s)
        busy = 0
        for s in slow[hops_http.MAX_CONNECTIONS :]:
            s.settimeout(10)
            if s.recv(200).startswith(b"HTTP/1.1 503"):
                busy += 1
        assert busy >= 1
        assert served.peak <= hops_http.MAX_CONNECTIONS
        deadline = time.monotonic() + 30
        while served.now > 0 and time.monotonic() < deadline:
            time.sleep(0.1)
        assert served.now == 0  # every slow one dropped
        alive(address)
    finally:
        for s in slow:
            s.close()
        srv.shutdown()
        srv.server_close()
        thread.join(5)
