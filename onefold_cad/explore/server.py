"""The explorer's local HTTP server (standard library only).

It listens on 127.0.0.1 and answers GET requests only:

- ``/``, ``/static/...``: the page and its scripts, held in memory (a fixed
  table: no path from a request ever reaches the file system);
- ``/api/templates``: the templates the page can switch between;
- ``/api/state?alpha=..&beta=..``: the design of those values solved,
  folded, placed, meshed and measured (:func:`onefold_cad.explore.state.design_state`;
  ``&mesh=KEY``: the page has the triangles of that ``mesh_key``, not sent again
  when they are the same);
- ``/api/simulate?...`` (the same query): the design as steel on the coarse
  mesh, standing under its weight
  (:func:`onefold_cad.explore.simulation.simulation_state`; seconds: each
  request has its own thread, so the page's other requests go on meanwhile);
- ``/api/steel?...`` (the same query): the same, for the page's Steel view:
  only the latest of these is simulated, its form first, its "stands" on
  ``/api/steel/check?...`` (:mod:`onefold_cad.explore.steel`);
- ``/api/compensate/{start,progress,cancel}?...``: the Compensate action's
  background job (:mod:`onefold_cad.explore.compensation`);
- ``/download/{dxf,step,3dm,json,toml,cones}?...``: the design's file.

The last :data:`RECENT_DESIGNS` designs asked for are kept by their query
(``functools.lru_cache``): a design's fold, resting placement and flat pattern
are computed once per design object (:func:`onefold_cad.design.derived`), so
the steel view's request for the design a state request just built, or a
slider moved back, reuses them.

Requests whose ``Host`` is not this server's own address (DNS rebinding),
that come from another site (``Sec-Fetch-Site`` / ``Origin``), that carry a
body, or whose target or values are too long are refused. A request the
machine has not the memory for (``MemoryError``) is answered 503 with one
line saying so, and the server goes on.

It serves at most :data:`MAX_CONNECTIONS` connections at once, each on its
own thread (one more is answered ``503`` at once and closed, never queued
on a thread), and drops a connection silent for :data:`TIMEOUT` seconds: a
few hundred half-sent requests cannot hold a thread each
(:class:`~onefold_cad.explore.bounded.BoundedServer`, which the Hops server
derives from too).
"""

from __future__ import annotations

import functools
import json
import sys
import threading
import traceback
import webbrowser
from collections.abc import Callable
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from onefold_cad.errors import InvalidParameterError, OneFoldError, memory_message
from onefold_cad.explore.bounded import MAX_CONNECTIONS, BoundedServer
from onefold_cad.explore.compensation import Compensations
from onefold_cad.explore.controls import (
    ParameterProblem,
    QueryError,
    design_from_params,
    parse_query,
)
from onefold_cad.explore.downloads import KINDS, make_download
from onefold_cad.explore.page import STATIC, TEXT, csp, static_files
from onefold_cad.explore.simulation import SIMULATE_LAW, simulation_state
from onefold_cad.explore.state import design_state, problem_state
from onefold_cad.explore.steel import LastSteel, LatestOnly

__all__ = [
    "DEFAULT_PORT",
    "MAX_CONNECTIONS",
    "MAX_TARGET",
    "RECENT_DESIGNS",
    "TIMEOUT",
    "ExploreServer",
    "load_templates",
    "make_server",
    "serve",
]

#: The port ``onefold explore`` listens on unless ``--port`` says otherwise.
DEFAULT_PORT = 8765
#: Longest accepted request target (path and query, characters).
MAX_TARGET = 8192
#: Seconds a connection may stay silent (a slow or half-sent request).
TIMEOUT = 30.0
#: Designs kept by their query, each with what derives from it (about 50 kB each
#: for the default template with its state, measured with tracemalloc).
RECENT_DESIGNS = 8


def _out_of_memory(exc: MemoryError) -> str:
    """The one line of a request the machine cannot afford (also in the
    server's log, without a traceback); the server answers 503 and goes on."""
    text = memory_message(exc)
    print(f"onefold explore: {text}", file=sys.stderr)
    return text


