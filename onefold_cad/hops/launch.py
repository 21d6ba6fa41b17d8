"""``onefold hops``'s entry: check the optional packages, listen, serve until
Ctrl-C. ghhops-server is imported only once they are found, so a missing
package is one line saying what to install.
"""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Sequence
from pathlib import Path

from onefold_cad.errors import not_installed
from onefold_cad.flags.parser import UsageError

__all__ = ["INSTALL_HOPS", "REQUIRED", "check_installed", "serve"]

#: What to install for ``onefold hops``.
INSTALL_HOPS = "pip install 'onefold_cad[rhino]'"
#: The modules the server imports from the ``rhino`` extra (ghhops-server
#: 1.5.5 imports werkzeug without declaring it).
REQUIRED = ("ghhops_server", "werkzeug", "rhino3dm")


def check_installed() -> None:
    """Raise :class:`UsageError` (one line: what to install) when a module of
    :data:`REQUIRED` is not installed (found, not imported)."""
    missing = [m for m in REQUIRED if importlib.util.find_spec(m) is None]
    if missing:
        raise UsageError(not_installed("onefold hops", missing, "rhino"))


def serve(
    host: str = "127.0.0.1",
    port: int = 5000,
    template_dir: str | None = None,
    allow_hosts: Sequence[str] = (),
) -> None:
    """Serve the Hops components on ``host:port`` (0: any free port) until
    Ctrl-C; the address goes to stderr first. Requests may name the shipped
    templates and those of ``template_dir`` (``--templates``), and be sent
    to the server's own address or a name of ``allow_hosts``.

    Raises:
        UsageError: a missing package, a folder that is not one, or an
            address it cannot listen on.
    """
    check_installed()
    if template_dir is not None and not Path(template_dir).is_dir():
        raise UsageError(f"--templates: not a folder: {template_dir!r}")
    from onefold_cad.hops.server import COMPONENTS, make_server

    try:
        server = make_server(host, port, template_dir, allow_hosts)
    except OSError as exc:
        why = exc.strerror or str(exc)
        raise UsageError(f"--host/--port: cannot listen on {host}:{port} ({why})") from None
    url = f"http://{host}:{server.server_address[1]}"
    paths = ", ".join(url + c.uri for c in COMPONENTS)
    print(
        f"onefold hops: serving {paths}  (the Hops component's Path; Ctrl+C stops)",
        file=sys.stderr,
        flush=True,
    )
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("onefold hops: stopped", file=sys.stderr)
    finally:
        server.server_close()
