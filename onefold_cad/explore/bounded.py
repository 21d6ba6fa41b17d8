"""A threading HTTP server that serves a bounded number of connections at
once: the next is answered ``503`` at once and closed, never queued on a
thread (standard library only). The explorer's server and the Hops server
(:mod:`onefold_cad.hops.http`, the layer above) both derive from it.
"""

from __future__ import annotations

import socket
import sys
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

__all__ = ["MAX_CONNECTIONS", "BoundedServer", "answer_busy"]

#: Connections served at once unless told otherwise (a browser opens six to a
#: server; a simulation keeps one for seconds).
MAX_CONNECTIONS = 16


def answer_busy(sock: socket.socket) -> None:
    """Answer 503 on a connection no thread serves (one line, then close)."""
    body = b"the server is busy: too many connections at once, try again\n"
    head = (
        "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain; charset=utf-8\r\n"
        f"Content-Length: {len(body)}\r\nConnection: close\r\nRetry-After: 1\r\n\r\n"
    ).encode("ascii")
    try:
        sock.settimeout(1.0)
        sock.sendall(head + body)
    except OSError:
        pass


class BoundedServer(ThreadingHTTPServer):
    """Serves at most ``max_connections`` connections at once, each on a
    daemon thread of its own; one more is answered 503 and closed."""

    daemon_threads = True
    block_on_close = False

    def __init__(
        self,
        address: tuple[str, int],
        handler: type[BaseHTTPRequestHandler],
        max_connections: int = MAX_CONNECTIONS,
    ) -> None:
        super().__init__(address, handler)
        self.slots = threading.BoundedSemaphore(max_connections)

    def process_request(self, request: Any, client_address: Any) -> None:
        """Serve the connection on a thread of its own if a slot is free,
        else answer 503 at once and close it."""
        if not self.slots.acquire(blocking=False):
            answer_busy(request)
            self.shutdown_request(request)
            return
        try:
            super().process_request(request, client_address)
        except Exception:
            # The thread could not be started, so its slot is free again.
            # Not on KeyboardInterrupt: Ctrl+C can land while the started
            # thread runs (it frees its own slot), and must reach the
            # serving loop as itself, not as a second release's ValueError.
            self.slots.release()
            raise

    def handle_error(self, request: Any, client_address: Any) -> None:
        """A client that hangs up mid-answer is not an error of ours: stay
        quiet; anything else is printed as the standard library does."""
        if isinstance(sys.exc_info()[1], (ConnectionError, TimeoutError)):
            return
        super().handle_error(request, client_address)

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        try:
            super().process_request_thread(request, client_address)
        finally:
            self.slots.release()