def load_templates(ref: str | None) -> tuple[dict[str, dict[str, Any]], str]:
    """The template data the page can use, and the key of the one it starts with.

    ``ref`` (a file or a shipped template's name; None: the default one) is
    validated as ``onefold solve`` would (same messages); the shipped
    templates follow it. The page names a template by its key only.
    """
    from onefold_cad.flags.jobs import load_jobs
    from onefold_cad.templates import (
        DEFAULT_TEMPLATE,
        find_template,
        list_templates,
        read_template,
    )

    path = find_template(ref or DEFAULT_TEMPLATE)
    load_jobs([str(path)], {})
    templates: dict[str, dict[str, Any]] = {path.stem: read_template(path)}
    for info in list_templates():
        if info.path.resolve() != Path(path).resolve():
            templates.setdefault(info.name, read_template(info.path))
    return templates, path.stem


class ExploreServer(BoundedServer):
    """A :class:`BoundedServer` on 127.0.0.1 serving one explorer page.

    Attributes:
        templates: template key -> template data.
        initial: the key of the template the page starts with.
        url: the page's address.
        verbose: log every request to stderr (default: errors only).
    """

    allow_reuse_address = True

    def __init__(
        self,
        templates: dict[str, dict[str, Any]],
        initial: str,
        port: int = DEFAULT_PORT,
        max_connections: int = MAX_CONNECTIONS,
    ) -> None:
        self.compensations = Compensations()  # before the bind: a failed one closes
        super().__init__(("127.0.0.1", port), ExploreHandler, max_connections)
        self.templates = templates
        self.initial = initial
        self.port = int(self.server_address[1])
        self.url = f"http://127.0.0.1:{self.port}/"
        self.hosts = {f"127.0.0.1:{self.port}", f"localhost:{self.port}"}
        self.origins = {f"http://{h}" for h in self.hosts}
        self.static = static_files()
        self.csp = csp(self.static["/"])
        self.verbose = False
        self.steel = LatestOnly()
        self.last_steel = LastSteel(self.steel)
        self.design_of = functools.lru_cache(maxsize=RECENT_DESIGNS)(self._design_of)

    def server_close(self) -> None:
        """Stop listening; a running compensation stops at its next simulation."""
        self.compensations.close()
        super().server_close()

    def _design_of(self, params: tuple[tuple[str, str], ...]) -> Any:
        """The design of the page's controls (sorted ``(name, text)`` pairs)."""
        return design_from_params(dict(params), self.templates, self.initial)


