"""The bounded server frees each connection's slot exactly once, and Ctrl+C
reaches the serving loop as itself even when it lands while a connection's
thread starts (it once came out as a second release's ValueError, which the
loop swallows, so the explorer never stopped)."""

from __future__ import annotations

import socket
import socketserver
import threading
from http.server import BaseHTTPRequestHandler

import pytest

from onefold_cad.explore.bounded import BoundedServer


class Quiet(BaseHTTPRequestHandler):
    def handle(self) -> None:  # nothing to read: the test calls the server directly
        pass


@pytest.fixture
def server():
    srv = BoundedServer(("127.0.0.1", 0), Quiet, max_connections=2)
    yield srv
    srv.server_close()


def free_slots(srv: BoundedServer) -> int:
    n = 0
    while srv.slots.acquire(blocking=False):
        n += 1
    for _ in range(n):
        srv.slots.release()
    return n


def test_ctrl_c_while_the_thread_starts_is_a_keyboard_interrupt(server, monkeypatch):
    """The connection's thread runs to its end (freeing its slot) and then
    Ctrl+C lands in the serving thread: KeyboardInterrupt, not ValueError."""

    def start_then_interrupt(self, request, client_address):
        thread = threading.Thread(
            target=self.process_request_thread, args=(request, client_address)
        )
        thread.start()
        thread.join()
        raise KeyboardInterrupt

    monkeypatch.setattr(socketserver.ThreadingMixIn, "process_request", start_then_interrupt)
    a, b = socket.socketpair()
    try:
        with pytest.raises(KeyboardInterrupt):
            server.process_request(a, ("127.0.0.1", 1))
    finally:
        b.close()
    assert free_slots(server) == 2


def test_a_thread_that_cannot_start_frees_its_slot(server, monkeypatch):
    def cannot_start(self, request, client_address):
        raise RuntimeError("can't start new thread")

    monkeypatch.setattr(socketserver.ThreadingMixIn, "process_request", cannot_start)
    a, b = socket.socketpair()
    try:
        with pytest.raises(RuntimeError):
            server.process_request(a, ("127.0.0.1", 1))
    finally:
        a.close()
        b.close()
    assert free_slots(server) == 2


def test_a_client_hanging_up_is_not_printed(server, capsys):
    try:
        raise ConnectionResetError(104, "Connection reset by peer")
    except ConnectionResetError:
        server.handle_error(None, ("127.0.0.1", 1))
    assert capsys.readouterr().err == ""
    try:
        raise ValueError("a bug of ours")
    except ValueError:
        server.handle_error(None, ("127.0.0.1", 1))
    assert "a bug of ours" in capsys.readouterr().err
