"""What a request to the Hops server may reach, and from where it may come.

A Hops request names its template as text. The server reads only the
shipped templates (by name) and, when it was started with ``--templates
DIR``, the ``.toml`` files in that folder (by name, ``my-fold`` or
``my-fold.toml``): never a path the request makes up. Its refusal is the
same for a file that exists and one that does not, so a request learns
nothing about the machine's files.

Requests are answered only when they are meant for this server and come
from Grasshopper (or a script) on a machine that may use it: the ``Host``
header must name the server's own address (a web page that points a name
of its own at 127.0.0.1 by DNS rebinding sends that name), and a request
that a browser made for a page of another site (an ``Origin`` header
other than the server's, ``Sec-Fetch-Site: cross-site``) is refused.
Grasshopper's Hops sends neither header. Standard library only.
"""

from __future__ import annotations

import ipaddress
from collections.abc import Iterable, Mapping
from email.message import Message
from pathlib import Path

from onefold_cad.errors import InvalidParameterError
from onefold_cad.templates import SITE_PREFIX, shipped_files

__all__ = [
    "LOOPBACK_NAMES",
    "allowed_hosts",
    "folder_templates",
    "request_problem",
    "resolve_template",
]

#: The names of this machine a local client may use for a loopback server.
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def allowed_hosts(host: str, port: int, extra: Iterable[str] = ()) -> frozenset[str]:
    """The ``Host`` header values a server listening on ``host:port`` answers
    (lower case, with the port): its own address, this machine's loopback
    names when it listens on a loopback address, and the names in ``extra``
    (``--allow-host``: the machine's name or address on a network)."""
    names = {host.lower()}
    if ":" in host and not host.startswith("["):  # an IPv6 address in a Host header
        names = {f"[{host.lower()}]"}
    if _is_loopback(host):
        names.update(LOOPBACK_NAMES)
    names.update(n.strip().lower() for n in extra if n.strip())
    return frozenset(f"{n}:{port}" for n in names)


def request_problem(headers: Mapping[str, str] | Message, hosts: frozenset[str]) -> str | None:
    """Why a request with these headers is refused (one line), or None.

    ``hosts``: :func:`allowed_hosts`; an allowed ``Origin`` is ``http://``
    one of them.
    """
    host = (headers.get("Host") or "").strip().lower()
    if host not in hosts:
        return (
            "forbidden: unknown Host (the server answers only its own address; "
            "onefold hops --allow-host NAME adds one)"
        )
    site = (headers.get("Sec-Fetch-Site") or "").strip().lower()
    origin = headers.get("Origin")
    if site in ("cross-site", "same-site") or (
        origin is not None and origin.strip().lower() not in {f"http://{h}" for h in hosts}
    ):
        return "forbidden: a request from another site"
    return None


def folder_templates(folder: Path | None) -> dict[str, Path]:
    """The design templates of the server's folder, by name (file stem):
    its ``*.toml`` files but site files, not those in subfolders."""
    if folder is None:
        return {}
    return {
        p.stem: p
        for p in sorted(folder.glob("*.toml"))
        if p.is_file() and not p.stem.startswith(SITE_PREFIX)
    }


def resolve_template(ref: object, folder: Path | None) -> str:
    """The file of the template a request names: a template of the server's
    ``folder`` (by name; it comes first) or a shipped one.

    Raises:
        InvalidParameterError: on ``template`` for anything else (a path, a
            name neither knows); the message lists the names it takes and
            is the same whether or not a file of that name exists anywhere.
    """
    text = str(ref).strip()
    key = text.removesuffix(".toml")
    own = folder_templates(folder)
    if key in own:
        return str(own[key])
    shipped = shipped_files()
    if key in shipped:
        return str(shipped[key])
    names = ", ".join(sorted({*own, *shipped})) or "none"
    where = (
        f"the shipped ones or those in {str(folder)!r}"
        if folder is not None
        else "the shipped ones (onefold hops --templates DIR adds the .toml files of DIR)"
    )
    shown = text if len(text) <= 80 else text[:77] + "..."
    raise InvalidParameterError(
        "template",
        f"no template named {shown!r}: the server reads templates by name only, {where} "
        f"(templates: {names})",
    )
