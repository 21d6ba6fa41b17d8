"""The local server: its routes, and what it refuses (foreign hosts, bodies, long targets)."""

from __future__ import annotations

import builtins
import io
import json
import os
import pathlib
import socket

import ezdxf
import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.explore.page import STATIC
from onefold_cad.explore.server import MAX_TARGET, make_server
from tests.explore.conftest import get
from tests.processes import interruptible
from tests.served import Served


def test_it_listens_on_loopback_only(server):
    assert server.server_address[0] == "127.0.0.1"


def test_the_page_and_its_scripts_are_served_with_a_content_security_policy(server):
    status, headers, body = get(server, "/")
    assert status == 200 and b'<canvas id="view">' in body
    assert "script-src 'self' 'sha256-" in headers["content-security-policy"]
    assert "frame-ancestors 'none'" in headers["content-security-policy"]
    for path in STATIC:
        status, headers, body = get(server, path)
        assert status == 200 and len(body) > 0, path
    _, _, licence = get(server, "/static/three/LICENSE")
    assert b"MIT License" in licence


def test_a_state_is_json_with_the_numbers(server):
    status, headers, body = get(server, "/api/state?alpha=33&beta=41")
    state = json.loads(body)
    assert status == 200 and headers["content-type"] == "application/json"
    assert state["ok"] and state["page"]["values"]["alpha"] == "33"
    assert set(state["numbers"]["fold_angles"]) == {"plus_x", "minus_x"}


def test_a_state_leaves_out_the_triangles_the_page_names(server):
    _, _, body = get(server, "/api/state?alpha=30")
    form = json.loads(body)["form"]
    _, _, body = get(server, f"/api/state?alpha=31&mesh={form['mesh_key']}")
    again = json.loads(body)["form"]
    assert form["indices"] and again["indices"] is None
    assert again["mesh_key"] == form["mesh_key"] and again["positions"] != form["positions"]


def test_a_bad_value_is_a_message_not_a_failure(server):
    status, _, body = get(server, "/api/state?alpha=95")
    state = json.loads(body)
    assert status == 200 and not state["ok"]
    assert state["messages"][0]["text"] == "--alpha: must be in (0, 90) deg, got 95"


def test_the_templates_are_listed_by_name(server):
    _, _, body = get(server, "/api/templates")
    info = json.loads(body)
    keys = [t["key"] for t in info["templates"]]
    assert info["initial"] == "patkau-one-fold" == keys[0]
    assert {"paper-square", "table1-row4", "star-polygon"} <= set(keys)


def test_the_dxf_download_is_a_dxf_with_a_cut_layer(server):
    status, headers, body = get(server, "/download/dxf?alpha=35")
    assert status == 200
    assert headers["content-disposition"] == 'attachment; filename="patkau-one-fold.dxf"'
    doc = ezdxf.read(io.StringIO(body.decode("utf-8")))
    assert len(doc.modelspace().query('*[layer=="CUT"]')) >= 1


def test_a_refused_download_says_why(server):
    status, _, body = get(server, "/download/dxf?alpha=95")
    assert status == 422 and body.decode() == "--alpha: must be in (0, 90) deg, got 95"