class ExploreHandler(BaseHTTPRequestHandler):
    """Answers the page's GET requests; refuses everything else."""

    server: ExploreServer
    server_version = "onefold-explore"
    sys_version = ""
    protocol_version = "HTTP/1.1"
    timeout = TIMEOUT

    # -- responses ----------------------------------------------------------
    def _send(
        self,
        status: int,
        body: bytes,
        mime: str,
        headers: dict[str, str] | None = None,
    ) -> None:
        self.send_response(status)
        self.send_header("Content-Type", mime)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("X-Content-Type-Options", "nosniff")
        self.send_header("Referrer-Policy", "no-referrer")
        for k, v in (headers or {}).items():
            self.send_header(k, v)
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(body)

    def _refuse(self, status: int, reason: str) -> None:
        self.close_connection = True
        self._send(status, (reason + "\n").encode("utf-8"), TEXT, {"Connection": "close"})

    def _json(self, status: int, data: dict[str, Any]) -> None:
        body = json.dumps(data, allow_nan=False, separators=(",", ":")).encode("utf-8")
        self._send(status, body, "application/json", {"Cache-Control": "no-store"})

    # -- checks -------------------------------------------------------------
    def _allowed(self) -> bool:
        """Refuse (and return False) unless the request is for us, from us, bodiless."""
        host = (self.headers.get("Host") or "").strip().lower()
        if host not in self.server.hosts:
            self._refuse(HTTPStatus.FORBIDDEN, "forbidden: unknown Host")
            return False
        site = (self.headers.get("Sec-Fetch-Site") or "").lower()
        origin = self.headers.get("Origin")
        if site in ("cross-site", "same-site") or (
            origin is not None and origin.lower() not in self.server.origins
        ):
            self._refuse(HTTPStatus.FORBIDDEN, "forbidden: request from another site")
            return False
        if self.headers.get("Transfer-Encoding") or (self.headers.get("Content-Length") or "0") != (
            "0"
        ):
            self._refuse(HTTPStatus.REQUEST_ENTITY_TOO_LARGE, "request bodies are not accepted")
            return False
        if len(self.path) > MAX_TARGET:
            self._refuse(HTTPStatus.REQUEST_URI_TOO_LONG, f"request target over {MAX_TARGET}")
            return False
        return True

    # -- methods ------------------------------------------------------------
    def do_GET(self) -> None:  # noqa: N802 (http.server's naming)
        """Serve the page, its files, states and downloads."""
        if not self._allowed():
            return
        target = urlsplit(self.path)
        path, query = target.path, target.query
        try:
            if path in STATIC:
                headers = {"Cache-Control": "no-cache"}
                if path == "/":
                    headers["Content-Security-Policy"] = self.server.csp
                self._send(HTTPStatus.OK, self.server.static[path], STATIC[path][1], headers)
            elif path == "/api/templates":
                self._templates()
            elif path == "/api/state":
                self._state(query)
            elif path == "/api/simulate":
                self._simulate(query, lambda _, d: simulation_state(d, law=SIMULATE_LAW))
            elif path == "/api/steel":
                self._simulate(query, self.server.last_steel.simulate)
            elif path == "/api/steel/check":
                self._simulate(query, self.server.last_steel.check)
            elif path.startswith("/api/compensate/"):
                action = path[len("/api/compensate/") :]
                self._json(*self.server.compensations.answer(action, query, self._design))
            elif path.startswith("/download/") and path[len("/download/") :] in KINDS:
                self._download(path[len("/download/") :], query)
            else:
                self._refuse(HTTPStatus.NOT_FOUND, "not found")
        except QueryError as exc:
            self._refuse(HTTPStatus.BAD_REQUEST, f"bad request: {exc}")
        except (BrokenPipeError, ConnectionResetError):
            self.close_connection = True

    def do_HEAD(self) -> None:  # noqa: N802
        """Refused: the page only needs GET."""
        self._refuse(HTTPStatus.METHOD_NOT_ALLOWED, "method not allowed")

    do_POST = do_PUT = do_DELETE = do_PATCH = do_OPTIONS = do_HEAD  # noqa: N815

    def _templates(self) -> None:
        items = [
            {
                "key": key,
                "description": str(data.get("description", "")).strip(),
            }
            for key, data in self.server.templates.items()
        ]
        self._json(HTTPStatus.OK, {"initial": self.server.initial, "templates": items})

    def _key(self, query: str) -> tuple[tuple[str, str], ...]:
        params = parse_query(query)
        params.pop("mesh", None)  # the page's triangles: not a design value
        return tuple(sorted(params.items()))

    def _design(self, query: str) -> Any:
        return self.server.design_of(self._key(query))

    def _state(self, query: str) -> None:
        try:
            known = parse_query(query).get("mesh")
            state = design_state(self._design(query), known_mesh=known)
        except ParameterProblem as exc:
            state = problem_state(exc)
        except QueryError:
            raise
        except MemoryError as exc:  # a request the machine cannot afford: answered, no crash
            text = _out_of_memory(exc)
            state = {"ok": False, "messages": [{"level": "error", "text": text, "controls": []}]}
            self._json(HTTPStatus.SERVICE_UNAVAILABLE, state)
            return
        except Exception as exc:  # a bad value must never break the page
            traceback.print_exc(file=sys.stderr)
            state = {
                "ok": False,
                "messages": [
                    {
                        "level": "error",
                        "text": f"internal error ({type(exc).__name__}: {exc})",
                        "controls": [],
                    }
                ],
            }
            self._json(HTTPStatus.INTERNAL_SERVER_ERROR, state)
            return
        self._json(HTTPStatus.OK, state)

    def _simulate(self, query: str, answer: Callable[[Any, Any], dict[str, Any]]) -> None:
        try:
            state = answer(self._key(query), self._design(query))
        except ParameterProblem as exc:
            state = {"ok": False, "error": " ".join(exc.message.split())}
        except QueryError:
            raise
        except MemoryError as exc:
            text = _out_of_memory(exc)
            self._json(HTTPStatus.SERVICE_UNAVAILABLE, {"ok": False, "error": text})
            return
        except Exception as exc:  # the page shows this line instead of a result
            traceback.print_exc(file=sys.stderr)
            text = f"internal error ({type(exc).__name__}: {' '.join(str(exc).split())})"
            self._json(HTTPStatus.INTERNAL_SERVER_ERROR, {"ok": False, "error": text})
            return
        self._json(HTTPStatus.OK, state)

    def _download(self, kind: str, query: str) -> None:
        try:
            file = make_download(kind, self._design(query))
        except (ParameterProblem, OneFoldError) as exc:
            text = " ".join(str(exc).split())
            self._send(HTTPStatus.UNPROCESSABLE_ENTITY, text.encode("utf-8"), TEXT)
            return
        except QueryError:
            raise
        except MemoryError as exc:
            text = _out_of_memory(exc)
            self._send(HTTPStatus.SERVICE_UNAVAILABLE, text.encode("utf-8"), TEXT)
            return
        except Exception as exc:  # the page shows this line instead of a broken download
            traceback.print_exc(file=sys.stderr)
            text = f"internal error ({type(exc).__name__}: {' '.join(str(exc).split())})"
            self._send(HTTPStatus.INTERNAL_SERVER_ERROR, text.encode("utf-8"), TEXT)
            return
        disposition = f'attachment; filename="{file.filename}"'
        self._send(
            HTTPStatus.OK,
            file.body,
            file.mime,
            {"Content-Disposition": disposition, "Cache-Control": "no-store"},
        )

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002
        """Requests are logged only when the server is verbose."""
        if self.server.verbose:
            super().log_message(format, *args)

    def log_error(self, format: str, *args: Any) -> None:  # noqa: A002
        """Protocol errors go to stderr."""
        sys.stderr.write(f"onefold explore: {format % args}\n")


