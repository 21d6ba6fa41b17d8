"""The Hops server's HTTP: ghhops-server's routes behind a guarded door.

:class:`HopsServer` is a :class:`~http.server.ThreadingHTTPServer` that
serves at most :data:`MAX_CONNECTIONS` connections at once (one more is
answered ``503`` at once and closed) and gives each a :data:`TIMEOUT` of
silence. :class:`HopsHandler` answers every request with a status and one
line, whatever it is sent:

- a ``Host`` or ``Origin`` that is not the server's own: ``403``
  (:func:`~onefold_cad.hops.guard.request_problem`);
- a POST without ``Content-Length`` (or chunked): ``411``; a length that is
  not a whole number: ``400``; a body over :data:`MAX_BODY`: ``413``, never
  read;
- a body that is not Hops' JSON (not UTF-8, not JSON, nested too deep, not
  an object, a ``pointer`` that is not a component's name): ``400`` with
  Hops' error answer (:func:`error_answer`);
- GET and POST as ghhops-server routes them (``GET /``, ``GET
  /onefold/solve``, ``POST /solve`` with ``pointer``, ``POST
  /onefold/solve``); other methods ``405``.

Standard library only; the app (:class:`~onefold_cad.hops.server.OneFoldHops`)
is the handler class's ``hops``.
"""

from __future__ import annotations

import json
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler
from typing import Any

from onefold_cad.explore.bounded import MAX_CONNECTIONS, BoundedServer
from onefold_cad.hops.ghhops import hlogger
from onefold_cad.hops.guard import request_problem

__all__ = [
    "MAX_BODY",
    "MAX_CONNECTIONS",
    "MAX_DEPTH",
    "TIMEOUT",
    "HopsHandler",
    "HopsServer",
    "RequestError",
    "error_answer",
    "parse_request",
]

#: Largest request body read (bytes): a Hops request of a sheet with ten
#: thousand vertices is under 1 MiB.
MAX_BODY = 4 * 1024 * 1024
#: Seconds a connection may stay silent (a slow or half-sent request).
TIMEOUT = 10.0
#: Deepest nesting of brackets read from a body (Hops' own is 5 deep).
MAX_DEPTH = 64


def error_answer(message: str) -> str:
    """The JSON of a Hops answer that is one error (one line)."""
    return json.dumps({"values": [], "errors": [" ".join(message.split())], "warnings": []})


class RequestError(ValueError):
    """A request body that is not Hops' JSON (its message: one line)."""


def _depth(text: str) -> int:
    """The deepest nesting of JSON brackets in ``text`` (brackets inside
    strings count too: an upper bound, enough to refuse before parsing)."""
    depth = deepest = 0
    for ch in text:
        if ch in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif ch in "]}":
            depth -= 1
    return deepest


def parse_request(body: bytes) -> dict[str, Any]:
    """A Hops request's JSON object read from ``body``.

    Raises:
        RequestError: not UTF-8, not JSON, nested over :data:`MAX_DEPTH`,
            not an object.
    """
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError:
        raise RequestError("the request is not UTF-8 text") from None
    if _depth(text) > MAX_DEPTH:
        raise RequestError(f"the request's JSON is nested over {MAX_DEPTH} deep")
    try:
        data = json.loads(text)
    except (ValueError, RecursionError) as exc:
        raise RequestError(f"the request is not JSON ({' '.join(str(exc).split())})") from None
    if not isinstance(data, dict):
        raise RequestError(f"the request is not a JSON object, got {type(data).__name__}")
    return data


class HopsServer(BoundedServer):
    """A :class:`~onefold_cad.explore.bounded.BoundedServer` (at most
    :data:`MAX_CONNECTIONS` connections at once, the next answered ``503`` and
    closed) that answers the ``Host`` values in ``hosts`` (set by
    ``make_server``; none until then)."""

    hosts: frozenset[str] = frozenset()


class HopsHandler(BaseHTTPRequestHandler):
    """Answers Hops' GET and POST requests (see the module's docstring); the
    app is the class attribute ``hops`` (set by ``make_server``)."""

    hops: Any = None
    server: HopsServer
    protocol_version = "HTTP/1.1"
    server_version = "onefold-hops"
    sys_version = ""
    timeout = TIMEOUT

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 (http.server's name)
        """Request lines go to ghhops' logger (INFO), as ghhops-server logs them."""
        hlogger.info("%s - - %s", self.address_string(), format % args)

    def _answer(self, status: int, text: str, mime: str = "application/json") -> None:
        body = text.encode("utf-8")
        self.send_response(status)
        self.send_header("Content-Type", mime)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("X-Content-Type-Options", "nosniff")
        if status >= 400 and status != 500:
            self.send_header("Connection", "close")
            self.close_connection = True
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(body)

    def _refuse(self, status: int, message: str) -> None:
        self._answer(status, error_answer(message))

    def _allowed(self) -> bool:
        problem = request_problem(self.headers, self.server.hosts)
        if problem is not None:
            self._refuse(HTTPStatus.FORBIDDEN, problem)
            return False
        return True

    def _body(self) -> bytes | None:
        """The request's body, or None (answered) when it cannot be read."""
        if self.headers.get("Transfer-Encoding"):
            self._refuse(
                HTTPStatus.LENGTH_REQUIRED, "a chunked request is not read: send Content-Length"
            )
            return None
        length = self.headers.get("Content-Length")
        if length is None:
            self._refuse(HTTPStatus.LENGTH_REQUIRED, "the request has no Content-Length")
            return None
        text = length.strip()
        if not text.isdigit() or not text.isascii():
            self._refuse(
                HTTPStatus.BAD_REQUEST,
                f"Content-Length must be a whole number of bytes, got {length[:40]!r}",
            )
            return None
        if int(text) > MAX_BODY:
            self._refuse(
                HTTPStatus.REQUEST_ENTITY_TOO_LARGE,
                f"the request is over {MAX_BODY} bytes ({text[:40]})",
            )
            return None
        try:
            body = self.rfile.read(int(text))
        except TimeoutError:
            self.close_connection = True
            return None
        if len(body) < int(text):  # the client stopped sending
            self.close_connection = True
            return None
        return body

    def do_GET(self) -> None:  # noqa: N802 (http.server's naming)
        """A component's metadata (``/onefold/solve``) or the list of them (``/``)."""
        if not self._allowed():
            return
        found, text = self.hops.query(uri=self.path.split("?")[0])
        if found:
            self._answer(HTTPStatus.OK, text)
        else:
            self._refuse(HTTPStatus.NOT_FOUND, "no such Hops component")

    def do_POST(self) -> None:  # noqa: N802
        """Solve a component: the app's answer (200, or 500 for a value it refuses)."""
        if not self._allowed():
            return
        body = self._body()
        if body is None:
            return
        try:
            request = parse_request(body)
            ok, text = self.hops.solve_request(self.path.split("?")[0], request)
        except RequestError as exc:
            self._refuse(HTTPStatus.BAD_REQUEST, f"the request is not Hops' JSON: {exc}")
            return
        except LookupError as exc:
            self._refuse(HTTPStatus.NOT_FOUND, str(exc.args[0]) if exc.args else "not found")
            return
        self._answer(HTTPStatus.OK if ok else HTTPStatus.INTERNAL_SERVER_ERROR, text)

    def do_HEAD(self) -> None:  # noqa: N802
        """Refused: Hops sends GET and POST only."""
        self._refuse(HTTPStatus.METHOD_NOT_ALLOWED, "method not allowed: Hops sends GET and POST")

    do_PUT = do_DELETE = do_PATCH = do_OPTIONS = do_HEAD  # noqa: N815
