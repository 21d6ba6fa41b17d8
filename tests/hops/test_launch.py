"""``onefold hops``: its options refused in one line, what to install without
ghhops-server, and the server started as the command starts it."""

from __future__ import annotations

import importlib.util
import re
import signal
import socket
import subprocess
import sys

import pytest

from tests.hops.client import get
from tests.processes import interruptible


@pytest.mark.parametrize("port", ["70000", "-1", "abc", "5000.5"])
def test_a_bad_port_is_one_line_naming_the_flag_and_its_range(cli, port):
    rc, out, err = cli("hops", "--port", port)
    assert rc == 2 and out == ""
    assert err == (
        f"onefold: error: --port: must be a whole number in [0, 65535] (0: any free port), "
        f"got {port!r}\n"
    )


def test_a_port_in_use_is_one_line(cli):
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        rc, out, err = cli("hops", "--port", str(port))
    assert rc == 2 and out == ""
    assert err.startswith(f"onefold: error: --host/--port: cannot listen on 127.0.0.1:{port} (")
    assert err.count("\n") == 1


def test_without_ghhops_server_it_says_what_to_install(cli, monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util,
        "find_spec",
        lambda name, *a: None if name == "ghhops_server" else real(name, *a),
    )
    rc, out, err = cli("hops")
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and "ghhops_server" in err
    assert "pip install 'onefold_cad[rhino]'" in err


def test_the_command_serves_until_ctrl_c():
    proc = subprocess.Popen(
        [sys.executable, "-m", "onefold_cad", "hops", "--port", "0"],
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=interruptible,
    )
    try:
        assert proc.stderr is not None
        line = proc.stderr.readline()
        m = re.match(r"onefold hops: serving (http://127\.0\.0\.1:\d+)/onefold/solve, ", line)
        assert m, line
        status, listing = get(f"{m.group(1)}/")
        assert status == 200 and {c["Uri"] for c in listing} == {"/onefold/solve", "/onefold/fit"}
        proc.send_signal(signal.SIGINT)
        _, rest = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 0
    assert rest.rstrip().endswith("onefold hops: stopped") and "Traceback" not in rest


def test_a_templates_folder_that_is_not_one_is_one_line(cli, tmp_path):
    rc, out, err = cli("hops", "--port", "0", "--templates", str(tmp_path / "none"))
    assert rc == 2 and out == ""
    assert err == f"onefold: error: --templates: not a folder: {str(tmp_path / 'none')!r}\n"