def make_server(template: str | None = None, port: int = DEFAULT_PORT) -> ExploreServer:
    """An :class:`ExploreServer` for ``template`` on 127.0.0.1:``port`` (0: any free
    port), not yet serving; the first state is computed once (imports warmed).

    Raises:
        InvalidParameterError: a bad template (the CLI's message) or a port
            out of range or in use ('--port').
    """
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise InvalidParameterError("--port", f"must be an integer in [0, 65535], got {port!r}")
    templates, initial = load_templates(template)
    try:
        server = ExploreServer(templates, initial, port)
    except OSError as exc:
        raise InvalidParameterError(
            "--port",
            f"cannot listen on 127.0.0.1:{port} ({exc.strerror}); choose another with "
            "--port N (0: any free port)",
        ) from None
    try:
        design_state(design_from_params({}, templates, initial))
    except ParameterProblem:
        pass
    return server


def serve(
    template: str | None = None, *, port: int = DEFAULT_PORT, open_browser: bool = True
) -> None:
    """Run the explorer for ``template`` until Ctrl+C, opening the page in the
    default browser unless ``open_browser`` is False."""
    server = make_server(template, port)
    print(
        f"onefold explore: {server.initial} at {server.url}  (Ctrl+C stops)",
        file=sys.stderr,
        flush=True,
    )
    if open_browser:
        threading.Thread(target=webbrowser.open, args=(server.url,), daemon=True).start()
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("onefold explore: stopped", file=sys.stderr)
    finally:
        server.server_close()