def test_an_unexpected_failure_is_a_message_too(server, monkeypatch, capsys):
    import onefold_cad.explore.server as srv

    def broken(*args, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(srv, "design_state", broken)
    monkeypatch.setattr(srv, "make_download", broken)
    status, _, body = get(server, "/api/state?alpha=33")
    state = json.loads(body)
    assert status == 500 and not state["ok"]
    assert state["messages"][0]["text"] == "internal error (RuntimeError: boom)"
    status, _, body = get(server, "/download/dxf?alpha=33")
    assert status == 500 and body == b"internal error (RuntimeError: boom)"
    assert "RuntimeError: boom" in capsys.readouterr().err  # the traceback, for the user


@pytest.mark.parametrize(
    "host",
    ["evil.example", "evil.example:{port}", "127.0.0.1", "127.0.0.2:{port}", "localhost:1"],
)
def test_a_foreign_host_is_refused(server, host):
    status, _, body = get(server, "/api/state", {"Host": host.format(port=server.port)})
    assert status == 403 and b"Host" in body


def test_localhost_is_our_host_too(server):
    assert get(server, "/api/templates", {"Host": f"localhost:{server.port}"})[0] == 200


def test_a_request_without_host_is_refused(server):
    with socket.create_connection(("127.0.0.1", server.port), timeout=30) as s:
        s.sendall(b"GET / HTTP/1.0\r\n\r\n")
        reply = s.makefile("rb").readline()
    assert reply.split()[1] == b"403"


@pytest.mark.parametrize(
    "headers",
    [{"Sec-Fetch-Site": "cross-site"}, {"Origin": "http://evil.example"}],
    ids=["cross-site", "foreign-origin"],
)
def test_a_request_from_another_site_is_refused(server, headers):
    assert get(server, "/download/step", headers)[0] == 403


def test_an_oversize_target_is_refused(server):
    target = "/api/state?alpha=" + "1" * MAX_TARGET
    assert get(server, target)[0] == 414


def test_an_oversize_value_is_refused(server):
    status, _, body = get(server, "/api/state?alpha=" + "3" * 100)
    assert status == 400 and b"too long" in body


def test_a_request_body_is_refused(server):
    assert get(server, "/api/state", {"Content-Length": "10"})[0] == 413
    assert get(server, "/api/state", {"Transfer-Encoding": "chunked"})[0] == 413


@pytest.mark.parametrize("method", ["POST", "PUT", "DELETE", "HEAD"])
def test_only_get_is_answered(server, method):
    assert get(server, "/api/state", method=method)[0] == 405


@pytest.mark.parametrize(
    "target",
    [
        "/static/../pyproject.toml",
        "/static/%2e%2e/%2e%2e/pyproject.toml",
        "/static/three/../../__init__.py",
        "//etc/passwd",
        "/etc/passwd",
        "/static/",
        "/download/../../etc/passwd",
        "/download/step.py",
    ],
)
def test_path_like_targets_never_reach_the_file_system(server, monkeypatch, target):
    def closed(*args, **kwargs):
        raise AssertionError(f"file system touched: {args!r}")

    for owner, name in [
        (builtins, "open"),
        (io, "open"),
        (os, "open"),
        (os, "stat"),
        (pathlib.Path, "open"),
        (pathlib.Path, "read_bytes"),
        (pathlib.Path, "exists"),
    ]:
        monkeypatch.setattr(owner, name, closed)
    status, _, body = get(server, target)
    monkeypatch.undo()
    assert status == 404 and body == b"not found\n"


def test_a_busy_port_is_an_error_naming_the_flag(server):
    with pytest.raises(InvalidParameterError, match=r"--port: cannot listen on 127\.0\.0\.1:"):
        make_server(None, port=server.port)


def test_the_commands_default_port_is_the_servers():
    from onefold_cad.cli.parser import build_parser
    from onefold_cad.explore.server import DEFAULT_PORT

    assert build_parser()["explore"].get_default("port") == DEFAULT_PORT


def test_a_bad_template_is_refused_with_the_clis_message():
    with pytest.raises(InvalidParameterError, match="template: no such file or shipped template"):
        make_server("no-such-template", port=0)


def test_the_command_serves_until_interrupted():
    """`onefold explore --no-browser --port 0` prints its address, serves the page, and
    Ctrl+C (SIGINT) stops it cleanly."""
    import signal
    import subprocess
    import sys
    import urllib.request

    proc = subprocess.Popen(
        [sys.executable, "-m", "onefold_cad", "explore", "paper-square", "--no-browser"]
        + ["--port", "0"],
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=interruptible,
    )
    try:
        line = proc.stderr.readline()
        assert line.startswith("onefold explore: paper-square at http://127.0.0.1:")
        url = line.split(" at ")[1].split()[0]
        with urllib.request.urlopen(url + "api/templates", timeout=60) as res:
            assert json.loads(res.read())["initial"] == "paper-square"
        proc.send_signal(signal.SIGINT)
        assert proc.wait(timeout=60) == 0
        assert "stopped" in proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def test_half_sent_requests_are_bounded_and_time_out(monkeypatch):
    """More slow clients than the server has slots: each
    slot is held by a half-sent request, the extra ones are answered 503 at
    once, the slow ones are dropped after the timeout (5 s here, the margin
    for opening them all on a busy machine), and then it answers. Loopback
    only, 26 connections, at most a minute."""
    import threading

    from onefold_cad.explore import server as explore_server

    served = Served(monkeypatch, explore_server.ExploreHandler, 5.0)

    def wait_for(count: int) -> None:
        assert served.wait_for(count)

    srv = make_server("paper-square", port=0)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    bound = explore_server.MAX_CONNECTIONS
    half = f"GET /api/templates HTTP/1.1\r\nHost: 127.0.0.1:{srv.port}\r\nAcc".encode()
    slow, answers = [], []
    try:
        for i in range(bound + 10):
            s = socket.create_connection(("127.0.0.1", srv.port), timeout=10)
            s.sendall(half)
            slow.append(s)
            if i < bound:
                wait_for(i + 1)  # served on a thread of its own, waiting for the rest
            else:
                answers.append(s.recv(400))
        assert served.peak == bound
        busy = b"\r\n\r\nthe server is busy: too many connections at once, try again\n"
        for a in answers:
            assert a.startswith(b"HTTP/1.1 503 Service Unavailable\r\n") and a.endswith(busy), a
        wait_for(0)  # every slow one dropped after the timeout
        for s in slow[:bound]:
            assert s.recv(400) == b""  # closed by the server, nothing answered
        status, _, body = get(srv, "/api/templates")
        assert status == 200 and json.loads(body)["initial"] == "paper-square"
    finally:
        for s in slow:
            s.close()
        srv.shutdown()
        srv.server_close()
        thread.join(10)
